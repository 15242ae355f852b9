/* Flow-law fits on the TAO least-squares driver of lsq_tao.h (see fit_tao.h). Residuals
 * r_i = (f(G_i; x) - q_i) / sigma_i. */
#include "fit_tao.h"

#include "lsq_tao.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The flow law as an lsq_tao.h model: q(G_i; x). */
static double flow_model(const double *x, int i, double *grad, void *ctx) {
  const fit_data *d = ((const void **)ctx)[0];
  const fit_model *m = ((const void **)ctx)[1];
  return fit_model_eval(m, x, d->G[i], grad);
}

/* Runs TAOBRGN (lsq_tao.h) from the model's initial guess; writes the optimum into x. */
static int solve(const fit_data *d, const fit_model *m, double *x, int *reason, int *its) {
  const void *ctx[2] = {d, m};
  const lsq_problem p = {d->n,        m->np, d->q,     d->sigma, flow_model,
                         (void *)ctx, m->x0, m->lower, m->upper, 200};
  return lsq_tao_solve(&p, x, reason, its);
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

/* Flags the parameters within FIT_AT_BOUND_TOL of a bound of the TAO problem, and the bound as a
 * reported parameter value (upper or lower for the reported parameter, which may be a decreasing
 * function of the internal one: forchheimer k = mu / a). */
static void find_bounds(fit_result *r) {
  const fit_model *m = &r->model;
  for (int j = 0; j < m->np; j++) {
    const double lo = m->lower[j], hi = m->upper[j], x = r->x[j];
    double b;
    int lower;
    if (isfinite(lo) && x - lo <= FIT_AT_BOUND_TOL * fmax(1.0, fabs(lo)))
      b = lo, lower = 1;
    else if (isfinite(hi) && hi - x <= FIT_AT_BOUND_TOL * fmax(1.0, fabs(hi)))
      b = hi, lower = 0;
    else
      continue;
    double xb[2] = {r->x[0], r->x[1]}, T[2][2];
    flow_law lb;
    xb[j] = b;
    fit_model_law(m, xb, &lb, T);
    r->at_bound[j] = 1;
    r->bound[j] = fit_param_value(&lb, j);
    r->bound_upper[j] = lower ? T[j][j] < 0 : !(T[j][j] < 0);
  }
}

/* The first reported value of a fit that is not finite, or NULL: everything the reports print. */
static const char *nonfinite_value(const fit_result *r, const fit_data *d, const fluid_props *fl,
                                   char *buf, int len) {
  const int np = flow_law_nparams(r->kind);
  for (int a = 0; a < np; a++) {
    const char *name = fit_param_name(r->kind, a);
    if (!isfinite(r->theta[a])) return snprintf(buf, len, "value of %s", name), buf;
    if (!isfinite(r->se[a])) return snprintf(buf, len, "standard error of %s", name), buf;
    if (r->at_bound[a] && !isfinite(r->bound[a]))
      return snprintf(buf, len, "bound of %s", name), buf;
    for (int b = 0; b < np; b++)
      if (!isfinite(r->cov[a][b])) return snprintf(buf, len, "covariance"), buf;
  }
  if (!isfinite(r->chi2) || !isfinite(r->aic) || !isfinite(r->bic) || !isfinite(r->chi2_dof))
    return "chi2";
  double gmax = 0;
  for (int i = 0; i < d->n; i++) {
    gmax = fmax(gmax, fabs(d->G[i]));
    if (!isfinite(flow_law_q_exact(&r->law, fl, d->G[i]))) return "flux at a data point";
  }
  for (int i = 0; i < FIT_CURVE_POINTS; i++)
    if (!isfinite(flow_law_q_exact(&r->law, fl, 1.1 * gmax * i / (FIT_CURVE_POINTS - 1.0))))
      return "flux on the reported curve";
  if (r->kind == LAW_POWER && !isfinite(r->model.g_ref)) return "reference gradient";
  return NULL;
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
  /* covariance of x: A^-1 (1x1 or 2x2 inverse); a singular A leaves parameters undetermined */
  int singular = 0;
  if (np == 1) {
    if (A[0][0] > 0)
      C[0][0] = 1.0 / A[0][0];
    else
      singular = 1;
  } else {
    double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
    if (fabs(det) > 1e-300 && isfinite(det)) {
      C[0][0] = A[1][1] / det;
      C[1][1] = A[0][0] / det;
      C[0][1] = C[1][0] = -A[0][1] / det;
    } else {
      singular = 1;
    }
  }
  if (singular) {
    r->ok = r->converged = 0;
    snprintf(r->why, sizeof r->why,
             "the data do not determine the parameters (singular normal matrix at the optimum, "
             "e.g. every point below G0)");
    return -1;
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
  find_bounds(r);
  char buf[64];
  const char *bad = nonfinite_value(r, d, fl, buf, sizeof buf);
  if (bad) {
    r->ok = r->converged = 0;
    snprintf(r->why, sizeof r->why,
             "the fit gave a non-finite %s (the data do not determine this law's parameters)", bad);
    return -1;
  }
  return 0;
}
