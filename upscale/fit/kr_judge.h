/* Whether a fitted relative-permeability law is a result (docs/relperm.md section 5, "When no law
 * fits"): the law is accepted only when each phase's points follow it within their errors,
 *
 *   chi2_i / dof_i <= 1 + 3 sqrt(2 / dof_i)          (i = krw, kro)
 *
 * three standard deviations of chi2/dof for Gaussian errors: the rule of `mdpore permeability`'s
 * Darcy range (campaign/campaign_linear.c). chi2_i sums the squared residuals (law - kr) / err of
 * the phase's points with an error; dof_i = n_i - (the phase's own parameters) - (the free shared
 * swc, sor) / 2, so the two phases' dof add to the fit's.
 *
 * A phase that fails is told apart by the best monotone curve through its points (weighted
 * isotonic regression: krw non-decreasing, kro non-increasing in Sw; points of equal Sw pooled),
 * whose chi2 is divided by the same dof_i: above the limit too, no monotone curve follows the rows
 * within their errors ("the rows scatter beyond their error bars"); within it, the rows are
 * consistent with some monotone curve but not with this law ("the law's shape does not follow the
 * data"). A phase without any error, or without a degree of freedom left, cannot be judged: the law
 * is then not accepted either. */
#ifndef MDPORE_UPSCALE_KR_JUDGE_H
#define MDPORE_UPSCALE_KR_JUDGE_H

#include "kr_fit.h"
#include "kr_table.h"

#define KR_JUDGE_SIGMA 3.0 /* the limit's standard deviations of chi2/dof */

typedef enum {
  KR_PHASE_PASSES = 0,
  KR_PHASE_SCATTER,   /* no monotone curve follows the rows within their errors */
  KR_PHASE_SHAPE,     /* a monotone curve does, the law does not */
  KR_PHASE_NO_ERRORS, /* no point of the phase has an error: chi2 cannot be judged */
  KR_PHASE_NO_DOF,    /* no degree of freedom left for the phase */
  KR_PHASE_NOT_FITTED /* no fit to judge */
} kr_phase_verdict;

typedef struct {
  int n;                             /* points with an error */
  double chi2, dof, chi2_dof, limit; /* limit = 1 + 3 sqrt(2 / dof) */
  double chi2_dof_monotone;          /* the best monotone curve's chi2 / dof */
  kr_phase_verdict verdict;
} kr_phase_check;

typedef struct {
  int judged;              /* a fit was there to judge */
  int accepted;            /* both phases pass */
  kr_phase_check phase[2]; /* 0: krw, 1: kro */
} kr_judgement;

/* The points of one phase (0 krw, 1 kro) that carry an error (> 0). */
int kr_phase_points_with_error(const kr_table *t, int phase);
/* Judges a fit (r->ok and r->converged); any other r gives judged = 0, accepted = 0, and the
 * phases' point counts (NO_ERRORS where a phase has none, NOT_FITTED otherwise). */
void kr_judge_fit(const kr_table *t, const kr_fit_result *r, kr_judgement *j);
/* "krw: chi2/dof = 21.3 (chi2 106.5 over 5 dof) > 2.9: the rows scatter beyond their error bars
 * (the best monotone curve through them: chi2/dof 18.2)". */
void kr_phase_text(const kr_phase_check *p, int phase, char *buf, int len);
const char *kr_verdict_name(kr_phase_verdict v); /* "passes", "scatter", "shape", ... (JSON) */

#endif
