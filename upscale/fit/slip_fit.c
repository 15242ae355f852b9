/* Weighted least-squares fit of the slip length (see slip_fit.h; the model is slip_law.h). */
#include "slip_fit.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int slip_check_points(const slip_point *p, int n, const slip_setup *s, char *err, int len) {
  const int npar = s->free_scale ? 2 : 1;
  if (n < npar) {
    snprintf(err, len,
             "%d point(s) for %d parameter(s): expected at least %d permeabilities (one per pore "
             "size)%s",
             n, npar, npar, s->free_scale ? "; --free-scale fits b and a scale a" : "");
    return -1;
  }
  for (int i = 0; i < n; i++) {
    const slip_point *q = &p[i];
    const char *key = NULL, *want = NULL;
    double v = 0;
    if (!(isfinite(q->h) && q->h > 0))
      key = "h", want = "a finite pore size > 0", v = q->h;
    else if (!(isfinite(q->k) && q->k > 0))
      key = "k", want = "a finite permeability > 0", v = q->k;
    else if (!(isfinite(q->k_err) && q->k_err > 0))
      key = "k_err", want = "a finite positive standard error", v = q->k_err;
    else if (!(isfinite(q->porosity) && q->porosity > 0 && q->porosity <= 1))
      key = "porosity", want = "a porosity in (0, 1]", v = q->porosity;
    if (key) {
      snprintf(err, len, "%s: key '%s': expected %s, got %g", q->source, key, want, v);
      return -1;
    }
  }
  if (s->free_scale) {
    int distinct = 0;
    for (int i = 1; i < n && !distinct; i++) distinct = fabs(p[i].h - p[0].h) > 1e-9 * p[0].h;
    if (!distinct) {
      snprintf(err, len,
               "--free-scale: expected at least 2 distinct pore sizes h (got %d point(s), all at "
               "h = %g): a scale and b cannot be told apart at one size",
               n, p[0].h);
      return -1;
    }
  }
  return 0;
}

/* chi^2 of the model at (a, b); NaN when b leaves the model's range at some point. */
static double chi2_at(const slip_point *p, int n, const slip_setup *s, double a, double b) {
  double c2 = 0;
  for (int i = 0; i < n; i++) {
    if (b <= slip_b_min(s->shape, s->model, p[i].h)) return NAN;
    const double k0 = slip_k_noslip(s->shape, p[i].h, p[i].porosity);
    const double r =
        (p[i].k - a * k0 * slip_factor(s->shape, s->model, p[i].h, b, NULL)) / p[i].k_err;
    c2 += r * r;
  }
  return c2;
}

/* Normal equations J^T W J and J^T W r at (a, b), parameters ordered (b, a). */
static void normal_eq(const slip_point *p, int n, const slip_setup *s, double a, double b,
                      double M[2][2], double v[2]) {
  memset(M, 0, 4 * sizeof(double));
  v[0] = v[1] = 0;
  for (int i = 0; i < n; i++) {
    const double k0 = slip_k_noslip(s->shape, p[i].h, p[i].porosity), w = 1.0 / p[i].k_err;
    double dfdb;
    const double f = slip_factor(s->shape, s->model, p[i].h, b, &dfdb);
    const double j[2] = {a * k0 * dfdb * w, k0 * f * w}, r = (p[i].k - a * k0 * f) * w;
    for (int x = 0; x < 2; x++) {
      v[x] += j[x] * r;
      for (int y = 0; y < 2; y++) M[x][y] += j[x] * j[y];
    }
  }
}

int slip_fit(const slip_point *p, int n, const slip_setup *s, slip_result *r, char *err, int len) {
  if (slip_check_points(p, n, s, err, len)) return -1;
  memset(r, 0, sizeof *r);
  r->n = n;
  r->npar = s->free_scale ? 2 : 1;
  r->dof = n - r->npar;
  double a = 1.0, b = 0.0, M[2][2], v[2];
  double c2 = chi2_at(p, n, s, a, b);
  int it, converged = 0;
  for (it = 1; it <= 200 && !converged; it++) {
    normal_eq(p, n, s, a, b, M, v);
    double db, da = 0;
    if (s->free_scale) {
      const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
      db = (M[1][1] * v[0] - M[0][1] * v[1]) / det;
      da = (M[0][0] * v[1] - M[1][0] * v[0]) / det;
    } else {
      db = v[0] / M[0][0];
    }
    /* Step halving keeps b inside the model's range and chi^2 from growing. */
    double t = 1.0, c2n = NAN;
    for (int h = 0; h < 60; h++, t *= 0.5) {
      c2n = chi2_at(p, n, s, a + t * da, b + t * db);
      if (isfinite(c2n) && c2n <= c2 * (1 + 1e-12) + 1e-300) break;
    }
    if (!isfinite(c2n)) break;
    b += t * db;
    a += t * da;
    converged = fabs(t * db) <= 1e-12 * (1.0 + fabs(b)) && fabs(t * da) <= 1e-12 * (1.0 + fabs(a));
    c2 = c2n;
  }
  if (!converged) {
    snprintf(err, len,
             "the fit of b did not converge (%s model, %s, %d points; last b = %g): the "
             "permeabilities may not follow k_noslip F(b/h)",
             slip_model_names[s->model], slip_shape_names[s->shape], n, b);
    return -1;
  }
  normal_eq(p, n, s, a, b, M, v);
  r->iterations = it - 1;
  r->b = b;
  r->a = a;
  if (s->free_scale) {
    const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    r->b_err = sqrt(M[1][1] / det);
    r->a_err = sqrt(M[0][0] / det);
    r->cov_ab = -M[0][1] / det;
  } else {
    r->b_err = 1.0 / sqrt(M[0][0]);
  }
  r->chi2 = c2;
  r->chi2_dof = r->dof > 0 ? c2 / r->dof : NAN;
  r->b_err_scaled = r->b_err * (r->dof > 0 && r->chi2_dof > 1 ? sqrt(r->chi2_dof) : 1.0);
  return 0;
}

double slip_model_ratio(const slip_setup *s, const slip_result *r, double h, double *err) {
  double dfdb;
  const double f = slip_factor(s->shape, s->model, h, r->b, &dfdb);
  if (err) { /* gradient (d/db, d/da) of a F through the covariance */
    const double gb = r->a * dfdb, ga = f;
    double var = gb * gb * r->b_err * r->b_err;
    if (s->free_scale) var += ga * ga * r->a_err * r->a_err + 2 * ga * gb * r->cov_ab;
    *err = sqrt(var > 0 ? var : 0);
  }
  return r->a * f;
}
