/* Corey or LET (see kr_select.h). */
#include "kr_select.h"

#include <math.h>
#include <stdio.h>

/* Upper tail of chi2 with k even: Q(x) = exp(-x/2) sum_{j < k/2} (x/2)^j / j!. */
static double chi2_tail_even(int k, double x) {
  double term = 1.0, sum = 1.0;
  for (int j = 1; j < k / 2; j++) {
    term *= 0.5 * x / j;
    sum += term;
  }
  return exp(-0.5 * x) * sum;
}

double kr_chi2_quantile_even(int k, double alpha) {
  double lo = 0.0, hi = 1.0;
  while (chi2_tail_even(k, hi) > alpha) hi *= 2.0;
  for (int it = 0; it < 200; it++) {
    const double mid = 0.5 * (lo + hi);
    if (chi2_tail_even(k, mid) > alpha)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

static int usable(const kr_fit_result *r) {
  return r->ok && r->converged;
}

void kr_choose(const kr_fit_result fits[KR_LAW_COUNT], int forced, kr_choice *c) {
  const kr_fit_result *co = &fits[KR_COREY], *let = &fits[KR_LET];
  c->chosen = -1;
  c->tested = usable(co) && usable(let);
  c->dp = let->n_free - co->n_free;
  c->D = c->D_crit = NAN;
  c->text[0] = 0;
  if (c->tested) {
    c->D = (co->chi2 - let->chi2) / (let->chi2_dof > 1.0 ? let->chi2_dof : 1.0);
    c->D_crit = kr_chi2_quantile_even(c->dp, KR_SELECT_ALPHA);
    const int better = c->D >= c->D_crit && let->bic < co->bic;
    snprintf(c->text, sizeof c->text,
             "D = (chi2_corey - chi2_let) / max(1, chi2_let/dof) = (%.4g - %.4g) / %.3g = %.3g %s "
             "%.3g (chi2 quantile, %d dof, level %.2g); BIC corey %.4g, let %.4g: %s",
             co->chi2, let->chi2, let->chi2_dof > 1.0 ? let->chi2_dof : 1.0, c->D,
             c->D >= c->D_crit ? ">=" : "<", c->D_crit, c->dp, KR_SELECT_ALPHA, co->bic, let->bic,
             better ? "LET is significantly better" : "LET is not significantly better: Corey");
    c->chosen = better ? KR_LET : KR_COREY;
  } else if (usable(co)) {
    c->chosen = KR_COREY;
    snprintf(c->text, sizeof c->text, "%s",
             let->ok || let->why[0] ? "no usable LET fit: Corey" : "Corey only");
  } else if (usable(let)) {
    c->chosen = KR_LET;
    snprintf(c->text, sizeof c->text, "no usable Corey fit: LET");
  }
  if (forced >= 0 && usable(&fits[forced])) {
    if (c->chosen != forced) {
      char tail[sizeof c->text];
      snprintf(tail, sizeof tail, "%s", c->text);
      snprintf(c->text, sizeof c->text, "--law %s asked for (the test alone: %.300s)",
               kr_law_name(forced), tail);
    }
    c->chosen = forced;
  } else if (forced >= 0) {
    c->chosen = -1;
  }
}
