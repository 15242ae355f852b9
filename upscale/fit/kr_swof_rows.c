/* The rows of the SWOF export (see kr_swof.h): law grid or measured points, kr > 1 clipped,
 * Pcow from the capillary-pressure curve. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "kr_isotonic.h"
#include "kr_swof.h"

#define BOLTZMANN_J_PER_K 1.380649e-23
#define PA_PER_BAR 1.0e5
#define DEFAULT_TEMPERATURE_K 298.0 /* the reduced-unit mapping of ../reference/physics.md */

static int alloc_rows(kr_swof *s, int n) {
  s->sw = calloc((size_t)n, sizeof(double));
  s->krw = calloc((size_t)n, sizeof(double));
  s->krow = calloc((size_t)n, sizeof(double));
  s->pcow = calloc((size_t)n, sizeof(double));
  return s->sw && s->krw && s->krow && s->pcow ? 0 : -1;
}

/* The measured rows: end rows from the law at swc (if below the first point) and at Sw = 1 (if
 * above the last), rows of equal Sw merged, krw made non-decreasing and krow non-increasing. */
static int measured_rows(const kr_table *t, const kr_law *law, kr_swof *s) {
  const double swc = law->p[0];
  const int head = swc < t->sw[0], tail = t->sw[t->n - 1] < 1.0;
  const int cap = t->n + head + tail;
  if (alloc_rows(s, cap)) return -1;
  double *ww = calloc((size_t)cap, sizeof(double)), *wo = calloc((size_t)cap, sizeof(double));
  double wmax = 1.0;
  if (!ww || !wo) {
    free(ww), free(wo);
    return -1;
  }
  for (int i = 0; i < t->n; i++) {
    if (t->krw_err[i] > 0) wmax = fmax(wmax, 1.0 / (t->krw_err[i] * t->krw_err[i]));
    if (t->kro_err[i] > 0) wmax = fmax(wmax, 1.0 / (t->kro_err[i] * t->kro_err[i]));
  }
  int n = 0;
  if (head) {
    s->sw[n] = swc, ww[n] = wo[n] = wmax;
    kr_law_eval(law, swc, &s->krw[n], &s->krow[n]);
    s->krw[n++] = 0.0;
  }
  for (int i = 0; i < t->n; i++) {
    const double w1 = t->krw_err[i] > 0 ? 1.0 / (t->krw_err[i] * t->krw_err[i]) : 1.0;
    const double w2 = t->kro_err[i] > 0 ? 1.0 / (t->kro_err[i] * t->kro_err[i]) : 1.0;
    if (n > 0 && t->sw[i] == s->sw[n - 1]) { /* same Sw: weighted mean */
      s->krw[n - 1] = (ww[n - 1] * s->krw[n - 1] + w1 * t->krw[i]) / (ww[n - 1] + w1);
      s->krow[n - 1] = (wo[n - 1] * s->krow[n - 1] + w2 * t->kro[i]) / (wo[n - 1] + w2);
      ww[n - 1] += w1, wo[n - 1] += w2;
      continue;
    }
    s->sw[n] = t->sw[i], s->krw[n] = t->krw[i], s->krow[n] = t->kro[i];
    ww[n] = w1, wo[n] = w2, n++;
  }
  if (tail) {
    s->sw[n] = 1.0, ww[n] = wo[n] = wmax;
    kr_law_eval(law, 1.0, &s->krw[n], &s->krow[n]);
    s->krow[n++] = 0.0;
  }
  s->n = n;
  /* krow non-increasing = -krow non-decreasing */
  for (int i = 0; i < n; i++) s->krow[i] = -s->krow[i];
  const int mw = kr_isotonic_increasing(s->krw, ww, n), mo = kr_isotonic_increasing(s->krow, wo, n);
  if (mw < 0 || mo < 0) {
    free(ww), free(wo);
    return -1;
  }
  s->n_isotonic = mw + mo;
  for (int i = 0; i < n; i++) {
    s->krow[i] = -s->krow[i];
    s->krw[i] = fmax(s->krw[i], 0.0); /* noise below 0 (kr_table.h keeps it within 3 errors) */
    s->krow[i] = fmax(s->krow[i], 0.0);
  }
  s->krw[0] = 0.0; /* krw = 0 at the first row and krow = 0 at the last, as simulators expect */
  s->krow[n - 1] = 0.0; /* (already so at the law's end rows; kept monotone by construction) */
  free(ww), free(wo);
  return 0;
}

/* The measured rows without a law (no law accepted): rows of equal Sw merged, krw made
 * non-decreasing and krow non-increasing by weighted isotonic regression, then an end row at Sw = 0
 * (krw = 0: no water, no water flow; krow the first row's, held) and one at Sw = 1 (krow = 0; krw
 * the last row's, held) where the table does not reach them. A table that starts at Sw = 0 has
 * krw = 0 set there, the measured value kept for the header. */
static int measured_rows_no_law(const kr_table *t, kr_swof *s) {
  const int head = t->sw[0] >= KR_SWOF_SW_RESOLUTION,
            tail = t->sw[t->n - 1] <= 1.0 - KR_SWOF_SW_RESOLUTION;
  const int cap = t->n + head + tail;
  if (alloc_rows(s, cap)) return -1;
  double *ww = calloc((size_t)cap, sizeof(double)), *wo = calloc((size_t)cap, sizeof(double));
  if (!ww || !wo) {
    free(ww), free(wo);
    return -1;
  }
  int n = head; /* the measured rows from index `head` on */
  for (int i = 0; i < t->n; i++) {
    const double w1 = t->krw_err[i] > 0 ? 1.0 / (t->krw_err[i] * t->krw_err[i]) : 1.0;
    const double w2 = t->kro_err[i] > 0 ? 1.0 / (t->kro_err[i] * t->kro_err[i]) : 1.0;
    if (n > head && t->sw[i] == s->sw[n - 1]) { /* same Sw: weighted mean */
      s->krw[n - 1] = (ww[n - 1] * s->krw[n - 1] + w1 * t->krw[i]) / (ww[n - 1] + w1);
      s->krow[n - 1] = (wo[n - 1] * s->krow[n - 1] - w2 * t->kro[i]) / (wo[n - 1] + w2);
      ww[n - 1] += w1, wo[n - 1] += w2;
      continue;
    }
    s->sw[n] = t->sw[i], s->krw[n] = t->krw[i], s->krow[n] = -t->kro[i]; /* -kro: see below */
    ww[n] = w1, wo[n] = w2, n++;
  }
  const int m = n - head; /* measured rows after merging */
  const int mw = kr_isotonic_increasing(s->krw + head, ww + head, m);
  const int mo = kr_isotonic_increasing(s->krow + head, wo + head, m);
  free(ww), free(wo);
  if (mw < 0 || mo < 0) return -1;
  s->n_isotonic = mw + mo;
  for (int i = head; i < n; i++) {
    s->krow[i] = fmax(-s->krow[i], 0.0); /* noise below 0 (kr_table.h keeps it within 3 errors) */
    s->krw[i] = fmax(s->krw[i], 0.0);
  }
  if (head) {
    s->sw[0] = 0.0, s->krw[0] = 0.0, s->krow[0] = s->krow[1];
  } else {
    s->first_krw_measured = s->krw[0]; /* the table starts at Sw = 0 */
    s->krw[0] = 0.0;
  }
  if (tail) {
    s->sw[n] = 1.0, s->krw[n] = s->krw[n - 1], s->krow[n] = 0.0;
    n++;
  } else {
    s->last_krow_measured = s->krow[n - 1];
    s->krow[n - 1] = 0.0;
  }
  s->n = n;
  s->head_row = head, s->tail_row = tail;
  return 0;
}

static int law_rows(const kr_law *law, int rows, kr_swof *s) {
  const double swc = law->p[0], sor = law->p[1], span = 1.0 - swc - sor;
  const int tail = sor > 0;
  if (alloc_rows(s, rows + tail)) return -1;
  for (int k = 0; k < rows; k++) {
    s->sw[k] = k == rows - 1 ? 1.0 - sor : swc + span * k / (rows - 1.0);
    kr_law_eval(law, s->sw[k], &s->krw[k], &s->krow[k]);
  }
  s->krw[0] = 0.0, s->krow[rows - 1] = 0.0; /* Se = 0 and 1 exactly (rounding of swc + 0) */
  if (tail) {
    s->sw[rows] = 1.0;
    s->krw[rows] = s->krw[rows - 1];
    s->krow[rows] = 0.0;
  }
  s->n = rows + tail;
  s->grid_rows = rows;
  s->tail_row = tail;
  return 0;
}

static void clip_rows(kr_swof *s) {
  s->kr_peak = 0.0;
  for (int i = 0; i < s->n; i++) {
    s->kr_peak = fmax(s->kr_peak, fmax(s->krw[i], s->krow[i]));
    if (s->krw[i] <= 1.0 && s->krow[i] <= 1.0) continue;
    if (s->n_clipped < KR_SWOF_MAX_CLIPPED) {
      s->clipped_row[s->n_clipped] = i;
      s->clipped_krw[s->n_clipped] = s->krw[i];
      s->clipped_krow[s->n_clipped] = s->krow[i];
    }
    s->n_clipped++;
    s->krw[i] = fmin(s->krw[i], 1.0);
    s->krow[i] = fmin(s->krow[i], 1.0);
  }
}

/* bar per unit of the Pc curve: Pa -> bar, or reduced kT/rc^3 -> bar when rc is known. */
static void pc_scale(const kr_table *t, const pc_curve *pc, kr_swof *s) {
  const double T = isfinite(t->temperature_K) ? t->temperature_K : DEFAULT_TEMPERATURE_K;
  s->pc_pa_per_reduced =
      isfinite(t->rc_m) && t->rc_m > 0 ? BOLTZMANN_J_PER_K * T / pow(t->rc_m, 3) : NAN;
  if (!pc)
    s->pc_bar_factor = 1.0 / PA_PER_BAR; /* Pcow = 0 in any unit */
  else if (pc->in_pa)
    s->pc_bar_factor = 1.0 / PA_PER_BAR;
  else
    s->pc_bar_factor = s->pc_pa_per_reduced / PA_PER_BAR; /* NAN: stays in reduced units */
}

int kr_swof_build(const kr_table *t, const kr_law *law, int rows, int measured, const pc_curve *pc,
                  kr_swof *s, char *err, int errlen) {
  memset(s, 0, sizeof *s);
  s->no_law = !law;
  s->measured = measured || !law;
  s->first_krw_measured = s->last_krow_measured = NAN;
  if (!measured && rows < 2) {
    snprintf(err, errlen, "--swof-rows: expected at least 2 rows (got %d)", rows);
    return -1;
  }
  if (!law       ? measured_rows_no_law(t, s)
      : measured ? measured_rows(t, law, s)
                 : law_rows(law, rows, s)) {
    snprintf(err, errlen, "out of memory building the SWOF rows");
    kr_swof_free(s);
    return -1;
  }
  for (int i = 1; i < s->n; i++)
    if (!(s->sw[i] > s->sw[i - 1])) {
      snprintf(err, errlen,
               "the SWOF rows' Sw are not strictly increasing (%.9g after %.9g): swc and sor of "
               "the fitted law leave no saturation range",
               s->sw[i], s->sw[i - 1]);
      kr_swof_free(s);
      return -1;
    }
  clip_rows(s);
  pc_scale(t, pc, s);
  const double f = isfinite(s->pc_bar_factor) ? s->pc_bar_factor : 1.0;
  for (int i = 0; i < s->n; i++) {
    s->pcow[i] = pc ? f * pc_curve_at(pc, s->sw[i]) : 0.0;
    if (i > 0 && s->pcow[i] > s->pcow[i - 1]) { /* SWOF: Pcow non-increasing with Sw */
      s->pcow[i] = s->pcow[i - 1];
      s->n_pc_levelled++;
    }
  }
  return 0;
}

void kr_swof_free(kr_swof *s) {
  free(s->sw), free(s->krw), free(s->krow), free(s->pcow);
  s->sw = s->krw = s->krow = s->pcow = NULL;
  s->n = 0;
}
