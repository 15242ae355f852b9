/* Relative-permeability law fits (see kr_fit.h). */
#include "kr_fit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lsq_tao.h"

/* A parameter within this distance of a bound (relative to max(1, |bound|)) is at the bound. */
#define KR_AT_BOUND_TOL 1e-6
/* Bounds of the shape parameters: exponents (Corey n, LET L and T) and LET's E. */
#define KR_EXP_MIN 0.5
#define KR_EXP_MAX 12.0
#define KR_LET_T_MIN 0.1
#define KR_LET_E_MIN 1e-3
#define KR_LET_E_MAX 1e3
#define KR_MAX_MAX 10.0
/* Gauss-Newton iterations per start: LET's nearly flat directions (E against L and T) take many. */
#define KR_MAX_ITERATIONS 2000

typedef struct {
  kr_law_kind kind;
  int n;           /* points */
  double *sw;      /* saturation of each point */
  int *phase;      /* 0: krw, 1: kro */
  double *y, *sig; /* kr and its error */
  int nfree;
  int free_idx[KR_MAX_PARAMS]; /* law parameter of each fit parameter */
  kr_law base;                 /* fixed values */
} kr_problem;

/* LET's E is fitted as ln E (it spans decades); everything else as it is. */
static int is_log_param(kr_law_kind kind, int p) {
  return kind == KR_LET && (p == 4 || p == 8);
}

static void x_to_law(const kr_problem *pb, const double *x, kr_law *law) {
  *law = pb->base;
  for (int k = 0; k < pb->nfree; k++) {
    const int p = pb->free_idx[k];
    law->p[p] = is_log_param(pb->kind, p) ? exp(x[k]) : x[k];
  }
}

/* The model for lsq_tao.h: kr of point i and its derivatives (kr_law_eval_grad; d/d ln E =
 * E d/dE). */
static double kr_model(const double *x, int i, double *grad, void *ctx) {
  const kr_problem *pb = ctx;
  kr_law law;
  double krw, kro, dkrw[KR_MAX_PARAMS], dkro[KR_MAX_PARAMS];
  x_to_law(pb, x, &law);
  kr_law_eval_grad(&law, pb->sw[i], &krw, &kro, dkrw, dkro);
  const double *d = pb->phase[i] ? dkro : dkrw;
  if (grad)
    for (int k = 0; k < pb->nfree; k++) {
      const int p = pb->free_idx[k];
      grad[k] = is_log_param(pb->kind, p) ? d[p] * law.p[p] : d[p];
    }
  return pb->phase[i] ? kro : krw;
}

/* The points with an error (> 0), and the data-set bounds of swc and sor. */
static int build_points(const kr_table *t, kr_problem *pb, kr_fit_result *r, double *swc_hi,
                        double *sor_hi) {
  pb->sw = malloc(2 * (size_t)t->n * sizeof(double));
  pb->y = malloc(2 * (size_t)t->n * sizeof(double));
  pb->sig = malloc(2 * (size_t)t->n * sizeof(double));
  pb->phase = malloc(2 * (size_t)t->n * sizeof(int));
  if (!pb->sw || !pb->y || !pb->sig || !pb->phase) return -1;
  double sw_w = INFINITY, sw_o = -INFINITY; /* lowest Sw where water flows, highest for oil */
  for (int i = 0; i < t->n; i++)
    for (int ph = 0; ph < 2; ph++) {
      const double kr = ph ? t->kro[i] : t->krw[i], e = ph ? t->kro_err[i] : t->krw_err[i];
      if (!(e > 0)) {
        ++*(ph ? &r->left_out_kro : &r->left_out_krw);
        continue;
      }
      if (kr > KR_NEGATIVE_SIGMA * e) {
        if (ph)
          sw_o = fmax(sw_o, t->sw[i]);
        else
          sw_w = fmin(sw_w, t->sw[i]);
      }
      pb->sw[pb->n] = t->sw[i];
      pb->y[pb->n] = kr;
      pb->sig[pb->n] = e;
      pb->phase[pb->n] = ph;
      ++*(ph ? &r->n_kro : &r->n_krw);
      pb->n++;
    }
  *swc_hi = sw_w;
  *sor_hi = 1.0 - sw_o;
  return 0;
}

static void problem_free(kr_problem *pb) {
  free(pb->sw);
  free(pb->y);
  free(pb->sig);
  free(pb->phase);
}

/* Bounds of every law parameter (reported values). */
static void set_bounds(kr_fit_result *r, double swc_hi, double sor_hi) {
  const int np = kr_law_nparams(r->kind);
  for (int p = 0; p < np; p++) r->lower[p] = KR_EXP_MIN, r->upper[p] = KR_EXP_MAX;
  r->lower[0] = 0.0, r->upper[0] = swc_hi * (1 - 1e-9);
  r->lower[1] = 0.0, r->upper[1] = sor_hi * (1 - 1e-9);
  r->lower[2] = 1e-6, r->upper[2] = KR_MAX_MAX;
  const int omax = r->kind == KR_COREY ? 4 : 6;
  r->lower[omax] = 1e-6, r->upper[omax] = KR_MAX_MAX;
  if (r->kind == KR_LET) {
    r->lower[4] = r->lower[8] = KR_LET_E_MIN;
    r->upper[4] = r->upper[8] = KR_LET_E_MAX;
    r->lower[5] = r->lower[9] = KR_LET_T_MIN;
  }
}

/* Starting points: swc and sor at two fractions of their ranges; shapes at Corey 2 (Corey) or
 * three LET shapes about the given Corey exponents. Returns the count. */
static int starts(const kr_fit_result *r, const kr_law *corey, double krw_top, double kro_top,
                  kr_law *s) {
  int n = 0;
  const double frac[2] = {0.1, 0.6};
  if (r->kind == KR_COREY) {
    for (int a = 0; a < 2; a++) {
      kr_law *l = &s[n++];
      l->kind = KR_COREY;
      l->p[0] = frac[a] * r->upper[0];
      l->p[1] = frac[a] * r->upper[1];
      l->p[2] = krw_top, l->p[3] = 2.0, l->p[4] = kro_top, l->p[5] = 2.0;
    }
    return n;
  }
  const double shapes[3][3] = {{0, 1.0, 1.0}, {2.0, 0.3, 2.0}, {0, 3.0, 0.5}};
  for (int a = 0; a < 3; a++) {
    kr_law *l = &s[n++];
    l->kind = KR_LET;
    l->p[0] = corey ? corey->p[0] : frac[0] * r->upper[0];
    l->p[1] = corey ? corey->p[1] : frac[0] * r->upper[1];
    l->p[2] = corey ? corey->p[2] : krw_top;
    l->p[6] = corey ? corey->p[4] : kro_top;
    l->p[3] = shapes[a][0] > 0 ? shapes[a][0] : corey ? corey->p[3] : 2.0;
    l->p[7] = shapes[a][0] > 0 ? shapes[a][0] : corey ? corey->p[5] : 2.0;
    l->p[4] = l->p[8] = shapes[a][1];
    l->p[5] = l->p[9] = shapes[a][2];
  }
  return n;
}

static double clampd(double v, double lo, double hi) {
  return v < lo ? lo : v > hi ? hi : v;
}

/* Covariance of the parameters that are free and not at a bound: standard errors into r->se. */
static int errors(kr_problem *pb, kr_fit_result *r, const double *x) {
  const int np = kr_law_nparams(r->kind);
  int use[KR_MAX_PARAMS], nu = 0; /* fit-vector indices kept */
  for (int k = 0; k < pb->nfree; k++)
    if (!r->at_bound[pb->free_idx[k]]) use[nu++] = k;
  for (int p = 0; p < np; p++) r->se[p] = 0.0;
  if (nu == 0) return 0;
  /* the reduced problem: parameters at a bound join the fixed ones */
  kr_problem red = *pb;
  x_to_law(pb, x, &red.base);
  red.nfree = nu;
  double xr[KR_MAX_PARAMS], A[KR_MAX_PARAMS * KR_MAX_PARAMS], C[KR_MAX_PARAMS * KR_MAX_PARAMS];
  for (int k = 0; k < nu; k++) {
    red.free_idx[k] = pb->free_idx[use[k]];
    xr[k] = x[use[k]];
  }
  const lsq_problem lp = {red.n, nu, red.y, red.sig, kr_model, &red, xr, NULL, NULL, 0};
  lsq_chi2(&lp, xr, A);
  if (lsq_invert(A, nu, C)) return -1;
  for (int k = 0; k < nu; k++) {
    const int p = red.free_idx[k];
    const double dpdx = is_log_param(r->kind, p) ? r->law.p[p] : 1.0; /* E = exp(x) */
    r->se[p] = sqrt(fmax(C[k * nu + k], 0.0)) * dpdx;
  }
  return 0;
}

int kr_fit_law(const kr_table *t, kr_law_kind kind, const kr_fit_opts *o, kr_fit_result *r) {
  memset(r, 0, sizeof *r);
  r->kind = kind;
  const int np = kr_law_nparams(kind);
  kr_problem pb = {0};
  pb.kind = kind;
  double swc_hi, sor_hi;
  if (build_points(t, &pb, r, &swc_hi, &sor_hi)) {
    snprintf(r->why, sizeof r->why, "out of memory");
    problem_free(&pb);
    return -1;
  }
  r->fixed[0] = isfinite(o->swc);
  r->fixed[1] = isfinite(o->sor);
  r->n_free = np - r->fixed[0] - r->fixed[1];
  r->n_points = pb.n;
  if (pb.n <= r->n_free) {
    snprintf(r->why, sizeof r->why,
             "%d kr points with an error (%d krw, %d kro from %d rows) cannot fit the %d free "
             "parameters of the %s law with a degree of freedom left",
             pb.n, r->n_krw, r->n_kro, t->n, r->n_free, kr_law_name(kind));
    problem_free(&pb);
    return -1;
  }
  if (!isfinite(swc_hi) || !(sor_hi < 1.0)) {
    snprintf(r->why, sizeof r->why,
             "no row where %s flows (kr more than %g errors above 0): the law's end points are "
             "not determined",
             !isfinite(swc_hi) ? "water" : "oil", KR_NEGATIVE_SIGMA);
    problem_free(&pb);
    return -1;
  }
  set_bounds(r, swc_hi, sor_hi);
  if (r->fixed[0]) r->lower[0] = r->upper[0] = o->swc;
  if (r->fixed[1]) r->lower[1] = r->upper[1] = o->sor;
  double krw_top = 0.05, kro_top = 0.05;
  for (int i = 0; i < pb.n; i++) {
    if (pb.phase[i])
      kro_top = fmax(kro_top, pb.y[i]);
    else
      krw_top = fmax(krw_top, pb.y[i]);
  }
  /* LET starts from the Corey fit of the same data */
  kr_law corey_law, *corey = NULL;
  if (kind == KR_LET && o->corey_start)
    corey_law = *o->corey_start, corey = &corey_law;
  else if (kind == KR_LET) {
    kr_fit_result rc;
    if (!kr_fit_law(t, KR_COREY, o, &rc)) corey_law = rc.law, corey = &corey_law;
  }
  kr_law s[4];
  const int ns = starts(r, corey, 1.1 * krw_top, 1.1 * kro_top, s);
  for (int p = 0; p < np; p++)
    if (!r->fixed[p]) pb.free_idx[pb.nfree++] = p;
  pb.base = s[0];
  if (r->fixed[0]) pb.base.p[0] = o->swc;
  if (r->fixed[1]) pb.base.p[1] = o->sor;
  double lo[KR_MAX_PARAMS], hi[KR_MAX_PARAMS], best_x[KR_MAX_PARAMS];
  for (int k = 0; k < pb.nfree; k++) {
    const int p = pb.free_idx[k];
    lo[k] = is_log_param(kind, p) ? log(r->lower[p]) : r->lower[p];
    hi[k] = is_log_param(kind, p) ? log(r->upper[p]) : r->upper[p];
  }
  double best_chi2 = INFINITY, best_converged = INFINITY;
  int best_reason = 0;
  for (int a = 0; a < ns; a++) {
    double x0[KR_MAX_PARAMS], x[KR_MAX_PARAMS];
    for (int k = 0; k < pb.nfree; k++) {
      const int p = pb.free_idx[k];
      const double v = clampd(s[a].p[p], r->lower[p], r->upper[p]);
      x0[k] = is_log_param(kind, p) ? log(v) : v;
    }
    lsq_problem lp = {pb.n, pb.nfree, pb.y, pb.sig, kr_model, &pb, x0, lo, hi, KR_MAX_ITERATIONS};
    int reason = 0, its = 0;
    if (lsq_tao_solve(&lp, x, &reason, &its)) continue;
    const double c2 = lsq_chi2(&lp, x, NULL);
    r->starts++;
    if (!isfinite(c2)) continue;
    if (reason > 0) best_converged = fmin(best_converged, c2);
    if (c2 < best_chi2) {
      best_chi2 = c2, best_reason = reason, r->iterations = its;
      memcpy(best_x, x, sizeof x);
    }
  }
  /* a start that stopped short of TAO's tolerance at the optimum another start converged to */
  if (best_reason <= 0 && best_converged <= best_chi2 * (1 + 1e-6) + 1e-9) best_reason = 1;
  if (!isfinite(best_chi2)) {
    snprintf(r->why, sizeof r->why, "TAO failed from every start");
    problem_free(&pb);
    return -1;
  }
  r->ok = 1;
  r->converged = best_reason > 0;
  if (!r->converged)
    snprintf(r->why, sizeof r->why, "TAO did not converge (reason %d)", best_reason);
  x_to_law(&pb, best_x, &r->law);
  for (int k = 0; k < pb.nfree; k++) {
    const int p = pb.free_idx[k];
    const double x = best_x[k];
    r->at_bound[p] = x - lo[k] <= KR_AT_BOUND_TOL * fmax(1.0, fabs(lo[k])) ||
                     hi[k] - x <= KR_AT_BOUND_TOL * fmax(1.0, fabs(hi[k]));
  }
  r->chi2 = best_chi2;
  r->dof = pb.n - r->n_free;
  r->chi2_dof = r->chi2 / r->dof;
  r->bic = r->chi2 + r->n_free * log((double)pb.n);
  r->inflation = r->chi2_dof > 1.0 ? sqrt(r->chi2_dof) : 1.0;
  if (errors(&pb, r, best_x)) {
    r->ok = r->converged = 0;
    snprintf(r->why, sizeof r->why,
             "the data do not determine the %s law's parameters (singular normal matrix at the "
             "optimum)",
             kr_law_name(kind));
    problem_free(&pb);
    return -1;
  }
  for (int p = 0; p < np; p++) r->se_inflated[p] = r->se[p] * r->inflation;
  problem_free(&pb);
  return 0;
}
