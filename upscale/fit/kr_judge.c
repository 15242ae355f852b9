/* The per-phase goodness-of-fit check of a relative-permeability law (see kr_judge.h). */
#include "kr_judge.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "kr_isotonic.h"

static double kr_of(const kr_table *t, int phase, int i) {
  return phase ? t->kro[i] : t->krw[i];
}

static double err_of(const kr_table *t, int phase, int i) {
  return phase ? t->kro_err[i] : t->krw_err[i];
}

int kr_phase_points_with_error(const kr_table *t, int phase) {
  int n = 0;
  for (int i = 0; i < t->n; i++) n += err_of(t, phase, i) > 0;
  return n;
}

/* chi2 of the best monotone curve through the phase's points: points of equal Sw pooled first
 * (their scatter about the weighted mean counts), then weighted isotonic regression of krw (or
 * -kro) in Sw. Returns NAN when out of memory. */
static double monotone_chi2(const kr_table *t, int phase) {
  double *y = malloc((size_t)t->n * sizeof(double)), *w = malloc((size_t)t->n * sizeof(double));
  double *y0 = malloc((size_t)t->n * sizeof(double)), chi2 = 0.0;
  int *first = malloc((size_t)t->n * sizeof(int)), m = 0;
  if (!y || !w || !y0 || !first) {
    free(y), free(w), free(y0), free(first);
    return NAN;
  }
  const double sign = phase ? -1.0 : 1.0; /* kro non-increasing = -kro non-decreasing */
  for (int i = 0; i < t->n; i++) {
    const double e = err_of(t, phase, i);
    if (!(e > 0)) continue;
    const double v = sign * kr_of(t, phase, i), wi = 1.0 / (e * e);
    if (m > 0 && t->sw[i] == t->sw[first[m - 1]]) { /* same Sw: one value */
      const double mean = (w[m - 1] * y[m - 1] + wi * v) / (w[m - 1] + wi);
      chi2 += w[m - 1] * (y[m - 1] - mean) * (y[m - 1] - mean) + wi * (v - mean) * (v - mean);
      y[m - 1] = mean, w[m - 1] += wi;
      continue;
    }
    first[m] = i, y[m] = v, w[m] = wi, m++;
  }
  memcpy(y0, y, (size_t)m * sizeof(double));
  if (kr_isotonic_increasing(y, w, m) < 0) chi2 = NAN;
  for (int k = 0; k < m && isfinite(chi2); k++) chi2 += w[k] * (y[k] - y0[k]) * (y[k] - y0[k]);
  free(y), free(w), free(y0), free(first);
  return chi2;
}

void kr_judge_fit(const kr_table *t, const kr_fit_result *r, kr_judgement *j) {
  memset(j, 0, sizeof *j);
  for (int ph = 0; ph < 2; ph++) {
    kr_phase_check *p = &j->phase[ph];
    p->n = kr_phase_points_with_error(t, ph);
    p->chi2 = p->dof = p->chi2_dof = p->limit = p->chi2_dof_monotone = NAN;
    p->verdict = p->n ? KR_PHASE_NOT_FITTED : KR_PHASE_NO_ERRORS;
  }
  if (!r->ok || !r->converged) return;
  j->judged = 1;
  for (int ph = 0; ph < 2; ph++)
    if (j->phase[ph].verdict == KR_PHASE_NOT_FITTED) j->phase[ph].verdict = KR_PHASE_NO_DOF;
  const int np = kr_law_nparams(r->kind), own = (np - 2) / 2; /* per phase, besides swc and sor */
  const double shared = (!r->fixed[0] + !r->fixed[1]) / 2.0;
  for (int ph = 0; ph < 2; ph++) {
    kr_phase_check *p = &j->phase[ph];
    if (!p->n) continue;
    p->chi2 = 0.0;
    for (int i = 0; i < t->n; i++) {
      const double e = err_of(t, ph, i);
      if (!(e > 0)) continue;
      double krw, kro;
      kr_law_eval(&r->law, t->sw[i], &krw, &kro);
      const double res = ((ph ? kro : krw) - kr_of(t, ph, i)) / e;
      p->chi2 += res * res;
    }
    p->dof = p->n - own - shared;
    if (!(p->dof > 0)) continue; /* KR_PHASE_NO_DOF */
    p->chi2_dof = p->chi2 / p->dof;
    p->limit = 1.0 + KR_JUDGE_SIGMA * sqrt(2.0 / p->dof);
    p->chi2_dof_monotone = monotone_chi2(t, ph) / p->dof;
    if (p->chi2_dof <= p->limit)
      p->verdict = KR_PHASE_PASSES;
    else
      p->verdict = p->chi2_dof_monotone > p->limit ? KR_PHASE_SCATTER : KR_PHASE_SHAPE;
  }
  j->accepted = j->phase[0].verdict == KR_PHASE_PASSES && j->phase[1].verdict == KR_PHASE_PASSES;
}

const char *kr_verdict_name(kr_phase_verdict v) {
  switch (v) {
  case KR_PHASE_PASSES:
    return "passes";
  case KR_PHASE_SCATTER:
    return "rows_scatter_beyond_errors";
  case KR_PHASE_SHAPE:
    return "law_shape_does_not_follow_data";
  case KR_PHASE_NO_ERRORS:
    return "no_errors_cannot_judge";
  case KR_PHASE_NO_DOF:
    return "no_dof_cannot_judge";
  default:
    return "not_fitted";
  }
}

void kr_phase_text(const kr_phase_check *p, int phase, char *buf, int len) {
  const char *name = phase ? "kro" : "krw";
  switch (p->verdict) {
  case KR_PHASE_NO_ERRORS:
    snprintf(buf, len,
             "%s: no point has an error (no %s_err column, or every one empty or 0): chi2 "
             "cannot be judged",
             name, name);
    return;
  case KR_PHASE_NO_DOF:
    snprintf(buf, len,
             "%s: %d point(s) with an error leave no degree of freedom for the law's "
             "parameters: chi2 cannot be judged",
             name, p->n);
    return;
  case KR_PHASE_NOT_FITTED:
    snprintf(buf, len, "%s: not judged (no fit)", name);
    return;
  default:
    break;
  }
  const int n =
      snprintf(buf, len, "%s: chi2/dof = %.3g (chi2 %.4g over %.3g dof) %s %.3g", name, p->chi2_dof,
               p->chi2, p->dof, p->verdict == KR_PHASE_PASSES ? "<=" : ">", p->limit);
  if (n >= len) return;
  if (p->verdict == KR_PHASE_PASSES)
    snprintf(buf + n, len - n, ": passes");
  else
    snprintf(buf + n, len - n, ": %s (the best monotone curve through the points: chi2/dof %.3g)",
             p->verdict == KR_PHASE_SCATTER ? "the rows scatter beyond their error bars"
                                            : "the law's shape does not follow the data",
             p->chi2_dof_monotone);
}
