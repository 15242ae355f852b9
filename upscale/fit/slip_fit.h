/* The slip length b fitted to permeabilities of one pore shape at several sizes (`mdpore slip`,
 * docs/permeability.md "Slip and apparent permeability"): weighted least squares of
 *
 *   k_i = a k_noslip(h_i) F(b / h_i)        (slip_law.h; a = 1 unless --free-scale)
 *
 * with weights 1 / k_err_i^2. Plain C (no PETSc): Gauss-Newton on one or two parameters. The
 * navier model with a = 1 is linear in b, so the first step is the exact closed-form solution
 *   b = sum w x (y - 1) / sum w x^2,  err(b) = 1 / sqrt(sum w x^2),  x = c / h, y = k / k_noslip. */
#ifndef MDPORE_UPSCALE_SLIP_FIT_H
#define MDPORE_UPSCALE_SLIP_FIT_H

#include "law/slip_law.h"

#define SLIP_SOURCE_LEN 512

typedef struct {
  double h;                     /* pore size: slit width or tube radius, length units */
  double k, k_err;              /* superficial permeability and its standard error */
  double porosity;              /* phi of the sample (1: k is per pore area) */
  char source[SLIP_SOURCE_LEN]; /* where the point was read: "FILE:LINE" or "FILE" */
  double rc_m;                  /* metres per length unit, NaN when unknown */
} slip_point;

typedef struct {
  slip_shape shape;
  slip_model model;
  int free_scale; /* 1: fit a as well (a viscosity or density mismatch common to every size) */
} slip_setup;

typedef struct {
  int n, npar, dof, iterations;
  double b, b_err;       /* slip length and its standard error from the input errors */
  double b_err_scaled;   /* b_err x sqrt(chi2/dof) when chi2/dof > 1 (Birge), else b_err */
  double a, a_err;       /* scale (1, err 0 without --free-scale) */
  double cov_ab;         /* covariance of a and b (0 without --free-scale) */
  double chi2, chi2_dof; /* NaN when dof = 0 (as many points as parameters) */
} slip_result;

/* Checks the points for a fit: at least as many as parameters, h > 0, k > 0, k_err > 0 and
 * porosity in (0, 1], all finite, and two distinct sizes with --free-scale. -1 with a message
 * naming the point's source and the key on a failure. */
int slip_check_points(const slip_point *p, int n, const slip_setup *s, char *err, int len);

/* Fits b (and a). 0, or -1 with a message (no convergence, b outside the model's range). */
int slip_fit(const slip_point *p, int n, const slip_setup *s, slip_result *r, char *err, int len);

/* The model's k_app / k_noslip at size h and its standard error from the fit's covariance. */
double slip_model_ratio(const slip_setup *s, const slip_result *r, double h, double *err);

#endif
