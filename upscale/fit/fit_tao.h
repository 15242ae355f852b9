/* Weighted least-squares fits of the flow laws with PETSc TAO (Gauss-Newton, TAOBRGN) and parameter
 * covariance from (J^T W J)^-1 at the optimum. The choice among the fits is fit_select.h's. */
#ifndef MDPORE_UPSCALE_FIT_TAO_H
#define MDPORE_UPSCALE_FIT_TAO_H

#include "fit_model.h"

typedef struct {
  flow_law_kind kind;
  int ok;        /* 1 if the fit ran (data supported the model); otherwise `why` says why not */
  int converged; /* TAO converged reason > 0 */
  int iterations;
  char why[160];
  fit_model model;
  double x[2];      /* internal parameters at the optimum */
  flow_law law;     /* fitted law */
  double theta[2];  /* reported parameters (fit_param_name) */
  double cov[2][2]; /* their covariance, from the stated standard errors (not rescaled by chi2) */
  double se[2];     /* standard errors sqrt(diag cov) */
  double chi2;
  int dof;
  double chi2_dof;
  double aic, bic; /* chi2 + 2p, chi2 + p ln N (Gaussian errors of known size) */
  double weight;   /* Schwarz (BIC) weight among the eligible models (0 if not eligible) */
  /* Parameters at a bound of the TAO problem (within FIT_AT_BOUND_TOL of it in the scaled internal
   * parameters): the bound then fixes the value, not the data, and the standard error is not a
   * confidence interval. bound[] is the bound as a reported parameter value; bound_upper[] says
   * whether it is an upper (1) or lower (0) bound of the reported parameter. */
  int at_bound[2];
  int bound_upper[2];
  double bound[2];
  /* The support test of a law beyond Darcy (fit_select.h), filled by fit_choose: whether its extra
   * parameter (G0, beta, n) is significant and physically admissible; Darcy is always supported. */
  int supported;
  double support_sigma;   /* extra parameter minus its Darcy value, in inflated standard errors */
  char support[200];      /* the test in words, e.g. "n-1 = 0.008 +- 0.006: 1.3 sigma < 3" */
  int eligible;           /* may be chosen (fit_choose) */
  char not_eligible[400]; /* why not, for a converged fit that is not eligible */
} fit_result;

/* A parameter within this distance of a bound (relative to max(1, |bound|), in the scaled internal
 * parameters, which are of order one at the initial guess) is at the bound. */
#define FIT_AT_BOUND_TOL 1e-6
/* Points of the sampled law curve in the JSON report, on 0 .. 1.1 max|G|. */
#define FIT_CURVE_POINTS 64

/* Fits one law. Must be called between PetscInitialize and PetscFinalize; runs on PETSC_COMM_SELF.
 * Flags parameters at a bound. A fit whose parameters are not determined (singular normal matrix)
 * or that gives any non-finite reported value (parameter, standard error, covariance, chi2, the law
 * at the data points or on the reported curve up to 1.1 max|G|) is refused: r->ok = 0, r->why says
 * why, and -1 is returned, so that no report ever prints nan or inf. */
int fit_law(const fit_data *d, const fluid_props *fl, flow_law_kind kind, fit_result *r);

#endif
