/* The choice among the fitted flow laws: support test and information criteria (see fit_select.h).
 */
#include "fit_select.h"

#include <math.h>
#include <stdio.h>

int fit_nested_law(flow_law_kind kind, const char **at) {
  static const char *where[LAW_COUNT] = {NULL, "G0 = 0", "beta = 0", "n = 1"};
  if (at) *at = kind >= 0 && kind < LAW_COUNT ? where[kind] : NULL;
  return kind == LAW_THRESHOLD || kind == LAW_FORCHHEIMER || kind == LAW_POWER ? LAW_DARCY : -1;
}

/* "beta" or "k and G0": the parameters of r at a bound; returns how many. */
static int bound_params(const fit_result *r, char *buf, int len) {
  int count = 0, n = 0;
  buf[0] = 0;
  for (int p = 0; p < flow_law_nparams(r->kind); p++)
    if (r->at_bound[p] && n < len) {
      n += snprintf(buf + n, len - n, "%s%s", count ? " and " : "", fit_param_name(r->kind, p));
      count++;
    }
  return count;
}

void fit_support_test(fit_result *r) {
  r->supported = 0;
  r->support_sigma = 0.0;
  if (!r->ok || !r->converged) {
    snprintf(r->support, sizeof r->support, "no converged fit to test");
    return;
  }
  if (fit_nested_law(r->kind, NULL) < 0) {
    r->supported = 1;
    snprintf(r->support, sizeof r->support, "the null law, nested in the others");
    return;
  }
  const int is_power = r->kind == LAW_POWER;
  const double extra = r->theta[1], deviation = extra - (is_power ? 1.0 : 0.0);
  /* Birge ratio: a fit whose residuals scatter more than the stated errors (chi2/dof > 1) has its
   * standard errors understated by sqrt(chi2/dof); below 1 the stated errors are kept. */
  const double inflation = r->chi2_dof > 1.0 ? sqrt(r->chi2_dof) : 1.0;
  const double se = r->se[1] * inflation;
  r->support_sigma = se > 0 ? deviation / se : 0.0;
  const double z = fabs(r->support_sigma);
  char estimate[128], at_bound[32];
  int n = snprintf(estimate, sizeof estimate, "%s = %.3g +- %.2g",
                   is_power ? "n-1" : fit_param_name(r->kind, 1), deviation + 0.0, se);
  if (inflation > 1.0 && n < (int)sizeof estimate)
    snprintf(estimate + n, sizeof estimate - n, " (error x%.2g for chi2/dof %.3g)", inflation,
             r->chi2_dof);
  const int nb = bound_params(r, at_bound, sizeof at_bound);
  if (nb)
    snprintf(r->support, sizeof r->support, "%s at %s bound: no confidence interval", at_bound,
             nb > 1 ? "their" : "its");
  else if (!is_power && !(deviation > 0))
    snprintf(r->support, sizeof r->support, "%s: inadmissible, %s", estimate,
             r->kind == LAW_THRESHOLD ? "G0 <= 0 is flux at zero gradient, not a threshold"
                                      : "beta <= 0 is no inertial resistance");
  else if (!(se > 0))
    snprintf(r->support, sizeof r->support, "%s: no error bar to test against", estimate);
  else if (z < FIT_SUPPORT_SIGMA)
    snprintf(r->support, sizeof r->support, "%s: %.1f sigma < %g", estimate, z, FIT_SUPPORT_SIGMA);
  else if (is_power && !(fabs(deviation) > FIT_POWER_MIN_DEVIATION))
    snprintf(r->support, sizeof r->support, "%s: %.1f sigma, but |n-1| <= %g", estimate, z,
             FIT_POWER_MIN_DEVIATION);
  else {
    r->supported = 1;
    n = snprintf(r->support, sizeof r->support, "%s: %.1f sigma >= %g", estimate, z,
                 FIT_SUPPORT_SIGMA);
    if (is_power && n < (int)sizeof r->support)
      snprintf(r->support + n, sizeof r->support - n, ", |n-1| > %g", FIT_POWER_MIN_DEVIATION);
  }
}

static double criterion(const fit_result *r, fit_criterion crit) {
  return crit == SELECT_AIC ? r->aic : r->bic;
}

int fit_lowest(const fit_result *r, int nr, fit_criterion crit) {
  int best = -1;
  for (int i = 0; i < nr; i++)
    if (r[i].ok && r[i].converged &&
        (best < 0 || criterion(&r[i], crit) < criterion(&r[best], crit)))
      best = i;
  return best;
}

int fit_has_darcy(const fit_result *r, int nr) {
  for (int i = 0; i < nr; i++)
    if (r[i].kind == LAW_DARCY && r[i].ok && r[i].converged) return 1;
  return 0;
}

/* Eligibility of one fit whose support test has run: a law beyond Darcy that is not supported
 * gives way to a converged Darcy fit; without one it stays eligible if it is a valid law. */
static void set_eligible(fit_result *r, int darcy_fitted) {
  r->eligible = r->ok && r->converged;
  r->not_eligible[0] = 0;
  if (!r->eligible || r->supported) return;
  const char *at;
  fit_nested_law(r->kind, &at);
  char at_bound[32], invalid[160];
  const int nb = bound_params(r, at_bound, sizeof at_bound);
  if (darcy_fitted) {
    r->eligible = 0;
    if (nb)
      snprintf(
          r->not_eligible, sizeof r->not_eligible,
          "%s at %s bound; the simpler darcy law (the %s law at %s) was fitted and is preferred",
          at_bound, nb > 1 ? "their" : "its", flow_law_name(r->kind), at);
    else
      snprintf(r->not_eligible, sizeof r->not_eligible,
               "not supported (%s); the simpler darcy law (the %s law at %s) was fitted and is "
               "preferred",
               r->support, flow_law_name(r->kind), at);
  } else if (flow_law_check(&r->law, invalid, sizeof invalid)) {
    r->eligible = 0;
    snprintf(r->not_eligible, sizeof r->not_eligible, "not supported (%s) and not a valid law: %s",
             r->support, invalid);
  }
}

int fit_choose(fit_result *r, int nr, fit_criterion crit) {
  const int darcy_fitted = fit_has_darcy(r, nr);
  for (int i = 0; i < nr; i++) {
    fit_support_test(&r[i]);
    set_eligible(&r[i], darcy_fitted);
  }
  int best = -1;
  double best_bic = INFINITY;
  for (int i = 0; i < nr; i++) {
    if (!r[i].eligible) continue;
    if (best < 0 || r[i].supported > r[best].supported ||
        (r[i].supported == r[best].supported && criterion(&r[i], crit) < criterion(&r[best], crit)))
      best = i;
    if (r[i].bic < best_bic) best_bic = r[i].bic;
  }
  /* Schwarz weights exp(-BIC/2), normalised over the eligible fits */
  double sum = 0;
  for (int i = 0; i < nr; i++)
    if (r[i].eligible) sum += exp(-0.5 * (r[i].bic - best_bic));
  for (int i = 0; i < nr; i++)
    r[i].weight = r[i].eligible && sum > 0 ? exp(-0.5 * (r[i].bic - best_bic)) / sum : 0;
  return best;
}

int fit_all(const fit_data *d, const fluid_props *fl, const flow_law_kind *kinds, int nk,
            fit_criterion crit, fit_result *r) {
  for (int i = 0; i < nk; i++) fit_law(d, fl, kinds[i], &r[i]);
  return fit_choose(r, nk, crit);
}
