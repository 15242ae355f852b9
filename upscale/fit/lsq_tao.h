/* Bounded weighted nonlinear least squares with PETSc TAO (Gauss-Newton, TAOBRGN): minimises
 *   chi2(x) = sum_i ((y_model(x, i) - y_i) / sigma_i)^2
 * over x in [lower, upper], and the covariance of x from the weighted normal matrix (J^T W J)^-1 at
 * the optimum. Shared by the flow-law fits (fit_tao.c) and the relative-permeability fits
 * (relperm_fit.c). Must be called between PetscInitialize and PetscFinalize; runs on PETSC_COMM_SELF.
 */
#ifndef MDPORE_UPSCALE_LSQ_TAO_H
#define MDPORE_UPSCALE_LSQ_TAO_H

#define LSQ_MAX_PARAMS 12

/* The model at data point i for parameters x; writes dy/dx_j into grad[0..np-1] when grad is not
 * NULL. */
typedef double (*lsq_model_fn)(const double *x, int i, double *grad, void *ctx);

typedef struct {
  int n, np;               /* data points, parameters (np <= LSQ_MAX_PARAMS) */
  const double *y, *sigma; /* data and their standard errors (> 0) */
  lsq_model_fn model;      /* the model and its context */
  void *ctx;
  const double *x0;            /* initial guess */
  const double *lower, *upper; /* bounds; +-INFINITY for none */
  int max_iterations;          /* 0: 200 */
} lsq_problem;

/* Runs TAOBRGN from p->x0; writes the optimum into x, TAO's converged reason (> 0: converged) and
 * the iteration count. Returns 0, or -1 if PETSc failed. */
int lsq_tao_solve(const lsq_problem *p, double *x, int *reason, int *iterations);

/* chi2 at x and the weighted normal matrix A = J^T W J (np x np, row-major) when A is not NULL. */
double lsq_chi2(const lsq_problem *p, const double *x, double *A);

/* Inverts the np x np symmetric matrix A into C (Gauss-Jordan with partial pivoting). Returns 0, or
 * -1 when A is singular (a pivot below 1e-14 of the largest diagonal element): the parameters are
 * then not all determined by the data. */
int lsq_invert(const double *A, int np, double *C);

#endif
