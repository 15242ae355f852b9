/* Least-squares models for each flow law (see fit_model.h). */
#include "fit_model.h"

#include <math.h>

/* Weighted linear regression y = c1 x + c0 with weights w; returns -1 if degenerate. */
static int linreg(int n, const double *x, const double *y, const double *w, double *c1,
                  double *c0) {
  double S = 0, Sx = 0, Sy = 0, Sxx = 0, Sxy = 0;
  for (int i = 0; i < n; i++) {
    S += w[i];
    Sx += w[i] * x[i];
    Sy += w[i] * y[i];
    Sxx += w[i] * x[i] * x[i];
    Sxy += w[i] * x[i] * y[i];
  }
  double det = S * Sxx - Sx * Sx;
  if (!(fabs(det) > 1e-300) || n < 2) return -1;
  *c1 = (S * Sxy - Sx * Sy) / det;
  *c0 = (Sxx * Sy - Sx * Sxy) / det;
  return 0;
}

/* Darcy through the origin: c = sum(w G q) / sum(w G^2). */
static double darcy_slope(const fit_data *d) {
  double num = 0, den = 0;
  for (int i = 0; i < d->n; i++) {
    double w = 1.0 / (d->sigma[i] * d->sigma[i]);
    num += w * d->G[i] * d->q[i];
    den += w * d->G[i] * d->G[i];
  }
  return den > 0 ? num / den : 0.0;
}

int fit_model_setup(fit_model *m, flow_law_kind kind, const fit_data *d, const fluid_props *fl) {
  m->kind = kind;
  m->np = flow_law_nparams(kind);
  m->fluid = *fl;
  m->g_ref = 1.0;
  double c = darcy_slope(d), gmax = 0, qmax = 0;
  for (int i = 0; i < d->n; i++) {
    gmax = fmax(gmax, fabs(d->G[i]));
    qmax = fmax(qmax, fabs(d->q[i]));
  }
  if (!(c > 0) || !(gmax > 0) || !(qmax > 0)) return -1; /* no flow along the gradient */
  double w[d->n], x[d->n], y[d->n];
  int k = 0;
  switch (kind) {
  case LAW_DARCY:
    m->scale[0] = c;
    m->x0[0] = 1.0;
    m->lower[0] = -INFINITY;
    m->upper[0] = INFINITY;
    break;
  case LAW_THRESHOLD: {
    /* straight line q = c1 G + c0 through the points with flow; G0 = -c0/c1 */
    for (int i = 0; i < d->n; i++) {
      if (fabs(d->q[i]) < 2 * d->sigma[i]) continue; /* below the threshold (zero within noise) */
      x[k] = fabs(d->G[i]);
      y[k] = fabs(d->q[i]);
      w[k++] = 1.0 / (d->sigma[i] * d->sigma[i]);
    }
    double c1 = c, c0 = 0.0;
    if (linreg(k, x, y, w, &c1, &c0) || !(c1 > 0)) {
      c1 = c;
      c0 = 0.0;
    }
    m->scale[0] = c1;
    m->scale[1] = gmax;
    m->x0[0] = 1.0;
    m->x0[1] = -c0 / c1 / gmax;
    m->lower[0] = 1e-12;
    m->upper[0] = INFINITY;
    m->lower[1] = -INFINITY;
    m->upper[1] = 1.0; /* G0 above every data point would leave no flow at all */
    break;
  }
  case LAW_FORCHHEIMER: {
    /* G/q = a + b|q| is linear in |q| */
    for (int i = 0; i < d->n; i++) {
      if (!(fabs(d->q[i]) > 2 * d->sigma[i]) || d->G[i] * d->q[i] <= 0) continue;
      double ratio = d->G[i] / d->q[i], rel = d->sigma[i] / fabs(d->q[i]);
      x[k] = fabs(d->q[i]);
      y[k] = ratio;
      w[k] = 1.0 / (ratio * ratio * rel * rel); /* error of G/q ~ (G/q) sigma/|q| */
      k++;
    }
    double b = 0, a = 1.0 / c;
    if (linreg(k, x, y, w, &b, &a) || !(a > 0)) {
      a = 1.0 / c;
      b = 0;
    }
    m->scale[0] = a;
    m->scale[1] = a / qmax; /* the b at which inertia equals viscous drag at the largest flux */
    m->x0[0] = 1.0;
    m->x0[1] = fmax(b, 0.0) / m->scale[1];
    m->lower[0] = 1e-9;
    m->upper[0] = INFINITY;
    m->lower[1] = 0.0; /* a negative beta would make the flux undefined at large gradients */
    m->upper[1] = INFINITY;
    break;
  }
  case LAW_POWER: {
    /* log|q| = log K_ref + n log(|G|/G_ref) */
    double slog = 0;
    int np = 0;
    for (int i = 0; i < d->n; i++)
      if (fabs(d->G[i]) > 0) {
        slog += log(fabs(d->G[i]));
        np++;
      }
    m->g_ref = np ? exp(slog / np) : 1.0;
    for (int i = 0; i < d->n; i++) {
      if (!(fabs(d->q[i]) > 2 * d->sigma[i]) || d->G[i] * d->q[i] <= 0) continue;
      x[k] = log(fabs(d->G[i]) / m->g_ref);
      y[k] = log(fabs(d->q[i]));
      double rel = d->sigma[i] / fabs(d->q[i]);
      w[k++] = 1.0 / (rel * rel);
    }
    double nexp = 1.0, lk = log(c * m->g_ref);
    if (linreg(k, x, y, w, &nexp, &lk) || !(nexp > 0)) {
      nexp = 1.0;
      lk = log(c * m->g_ref);
    }
    m->scale[0] = exp(lk);
    m->scale[1] = 1.0;
    m->x0[0] = 1.0;
    m->x0[1] = nexp;
    m->lower[0] = 1e-12;
    m->upper[0] = INFINITY;
    m->lower[1] = 1e-3;
    m->upper[1] = 100.0;
    break;
  }
  default:
    return -1;
  }
  return 0;
}

double fit_model_eval(const fit_model *m, const double *x, double G, double *dqdx) {
  double s = G < 0 ? -1.0 : 1.0, aG = fabs(G), q = 0;
  switch (m->kind) {
  case LAW_DARCY:
    q = m->scale[0] * x[0] * G;
    if (dqdx) dqdx[0] = m->scale[0] * G;
    break;
  case LAW_THRESHOLD: {
    /* hinge: the derivative is one-sided at G = G0 (a kink the Gauss-Newton steps tolerate) */
    double cc = m->scale[0] * x[0], g0 = m->scale[1] * x[1], over = aG - g0;
    int on = over > 0;
    q = on ? s * cc * over : 0.0;
    if (dqdx) {
      dqdx[0] = on ? s * m->scale[0] * over : 0.0;
      dqdx[1] = on ? -s * cc * m->scale[1] : 0.0;
    }
    break;
  }
  case LAW_FORCHHEIMER: {
    double a = m->scale[0] * x[0], b = m->scale[1] * x[1];
    q = 2.0 * G / (a + sqrt(a * a + 4.0 * b * aG));
    if (dqdx) { /* implicit differentiation of a q + b q|q| = G */
      double den = a + 2.0 * b * fabs(q);
      dqdx[0] = -q / den * m->scale[0];
      dqdx[1] = -q * fabs(q) / den * m->scale[1];
    }
    break;
  }
  case LAW_POWER: {
    double kr = m->scale[0] * x[0], n = x[1];
    double r = aG / m->g_ref, p = aG > 0 ? pow(r, n) : 0.0;
    q = s * kr * p;
    if (dqdx) {
      dqdx[0] = s * m->scale[0] * p;
      dqdx[1] = aG > 0 ? q * log(r) : 0.0;
    }
    break;
  }
  default:
    break;
  }
  return q;
}

void fit_model_law(const fit_model *m, const double *x, flow_law *law, double T[2][2]) {
  const double mu = m->fluid.mu, rho = m->fluid.rho;
  law->kind = m->kind;
  law->k = law->g0 = law->beta = law->K = law->n = 0;
  T[0][0] = T[0][1] = T[1][0] = T[1][1] = 0;
  switch (m->kind) {
  case LAW_DARCY:
    law->k = mu * m->scale[0] * x[0];
    T[0][0] = mu * m->scale[0];
    break;
  case LAW_THRESHOLD:
    law->k = mu * m->scale[0] * x[0];
    law->g0 = m->scale[1] * x[1];
    T[0][0] = mu * m->scale[0];
    T[1][1] = m->scale[1];
    break;
  case LAW_FORCHHEIMER: {
    double a = m->scale[0] * x[0];
    law->k = mu / a;
    law->beta = m->scale[1] * x[1] / rho;
    T[0][0] = -mu / (a * a) * m->scale[0];
    T[1][1] = m->scale[1] / rho;
    break;
  }
  case LAW_POWER: {
    double kr = m->scale[0] * x[0], n = x[1], f = pow(m->g_ref, -n);
    law->K = kr * f;
    law->n = n;
    T[0][0] = m->scale[0] * f;
    T[0][1] = -law->K * log(m->g_ref);
    T[1][1] = 1.0;
    break;
  }
  default:
    break;
  }
}

const char *fit_param_name(flow_law_kind kind, int i) {
  static const char *names[LAW_COUNT][2] = {{"k", ""}, {"k", "G0"}, {"k", "beta"}, {"K", "n"}};
  return names[kind][i];
}

double fit_param_value(const flow_law *law, int i) {
  switch (law->kind) {
  case LAW_DARCY:
    return law->k;
  case LAW_THRESHOLD:
    return i ? law->g0 : law->k;
  case LAW_FORCHHEIMER:
    return i ? law->beta : law->k;
  case LAW_POWER:
    return i ? law->n : law->K;
  default:
    return NAN;
  }
}
