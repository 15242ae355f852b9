/* The allocation rule of the campaign-level stop (campaign.h, camp_allocate): which runs of an axis
 * to continue in the next round, and by how many steps, so that the error of k falls most per
 * particle-step.
 *
 * k = mu b, b the weighted least-squares slope of q = b G through the origin over the Darcy range's
 * rows, has var(b) = 1 / W, W = sum_i G_i^2 / s_i^2 (s_i the error of q_i). The error of a mean
 * over a steady window of T_i steps falls as s_i^2 = c_i / T_i (c_i: the variance times twice the
 * correlation time, in steps), so dW / dT_i = G_i^2 / (s_i^2 T_i), and per particle-step
 * G_i^2 / (s_i^2 T_i N_i). W is linear in each T_i, so the cheapest way to a given W is the run
 * with the highest gain per particle-step (with thermal noise that does not depend on G: the
 * strongest gradient of the range); each run at most doubles per round, so its c_i is measured
 * again before most of the steps go to it. */
#include <math.h>
#include <stdlib.h>

#include "campaign.h"

typedef struct {
  int row;
  double gain; /* dW / d(particle-step) */
} ranked;

static int by_gain(const void *a, const void *b) {
  const double x = ((const ranked *)a)->gain, y = ((const ranked *)b)->gain;
  return (x < y) - (x > y); /* decreasing */
}

double camp_allocate(const camp_alloc_row *rows, int n, double rel_err, double target,
                     long long quantum, long long *budget, long long *ext) {
  double W = 0;
  ranked order[CAMP_MAX_RUNS];
  int m = 0;
  if (quantum < 1) quantum = 1;
  for (int i = 0; i < n; i++) {
    ext[i] = 0;
    const camp_alloc_row *r = &rows[i];
    if (!(r->s > 0) || !(r->T > 0) || !isfinite(r->G) || r->G == 0) continue;
    W += r->G * r->G / (r->s * r->s);
    if (m < CAMP_MAX_RUNS)
      order[m++] = (ranked){i, r->G * r->G / (r->s * r->s * r->T * (r->N > 0 ? r->N : 1))};
  }
  if (!(rel_err > target) || !(W > 0)) return 0;
  /* W_need / W = 1.1 (e / E)^2: the error falls as 1 / sqrt(W) */
  double deficit = W * (CAMP_ALLOC_MARGIN * (rel_err / target) * (rel_err / target) - 1);
  qsort(order, (size_t)m, sizeof order[0], by_gain);
  for (int j = 0; j < m && deficit > 0 && *budget >= quantum; j++) {
    const camp_alloc_row *r = &rows[order[j].row];
    const double per_step = r->G * r->G / (r->s * r->s * r->T); /* dW / dT */
    long long need = (long long)ceil(deficit / per_step / (double)quantum) * quantum;
    long long cap = r->steps / quantum * quantum; /* at most doubling */
    if (cap < quantum) cap = quantum;
    if (cap > *budget / quantum * quantum) cap = *budget / quantum * quantum;
    const long long dT = need < cap ? need : cap;
    if (dT <= 0) continue;
    ext[order[j].row] = dT;
    *budget -= dT;
    deficit -= per_step * (double)dT;
  }
  return deficit > 0 ? deficit / W : 0;
}
