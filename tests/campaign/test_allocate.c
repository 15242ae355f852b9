/* The allocation rule of the campaign-level stop (campaign/campaign_allocate.c) on synthetic rows:
 * the steps go to the run with the most information about the slope per particle-step
 * (G^2 / (s^2 T N)), each run at most doubles in a round, the extension covers the deficit so that
 * the predicted error of k (s_i^2 ~ 1 / T_i) is at most the target, the budget is kept, and nothing
 * is extended once the target is met. */
#include <math.h>
#include <stdio.h>

#include "campaign.h"

static int failures;

static void check(int ok, const char *what) {
  printf("%s %s\n", ok ? "ok  " : "FAIL", what);
  if (!ok) failures++;
}

/* The relative error of k predicted after the extension: W grows as sum G^2 / s^2 with
 * s^2 = s0^2 T / (T + ext). */
static double predicted(const camp_alloc_row *rows, int n, const long long *ext, double rel_err) {
  double W0 = 0, W1 = 0;
  for (int i = 0; i < n; i++) {
    const double w = rows[i].G * rows[i].G / (rows[i].s * rows[i].s);
    W0 += w;
    W1 += w * (rows[i].T + (double)ext[i]) / rows[i].T;
  }
  return rel_err * sqrt(W0 / W1);
}

int main(void) {
  camp_alloc_row rows[5];
  long long ext[5];
  for (int i = 0; i < 5; i++) /* equal noise and cost: the strongest gradient informs most */
    rows[i] = (camp_alloc_row){.G = 0.1 * (i + 1), .s = 1e-3, .T = 2000, .N = 1000, .steps = 2000};
  long long budget = 1000000;
  double left = camp_allocate(rows, 5, 0.04, 0.03, 10, &budget, ext);
  printf("  e 4%% -> 3%%: ext %lld %lld %lld %lld %lld, budget left %lld\n", ext[0], ext[1], ext[2],
         ext[3], ext[4], budget);
  check(left == 0 && ext[4] > 0 && ext[0] == 0 && ext[4] >= ext[3] && ext[3] >= ext[2] &&
            ext[2] >= ext[1],
        "equal noise: the strongest gradients first (doubled), the weakest not at all");
  check(ext[4] <= rows[4].steps && ext[3] <= rows[3].steps, "no run more than doubles in a round");
  check(predicted(rows, 5, ext, 0.04) <= 0.03, "the predicted error of k reaches the target");
  long long spent = 0;
  int whole = 1;
  for (int i = 0; i < 5; i++) {
    spent += ext[i];
    whole &= ext[i] % 10 == 0;
  }
  check(whole, "extensions are whole flux samples (multiples of the quantum)");
  check(budget == 1000000 - spent, "the budget lost exactly the steps given");

  /* noisier strong run: the gain per particle-step G^2 / (s^2 T N) decides, not G alone */
  rows[4].s = 1e-2; /* 100x the variance: 0.25 / 1e-4 < 0.16 / 1e-6 */
  budget = 1000000;
  camp_allocate(rows, 5, 0.04, 0.03, 10, &budget, ext);
  check(ext[3] > 0 && ext[3] >= ext[4], "a noisy strong run yields to the quieter next one");
  rows[4].s = 1e-3;

  /* a bigger run costs more per step */
  rows[4].N = 1e6;
  budget = 1000000;
  camp_allocate(rows, 5, 0.04, 0.03, 10, &budget, ext);
  check(ext[3] > 0 && ext[3] >= ext[4], "cost per particle-step: a 1000x larger run last");
  rows[4].N = 1000;

  budget = 500;
  left = camp_allocate(rows, 5, 0.1, 0.03, 10, &budget, ext);
  spent = ext[0] + ext[1] + ext[2] + ext[3] + ext[4];
  check(left > 0 && spent <= 500 && budget >= 0, "a short budget: spent within it, deficit left");

  budget = 1000000;
  left = camp_allocate(rows, 5, 0.02, 0.03, 10, &budget, ext);
  check(left == 0 && ext[0] + ext[1] + ext[2] + ext[3] + ext[4] == 0 && budget == 1000000,
        "target met: nothing extended");

  /* far from the target: doubling caps every run, the rest of the deficit left for later rounds */
  budget = 1000000;
  left = camp_allocate(rows, 5, 0.5, 0.03, 10, &budget, ext);
  int all_doubled = 1;
  for (int i = 0; i < 5; i++) all_doubled &= ext[i] == rows[i].steps;
  check(left > 0 && all_doubled, "far from the target: every run doubles, the deficit carries on");
  printf("%s\n", failures ? "FAILED" : "all passed");
  return failures ? 1 : 0;
}
