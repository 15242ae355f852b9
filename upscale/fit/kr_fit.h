/* Weighted least-squares fit of a relative-permeability law (kr_law.h) to a kr table (kr_table.h)
 * on the TAO driver of lsq_tao.h. krw and kro are fitted together (they share swc and sor): every
 * row contributes a krw point and a kro point, each weighted by 1/err^2; a point whose error is
 * empty or 0 cannot be weighted and is left out (counted in the result).
 *
 * swc and sor: fitted by default, within bounds the data set: swc below the lowest Sw at which
 * water flows (krw > KR_NEGATIVE_SIGMA errors above 0), sor below 1 - the highest Sw at which oil
 * flows; or fixed by the caller. The table's end points are not taken as swc and sor because a
 * campaign's lowest and highest Sw are where its saturations stopped, and a phase that still flows
 * there (wetting films, connected oil) has its residual saturation beyond them.
 *
 * Errors: the covariance (J^T W J)^-1 of the free parameters at the optimum, parameters at a bound
 * held fixed (their error is not a confidence interval and is reported as 0 with the flag); the
 * standard errors are also given inflated by sqrt(chi2/dof) when that exceeds 1 (the Birge ratio,
 * as fit_select.h: data that scatter more than their error bars widen the errors, never narrow). */
#ifndef MDPORE_UPSCALE_KR_FIT_H
#define MDPORE_UPSCALE_KR_FIT_H

#include "kr_table.h"
#include "law/kr_law.h"

typedef struct {
  double swc, sor;           /* fixed values, or NAN to fit */
  const kr_law *corey_start; /* LET: the Corey fit of the same data to start from (NULL: fitted
                                here) */
} kr_fit_opts;

typedef struct {
  kr_law_kind kind;
  int ok;        /* 1 if the fit ran; otherwise `why` says why not */
  int converged; /* TAO's reason > 0 at the best start */
  int iterations, starts;
  char why[240];
  kr_law law;
  double se[KR_MAX_PARAMS];                          /* standard errors from the stated kr errors */
  double se_inflated[KR_MAX_PARAMS];                 /* x inflation */
  double inflation;                                  /* max(1, sqrt(chi2/dof)) */
  int fixed[KR_MAX_PARAMS];                          /* fixed by the caller (swc, sor) */
  int at_bound[KR_MAX_PARAMS];                       /* at a bound of the fit */
  double lower[KR_MAX_PARAMS], upper[KR_MAX_PARAMS]; /* the bounds (reported parameters) */
  int n_free;                                        /* parameters fitted (not fixed) */
  int n_points, n_krw, n_kro;                        /* points fitted */
  int left_out_krw, left_out_kro;                    /* points without an error, left out */
  double chi2, chi2_dof, bic;                        /* bic = chi2 + n_free ln(n_points) */
  int dof;
} kr_fit_result;

/* Fits one law. Must run between PetscInitialize and PetscFinalize. Returns 0, or -1 with r->ok = 0
 * and r->why (fewer points than parameters plus one, no row where a phase flows, a singular normal
 * matrix, TAO failure). */
int kr_fit_law(const kr_table *t, kr_law_kind kind, const kr_fit_opts *o, kr_fit_result *r);

#endif
