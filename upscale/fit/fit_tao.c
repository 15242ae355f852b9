/* TAO least-squares driver (see fit_tao.h). Residuals r_i = (f(G_i; x) - q_i) / sigma_i. */
#include "fit_tao.h"

#include <math.h>
#include <petsctao.h>
#include <stdio.h>
#include <string.h>

typedef struct {
  const fit_data *d;
  const fit_model *m;
} lsq_ctx;

static PetscErrorCode residual(Tao tao, Vec X, Vec R, void *ctx) {
  (void)tao;
  const lsq_ctx *c = ctx;
  const PetscScalar *x;
  PetscScalar *r;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(R, &r));
  for (int i = 0; i < c->d->n; i++)
    r[i] = (fit_model_eval(c->m, x, c->d->G[i], NULL) - c->d->q[i]) / c->d->sigma[i];
  PetscCall(VecRestoreArray(R, &r));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

static PetscErrorCode jacobian(Tao tao, Vec X, Mat J, Mat Jpre, void *ctx) {
  (void)tao;
  (void)Jpre;
  const lsq_ctx *c = ctx;
  const PetscScalar *x;
  double g[2];
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  for (int i = 0; i < c->d->n; i++) {
    fit_model_eval(c->m, x, c->d->G[i], g);
    for (int j = 0; j < c->m->np; j++)
      PetscCall(MatSetValue(J, i, j, g[j] / c->d->sigma[i], INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* Runs TAOBRGN from the model's initial guess; writes the optimum into x. */
static PetscErrorCode solve(const fit_data *d, const fit_model *m, double *x, int *reason,
                            int *its) {
  lsq_ctx ctx = {d, m};
  Tao tao;
  Vec X, R, lo, hi;
  Mat J;
  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, m->np, &X));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, d->n, &R));
  PetscCall(VecDuplicate(X, &lo));
  PetscCall(VecDuplicate(X, &hi));
  for (int j = 0; j < m->np; j++) {
    PetscCall(VecSetValue(X, j, m->x0[j], INSERT_VALUES));
    PetscCall(
        VecSetValue(lo, j, isfinite(m->lower[j]) ? m->lower[j] : PETSC_NINFINITY, INSERT_VALUES));
    PetscCall(
        VecSetValue(hi, j, isfinite(m->upper[j]) ? m->upper[j] : PETSC_INFINITY, INSERT_VALUES));
  }
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, d->n, m->np, NULL, &J));
  PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
  PetscCall(TaoSetType(tao, TAOBRGN));
  PetscCall(TaoSetSolution(tao, X));
  PetscCall(TaoSetVariableBounds(tao, lo, hi));
  PetscCall(TaoSetResidualRoutine(tao, R, residual, &ctx));
  PetscCall(TaoSetJacobianResidualRoutine(tao, J, J, jacobian, &ctx));
  /* A vanishing proximal term keeps Gauss-Newton steps well posed without biasing the optimum. */
  PetscCall(TaoBRGNSetRegularizerWeight(tao, 1e-12));
  PetscCall(TaoSetTolerances(tao, 1e-8, 1e-12, 0.0)); /* floor of |J^T r| is ~1e-12 */
  PetscCall(TaoSetMaximumIterations(tao, 200));
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
  for (int j = 0; j < m->np; j++) x[j] = xa[j];
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscCall(TaoDestroy(&tao));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&R));
  PetscCall(VecDestroy(&lo));
  PetscCall(VecDestroy(&hi));
  PetscFunctionReturn(0);
}

/* chi^2 and the Gauss-Newton normal matrix A = J^T J (weighted) at x. */
static double normal_matrix(const fit_data *d, const fit_model *m, const double *x,
                            double A[2][2]) {
  double chi2 = 0, g[2] = {0, 0};
  A[0][0] = A[0][1] = A[1][0] = A[1][1] = 0;
  for (int i = 0; i < d->n; i++) {
    double r = (fit_model_eval(m, x, d->G[i], g) - d->q[i]) / d->sigma[i];
    chi2 += r * r;
    for (int a = 0; a < m->np; a++)
      for (int b = 0; b < m->np; b++) A[a][b] += g[a] * g[b] / (d->sigma[i] * d->sigma[i]);
  }
  return chi2;
}

int fit_law(const fit_data *d, const fluid_props *fl, flow_law_kind kind, fit_result *r) {
  memset(r, 0, sizeof *r);
  r->kind = kind;
  int np = flow_law_nparams(kind);
  if (d->n <= np) {
    snprintf(r->why, sizeof r->why,
             "%d points cannot fit %d parameters with a degree of freedom left", d->n, np);
    return -1;
  }
  if (fit_model_setup(&r->model, kind, d, fl)) {
    snprintf(r->why, sizeof r->why, "no flux along the gradient in the data");
    return -1;
  }
  int reason = 0;
  if (solve(d, &r->model, r->x, &reason, &r->iterations)) {
    snprintf(r->why, sizeof r->why, "TAO failed");
    return -1;
  }
  r->ok = 1;
  r->converged = reason > 0;
  if (!r->converged) snprintf(r->why, sizeof r->why, "TAO did not converge (reason %d)", reason);
  double A[2][2], T[2][2], C[2][2] = {{0, 0}, {0, 0}};
  r->chi2 = normal_matrix(d, &r->model, r->x, A);
  /* covariance of x: A^-1 (1x1 or 2x2 inverse) */
  if (np == 1) {
    C[0][0] = A[0][0] > 0 ? 1.0 / A[0][0] : INFINITY;
  } else {
    double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
    if (fabs(det) > 1e-300) {
      C[0][0] = A[1][1] / det;
      C[1][1] = A[0][0] / det;
      C[0][1] = C[1][0] = -A[0][1] / det;
    } else {
      C[0][0] = C[1][1] = INFINITY; /* parameters not determined (e.g. all points below G0) */
    }
  }
  fit_model_law(&r->model, r->x, &r->law, T);
  for (int a = 0; a < np; a++) {
    r->theta[a] = fit_param_value(&r->law, a);
    for (int b = 0; b < np; b++) {
      double s = 0;
      for (int i = 0; i < np; i++)
        for (int j = 0; j < np; j++) s += T[a][i] * C[i][j] * T[b][j];
      r->cov[a][b] = s;
    }
    r->se[a] = sqrt(r->cov[a][a]);
  }
  r->dof = d->n - np;
  r->chi2_dof = r->chi2 / r->dof;
  r->aic = r->chi2 + 2.0 * np;
  r->bic = r->chi2 + np * log((double)d->n);
  return 0;
}

int fit_all(const fit_data *d, const fluid_props *fl, const flow_law_kind *kinds, int nk,
            fit_criterion crit, fit_result *r) {
  int best = -1;
  double best_bic = INFINITY;
  for (int i = 0; i < nk; i++) {
    fit_law(d, fl, kinds[i], &r[i]);
    if (!r[i].ok || !r[i].converged) continue;
    double c = crit == SELECT_AIC ? r[i].aic : r[i].bic;
    if (best < 0 || c < (crit == SELECT_AIC ? r[best].aic : r[best].bic)) best = i;
    if (r[i].bic < best_bic) best_bic = r[i].bic;
  }
  double sum = 0;
  for (int i = 0; i < nk; i++)
    if (r[i].ok && r[i].converged) sum += exp(-0.5 * (r[i].bic - best_bic));
  for (int i = 0; i < nk; i++)
    r[i].weight =
        (r[i].ok && r[i].converged && sum > 0) ? exp(-0.5 * (r[i].bic - best_bic)) / sum : 0;
  return best;
}
