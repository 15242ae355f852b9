/* The choice of one flow law among the fitted ones. Darcy is nested in the other three laws
 * (threshold at G0 = 0, Forchheimer at beta = 0, power at n = 1) and is the null model: a law beyond
 * Darcy may be chosen only when it passes the support test on its extra parameter p (a nested-model
 * test), with p0 its Darcy value and se(p) its standard error:
 *
 *   inflation = sqrt(chi2/dof) of the law's own fit when above 1, else 1 (the Birge ratio: data
 *               that scatter more than their error bars widen the error, never narrow it)
 *   z         = (p - p0) / (se(p) inflation)
 *   supported = p not at a bound of the fit, p admissible (G0 > 0, beta > 0), |z| >= FIT_SUPPORT_SIGMA,
 *               and for the power law also |n - 1| > FIT_POWER_MIN_DEVIATION.
 *
 * With Darcy fitted (and converged) the eligible laws are Darcy and the supported laws, and the
 * information criterion (BIC or AIC) ranks only these. Without Darcy among the fits an unsupported
 * law stays eligible as long as it is a valid law (flow_law_check: G0 > 0, beta >= 0), flagged, and
 * a supported law is preferred to it. */
#ifndef MDPORE_UPSCALE_FIT_SELECT_H
#define MDPORE_UPSCALE_FIT_SELECT_H

#include "fit_tao.h"

/* The level of the support test, in (inflated) standard errors: 3 sigma, a chance of about 0.3%
 * that pure Darcy data pass it per law (two-sided, Gaussian). */
#define FIT_SUPPORT_SIGMA 3.0
/* The smallest |n - 1| of a supported power law: closer to 1 it is Darcy for any use of the law. */
#define FIT_POWER_MIN_DEVIATION 0.05

typedef enum { SELECT_BIC = 0, SELECT_AIC } fit_criterion;

/* The law with fewer parameters that `kind` reduces to at one value of its second parameter
 * (darcy: threshold at G0 = 0, forchheimer at beta = 0, power at n = 1), or -1 if none. */
int fit_nested_law(flow_law_kind kind, const char **at);

/* Fills r->supported, r->support_sigma and r->support (the test above) for a fitted result. */
void fit_support_test(fit_result *r);

/* Chooses among fitted results (r[0..nr-1], already filled by fit_law): runs the support test on
 * each, sets r[i].eligible and r[i].not_eligible and the BIC weights among the eligible fits, and
 * returns the index of the chosen law (supported before unsupported, then the lowest criterion), or
 * -1 if none is eligible. */
int fit_choose(fit_result *r, int nr, fit_criterion crit);

/* The index of the lowest criterion among ok and converged fits, eligible or not (-1 if none): the
 * law an information criterion alone would have chosen. */
int fit_lowest(const fit_result *r, int nr, fit_criterion crit);

/* Whether a usable (fitted and converged) Darcy fit is among r[0..nr-1]. */
int fit_has_darcy(const fit_result *r, int nr);

/* Fits every law in `kinds` (count nk) and returns fit_choose's choice. */
int fit_all(const fit_data *d, const fluid_props *fl, const flow_law_kind *kinds, int nk,
            fit_criterion crit, fit_result *r);

#endif
