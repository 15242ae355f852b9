/* Weighted least-squares fits of the flow laws with PETSc TAO (Gauss-Newton, TAOBRGN), parameter
 * covariance from (J^T W J)^-1 at the optimum, and model selection by information criteria. */
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
  double weight;   /* Schwarz (BIC) weight among the fitted models */
} fit_result;

typedef enum { SELECT_BIC = 0, SELECT_AIC } fit_criterion;

/* Fits one law. Must be called between PetscInitialize and PetscFinalize; runs on PETSC_COMM_SELF.
 */
int fit_law(const fit_data *d, const fluid_props *fl, flow_law_kind kind, fit_result *r);

/* Fits every law in `kinds` (count nk) and returns the index (into r) of the chosen model: the
 * lowest criterion among converged fits, or -1 if none converged. Fills r[i].weight. */
int fit_all(const fit_data *d, const fluid_props *fl, const flow_law_kind *kinds, int nk,
            fit_criterion crit, fit_result *r);

#endif
