/* Relative-permeability fits (kr_fit.h, kr_select.h) on synthetic tables with Gaussian noise of
 * known size, seeded:
 *  - Corey truth: every parameter recovered within 2 (inflated) standard errors in >= 88% of the
 *    trials (95.4% expected for a correct covariance), and within 3 in the first trial; LET chosen
 *    in at most 3% of the trials (the test's level is 0.27%);
 *  - LET truth of a shape Corey cannot follow: LET chosen in >= 90% of the trials;
 *  - the chi2 quantile behind the test: 4 dof at 0.27% is 16.25 (tables). */
#include <math.h>
#include <petscsys.h>
#include <stdio.h>
#include <string.h>

#include "kr_select.h"
#include "synthetic_rng.h"

#define TRIALS 60
#define ROWS 14

static double sw_col[ROWS], krw_col[ROWS], kro_col[ROWS], ew_col[ROWS], eo_col[ROWS];

/* A table of ROWS saturations in [0.2, 0.78] drawn from `truth`, error 2% of kr + 0.003. */
static void synth(const kr_law *truth, uint64_t *seed, kr_table *t) {
  memset(t, 0, sizeof *t);
  snprintf(t->path, sizeof t->path, "synthetic");
  t->rc_m = t->temperature_K = t->M = NAN;
  for (int i = 0; i < ROWS; i++) {
    double krw, kro;
    sw_col[i] = 0.2 + 0.58 * i / (ROWS - 1.0);
    kr_law_eval(truth, sw_col[i], &krw, &kro);
    ew_col[i] = 0.02 * krw + 0.003;
    eo_col[i] = 0.02 * kro + 0.003;
    krw_col[i] = krw + ew_col[i] * gaussian(seed);
    kro_col[i] = kro + eo_col[i] * gaussian(seed);
  }
  t->n = ROWS;
  t->sw = sw_col, t->krw = krw_col, t->kro = kro_col, t->krw_err = ew_col, t->kro_err = eo_col;
}

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  int failed = 0;
  const double q = kr_chi2_quantile_even(4, KR_SELECT_ALPHA);
  printf("chi2 quantile, 4 dof, upper 0.27%%: %.4f (tables: 16.25)\n", q);
  if (fabs(q - 16.25) > 0.01) failed = 1;

  const kr_law corey = {KR_COREY, {0.12, 0.18, 0.45, 2.6, 0.9, 1.9}};
  const kr_fit_opts fit_all = {NAN, NAN, NULL};
  int inside[6] = {0}, converged = 0, let_chosen = 0;
  uint64_t seed = 20251129;
  for (int k = 0; k < TRIALS; k++) {
    kr_table t;
    kr_fit_result fits[KR_LAW_COUNT];
    kr_choice c;
    synth(&corey, &seed, &t);
    kr_fit_law(&t, KR_COREY, &fit_all, &fits[KR_COREY]);
    const kr_fit_opts from_corey = {NAN, NAN, fits[KR_COREY].ok ? &fits[KR_COREY].law : NULL};
    kr_fit_law(&t, KR_LET, &from_corey, &fits[KR_LET]);
    kr_choose(fits, -1, &c);
    let_chosen += c.chosen == KR_LET;
    const kr_fit_result *r = &fits[KR_COREY];
    if (!(r->ok && r->converged)) continue;
    converged++;
    for (int p = 0; p < 6; p++) {
      const double z = (r->law.p[p] - corey.p[p]) / r->se_inflated[p];
      inside[p] += fabs(z) <= 2.0;
      if (k == 0) {
        printf("trial 0: %-8s true %.4g fitted %.4g +- %.2g (%.2f sigma)\n",
               kr_law_param_name(KR_COREY, p), corey.p[p], r->law.p[p], r->se_inflated[p], z);
        if (!(fabs(z) <= 3.0)) failed = 1;
      }
    }
    if (k == 0) printf("trial 0: chi2/dof %.3g; %s\n", r->chi2_dof, c.text);
  }
  printf("Corey truth: converged %d/%d, LET chosen %d/%d\n", converged, TRIALS, let_chosen, TRIALS);
  if (converged < 0.95 * TRIALS || let_chosen > 0.03 * TRIALS) failed = 1;
  for (int p = 0; p < 6; p++) {
    printf("  %-8s within 2 sigma in %d/%d\n", kr_law_param_name(KR_COREY, p), inside[p],
           converged);
    if (inside[p] < 0.88 * converged) failed = 1;
  }

  /* LET with a steep rise at high Se (T < 1, large E): no single Corey exponent follows it */
  const kr_law let = {KR_LET, {0.1, 0.15, 0.6, 1.2, 8.0, 0.6, 0.85, 1.4, 6.0, 0.7}};
  int let_found = 0;
  for (int k = 0; k < TRIALS; k++) {
    kr_table t;
    kr_fit_result fits[KR_LAW_COUNT];
    kr_choice c;
    synth(&let, &seed, &t);
    kr_fit_law(&t, KR_COREY, &fit_all, &fits[KR_COREY]);
    const kr_fit_opts from_corey = {NAN, NAN, fits[KR_COREY].ok ? &fits[KR_COREY].law : NULL};
    kr_fit_law(&t, KR_LET, &from_corey, &fits[KR_LET]);
    kr_choose(fits, -1, &c);
    let_found += c.chosen == KR_LET;
    if (k == 0) printf("LET truth, trial 0: %s\n", c.text);
  }
  printf("LET truth: LET chosen %d/%d\n", let_found, TRIALS);
  if (let_found < 0.9 * TRIALS) failed = 1;
  printf(failed ? "FAILED\n" : "passed\n");
  PetscCall(PetscFinalize());
  return failed;
}
