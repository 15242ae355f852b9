/* Writes the SWOF file (see kr_swof.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "common/atomic_file.h"
#include "kr_swof.h"

/* Comment lines: "-- " + text, long texts wrapped at about 100 columns. */
static void comment(FILE *f, const char *text) {
  const int width = 96;
  int len = (int)strlen(text);
  while (len > width) {
    int cut = width;
    while (cut > 40 && text[cut] != ' ') cut--;
    fprintf(f, "-- %.*s\n", cut, text);
    text += cut + (text[cut] == ' ');
    len = (int)strlen(text);
  }
  fprintf(f, "-- %s\n", text);
}

static void pc_header(FILE *f, const kr_swof *s, const pc_curve *pc) {
  char buf[600];
  if (!pc) {
    comment(f, "Pcow: 0 on every row (no capillary-pressure curve given: mdpore fit relperm "
               "--pc-morph pc_morph.csv sets it)");
    return;
  }
  snprintf(buf, sizeof buf,
           "Pcow = p_o - p_w from the morphological drainage curve %.300s (%d points of different "
           "Sw, %d row(s) of equal Sw merged keeping the largest Pc; linear interpolation, "
           "constant beyond Sw = %.4g .. %.4g)",
           pc->path, pc->n, pc->merged, pc->sw[0], pc->sw[pc->n - 1]);
  comment(f, buf);
  if (pc->in_pa)
    comment(f, "Pcow in bar (the curve's pc_Pa column / 1e5)");
  else if (isfinite(s->pc_bar_factor)) {
    snprintf(buf, sizeof buf,
             "Pcow in bar: the curve's reduced pc x kT/rc^3 = %.6g Pa (rc and T from the kr "
             "table's rc_m and temperature_K, T = 298 K when not given) / 1e5",
             s->pc_pa_per_reduced);
    comment(f, buf);
  } else
    comment(f, "Pcow in REDUCED units (kT/rc^3): the kr table gives no rc_m, so the scale is "
               "unknown; to convert to bar multiply by 1.380649e-28 T / rc^3 (T in K, rc in m)");
  if (s->n_pc_levelled) {
    snprintf(buf, sizeof buf,
             "%d Pcow value(s) lowered to the row above to keep Pcow non-increasing in Sw",
             s->n_pc_levelled);
    comment(f, buf);
  }
}

static void clip_header(FILE *f, const kr_swof *s) {
  char buf[300];
  if (!s->n_clipped) {
    comment(f, "kr > 1 policy: kr is clipped to 1 (none was above 1 here)");
    return;
  }
  snprintf(buf, sizeof buf,
           "kr > 1 policy: kr is clipped to 1 (OPM Flow reports krw or krow above 1 in SWOF as an "
           "error; mdpore darcy refuses it). %d row(s) clipped, unclipped peak kr = %.6g:",
           s->n_clipped, s->kr_peak);
  comment(f, buf);
  for (int c = 0; c < s->n_clipped && c < KR_SWOF_MAX_CLIPPED; c++) {
    const int i = s->clipped_row[c];
    snprintf(buf, sizeof buf, "  row %d: Sw = %.6f  krw %.6g -> %.6g  krow %.6g -> %.6g", i + 1,
             s->sw[i], s->clipped_krw[c], s->krw[i], s->clipped_krow[c], s->krow[i]);
    comment(f, buf);
  }
  if (s->n_clipped > KR_SWOF_MAX_CLIPPED) comment(f, "  (more rows not listed)");
  snprintf(buf, sizeof buf,
           "to keep the mobilities exact instead: divide krw and krow by %.6g and multiply the "
           "permeability (PERMX...) by %.6g",
           s->kr_peak, s->kr_peak);
  comment(f, buf);
}

int kr_swof_write(const char *path, const kr_swof *s, const kr_table *t, const pc_curve *pc,
                  const char *law_text, const char *choice, char *err, int errlen) {
  char tmp[4200], buf[3200];
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) {
    snprintf(err, errlen, "%s: cannot write the SWOF table", path);
    return -1;
  }
  comment(f, "SWOF table written by mdpore fit relperm (docs/relperm.md section 5)");
  snprintf(buf, sizeof buf, "source: %.500s (%d rows)", t->path, t->n);
  comment(f, buf);
  for (int i = 0; i < t->n_comments; i++) {
    snprintf(buf, sizeof buf, "  source: %.1000s", t->comments[i]);
    comment(f, buf);
  }
  snprintf(buf, sizeof buf, "law: %s", law_text);
  comment(f, buf);
  if (choice && *choice) {
    snprintf(buf, sizeof buf, "law choice: %.1000s", choice);
    comment(f, buf);
  }
  if (s->no_law) {
    int k = snprintf(
        buf, sizeof buf,
        "rows: THE MEASURED POINTS, NOT A LAW (no law is accepted: the reason above): "
        "the %d rows of the table, krw made non-decreasing and krow non-increasing by weighted "
        "isotonic regression (%d value(s) moved)",
        t->n, s->n_isotonic);
    if (s->head_row)
      k += snprintf(buf + k, sizeof buf - k,
                    "; first row Sw = 0 added (krw = 0; krow held from the first measured row)");
    else
      k += snprintf(buf + k, sizeof buf - k, "; the first row's krw %.6g set to 0",
                    s->first_krw_measured);
    if (s->tail_row)
      snprintf(buf + k, sizeof buf - k,
               "; last row Sw = 1 added (krow = 0; krw held from the last measured row)");
    else
      snprintf(buf + k, sizeof buf - k, "; the last row's krow %.6g set to 0",
               s->last_krow_measured);
  } else if (s->measured)
    snprintf(
        buf, sizeof buf,
        "rows: the %d measured points (Sw from particle counts), krw and krow made monotone by "
        "weighted isotonic regression (%d value(s) moved), end rows at swc and Sw = 1 from "
        "the fitted law",
        t->n, s->n_isotonic);
  else
    snprintf(buf, sizeof buf,
             "rows: the fitted law on a uniform grid of %d points in Sw from swc = %.6g to 1 - sor "
             "= %.6g%s",
             s->grid_rows, s->sw[0], s->sw[s->grid_rows - 1], s->tail_row ? ", and Sw = 1" : "");
  comment(f, buf);
  comment(f, "units: METRIC (Sw, krw, krow dimensionless; Pcow in bar unless stated below)");
  pc_header(f, s, pc);
  clip_header(f, s);
  fprintf(f, "SWOF\n-- %10s %14s %14s %14s\n", "Sw", "krw", "krow", "Pcow");
  for (int i = 0; i < s->n; i++)
    fprintf(f, "   %10.6f %14.8e %14.8e %14.8e\n", s->sw[i], s->krw[i], s->krow[i],
            s->pcow[i] + 0.0);
  fprintf(f, "/\n");
  if (atomic_commit(f, tmp, path)) {
    snprintf(err, errlen, "%s: cannot write the SWOF table", path);
    return -1;
  }
  return 0;
}
