/* TAO least-squares driver and normal-matrix covariance (see lsq_tao.h). Residuals
 * r_i = (y_model(x, i) - y_i) / sigma_i. */
#include "lsq_tao.h"

#include <math.h>
#include <petsctao.h>
#include <string.h>

static PetscErrorCode residual(Tao tao, Vec X, Vec R, void *ctx) {
  (void)tao;
  const lsq_problem *p = ctx;
  const PetscScalar *x;
  PetscScalar *r;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(R, &r));
  for (int i = 0; i < p->n; i++) r[i] = (p->model(x, i, NULL, p->ctx) - p->y[i]) / p->sigma[i];
  PetscCall(VecRestoreArray(R, &r));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

static PetscErrorCode jacobian(Tao tao, Vec X, Mat J, Mat Jpre, void *ctx) {
  (void)tao;
  (void)Jpre;
  const lsq_problem *p = ctx;
  const PetscScalar *x;
  double g[LSQ_MAX_PARAMS];
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  for (int i = 0; i < p->n; i++) {
    p->model(x, i, g, p->ctx);
    for (int j = 0; j < p->np; j++)
      PetscCall(MatSetValue(J, i, j, g[j] / p->sigma[i], INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

static PetscErrorCode solve(const lsq_problem *p, double *x, int *reason, int *its) {
  Tao tao;
  Vec X, R, lo, hi;
  Mat J;
  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, p->np, &X));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, p->n, &R));
  PetscCall(VecDuplicate(X, &lo));
  PetscCall(VecDuplicate(X, &hi));
  for (int j = 0; j < p->np; j++) {
    PetscCall(VecSetValue(X, j, p->x0[j], INSERT_VALUES));
    PetscCall(
        VecSetValue(lo, j, isfinite(p->lower[j]) ? p->lower[j] : PETSC_NINFINITY, INSERT_VALUES));
    PetscCall(
        VecSetValue(hi, j, isfinite(p->upper[j]) ? p->upper[j] : PETSC_INFINITY, INSERT_VALUES));
  }
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, p->n, p->np, NULL, &J));
  PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
  PetscCall(TaoSetType(tao, TAOBRGN));
  PetscCall(TaoSetSolution(tao, X));
  PetscCall(TaoSetVariableBounds(tao, lo, hi));
  PetscCall(TaoSetResidualRoutine(tao, R, residual, (void *)p));
  PetscCall(TaoSetJacobianResidualRoutine(tao, J, J, jacobian, (void *)p));
  /* A vanishing proximal term keeps Gauss-Newton steps well posed without biasing the optimum. */
  PetscCall(TaoBRGNSetRegularizerWeight(tao, 1e-12));
  PetscCall(TaoSetTolerances(tao, 1e-8, 1e-12, 0.0)); /* floor of |J^T r| is ~1e-12 */
  PetscCall(TaoSetMaximumIterations(tao, p->max_iterations > 0 ? p->max_iterations : 200));
  PetscCall(TaoSetOptionsPrefix(tao, "fit_"));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoSolve(tao));
  TaoConvergedReason why;
  PetscInt n_it;
  PetscCall(TaoGetConvergedReason(tao, &why));
  PetscCall(TaoGetIterationNumber(tao, &n_it));
  *reason = (int)why;
  *its = (int)n_it;
  const PetscScalar *xa;
  PetscCall(VecGetArrayRead(X, &xa));
  for (int j = 0; j < p->np; j++) x[j] = xa[j];
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscCall(TaoDestroy(&tao));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&R));
  PetscCall(VecDestroy(&lo));
  PetscCall(VecDestroy(&hi));
  PetscFunctionReturn(0);
}

int lsq_tao_solve(const lsq_problem *p, double *x, int *reason, int *iterations) {
  return solve(p, x, reason, iterations) ? -1 : 0;
}

double lsq_chi2(const lsq_problem *p, const double *x, double *A) {
  double chi2 = 0, g[LSQ_MAX_PARAMS];
  const int np = p->np;
  if (A) memset(A, 0, (size_t)np * np * sizeof *A);
  for (int i = 0; i < p->n; i++) {
    const double s2 = p->sigma[i] * p->sigma[i];
    const double r = (p->model(x, i, A ? g : NULL, p->ctx) - p->y[i]) / p->sigma[i];
    chi2 += r * r;
    if (A)
      for (int a = 0; a < np; a++)
        for (int b = 0; b < np; b++) A[a * np + b] += g[a] * g[b] / s2;
  }
  return chi2;
}

int lsq_invert(const double *A, int np, double *C) {
  double M[LSQ_MAX_PARAMS][2 * LSQ_MAX_PARAMS], dmax = 0;
  for (int i = 0; i < np; i++) {
    for (int j = 0; j < np; j++) {
      M[i][j] = A[i * np + j];
      M[i][np + j] = i == j;
    }
    dmax = fmax(dmax, fabs(A[i * np + i]));
  }
  if (!(dmax > 0) || !isfinite(dmax)) return -1;
  for (int c = 0; c < np; c++) {
    int piv = c;
    for (int r = c + 1; r < np; r++)
      if (fabs(M[r][c]) > fabs(M[piv][c])) piv = r;
    if (!(fabs(M[piv][c]) > 1e-14 * dmax)) return -1;
    if (piv != c)
      for (int j = 0; j < 2 * np; j++) {
        const double t = M[c][j];
        M[c][j] = M[piv][j];
        M[piv][j] = t;
      }
    const double inv = 1.0 / M[c][c];
    for (int j = 0; j < 2 * np; j++) M[c][j] *= inv;
    for (int r = 0; r < np; r++)
      if (r != c && M[r][c] != 0) {
        const double f = M[r][c];
        for (int j = 0; j < 2 * np; j++) M[r][j] -= f * M[c][j];
      }
  }
  for (int i = 0; i < np; i++)
    for (int j = 0; j < np; j++) C[i * np + j] = M[i][np + j];
  return 0;
}
