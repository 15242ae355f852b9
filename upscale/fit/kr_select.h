/* The choice between the Corey and LET laws (docs/relperm.md section 5). Corey (6 parameters) is
 * the null law; LET (10) reduces to it in a limit (T -> 0 and E -> infinity with kr_max / E fixed
 * gives kr_max' Se^L), so the test is the nested-model one on the chi2 drop:
 *
 *   D = (chi2_corey - chi2_let) / max(1, chi2_let / dof_let)
 *
 * (the denominator inflates it down when LET's own residuals scatter beyond the error bars, as the
 * Birge ratio of fit_select.h), compared with the chi2 quantile of dp = 4 degrees of freedom at
 * the level KR_SELECT_ALPHA (0.27 %, the two-sided 3-sigma level of fit_select.h's support test).
 * LET is chosen only when D exceeds it AND LET's BIC is lower; otherwise Corey. */
#ifndef MDPORE_UPSCALE_KR_SELECT_H
#define MDPORE_UPSCALE_KR_SELECT_H

#include <math.h>

#include "fit_select.h"
#include "kr_fit.h"

/* The test's level: the two-sided Gaussian tail beyond FIT_SUPPORT_SIGMA (3), 0.27 %, the level at
 * which `mdpore fit` accepts a flow law beyond Darcy (fit_select.h). */
#define KR_SELECT_ALPHA erfc(FIT_SUPPORT_SIGMA / M_SQRT2)

typedef struct {
  int chosen;       /* KR_COREY, KR_LET, or -1 if no fit */
  int tested;       /* both fits ran, so the test was made */
  double D, D_crit; /* the statistic and its critical value */
  int dp;           /* degrees of freedom of the test */
  char text[400];   /* the test and the outcome in words */
} kr_choice;

/* The chi2 quantile of k (even) degrees of freedom at upper-tail probability alpha. */
double kr_chi2_quantile_even(int k, double alpha);

/* fits[KR_COREY], fits[KR_LET]: results of kr_fit_law (ok = 0 where not run). forced: -1 for the
 * test, else the law asked for (--law), which is then chosen whatever the test says. */
void kr_choose(const kr_fit_result fits[KR_LAW_COUNT], int forced, kr_choice *c);

#endif
