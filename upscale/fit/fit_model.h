/* One candidate law as a least-squares model: q = f(G; x) in scaled internal parameters x (each of
 * order one at the initial guess), and the map from x to the physical law parameters.
 *
 *   darcy        x0 -> c = k/mu                          law: k = mu c
 *   threshold    x0 -> c, x1 -> G0; q = c max(|G|-G0, 0) law: k = mu c, G0
 *   forchheimer  x0 -> a = mu/k, x1 -> b = beta rho; q solves a q + b q|q| = G
 *   power        x0 -> K_ref, x1 -> n; q = K_ref (|G|/G_ref)^n, so K = K_ref G_ref^-n
 */
#ifndef MDPORE_UPSCALE_FIT_MODEL_H
#define MDPORE_UPSCALE_FIT_MODEL_H

#include "law/flow_law.h"

typedef struct {
  int n;
  const double *G, *q, *sigma;
} fit_data;

typedef struct {
  flow_law_kind kind;
  int np;
  fluid_props fluid;
  double scale[2];           /* physical internal parameter = scale * x */
  double g_ref;              /* power law reference gradient (geometric mean of |G|) */
  double x0[2];              /* initial guess in x */
  double lower[2], upper[2]; /* bounds in x */
} fit_model;

/* Sets up the model for the data: scales, initial guess from linear fits, bounds.
 * Returns -1 if the data cannot support this law (e.g. no positive flux for the power law). */
int fit_model_setup(fit_model *m, flow_law_kind kind, const fit_data *d, const fluid_props *fl);

/* q(G; x) and, if dqdx is not NULL, dq/dx_j. */
double fit_model_eval(const fit_model *m, const double *x, double G, double *dqdx);

/* The physical law for x, and T[i][j] = d theta_i / d x_j for the covariance transform, where theta
 * are the reported parameters (darcy: k; threshold: k, G0; forchheimer: k, beta; power: K, n). */
void fit_model_law(const fit_model *m, const double *x, flow_law *law, double T[2][2]);

/* Names and values of the reported parameters of a law. */
const char *fit_param_name(flow_law_kind kind, int i);
double fit_param_value(const flow_law *law, int i);

#endif
