/* The Eclipse/OPM SWOF export of `mdpore fit relperm --swof` (docs/relperm.md section 5): keyword
 * SWOF, one row per saturation "Sw krw krow Pcow", '--' comment lines stating the source, the law,
 * the grid and the units, and a closing '/'.
 *
 * Rows are either the fitted law on a uniform grid of Sw from swc to 1 - sor (plus Sw = 1 when
 * sor > 0), or the measured points (--swof-points measured) made monotone by weighted isotonic
 * regression (pool adjacent violators, weights 1/err^2), with end rows from the fitted law at swc
 * and Sw = 1. Either way: Sw strictly increasing, krw non-decreasing with krw = 0 on the first row,
 * krow non-increasing with krow = 0 on the last row, every kr in [0, 1].
 *
 * kr > 1 (the oil's kr exceeds 1 at M > 1, lubricated by wetting films): clipped to 1, each clipped
 * row listed in the header with its unclipped value. OPM Flow's saturation-function diagnostics
 * report krw above 1 and krow above 1 in SWOF as errors ("krw should be in range [0,1]"), and
 * `mdpore darcy` refuses kr > 1 in a table. The header also gives the exact alternative: divide both
 * kr columns by the largest kr and multiply the permeability by it (the same mobilities).
 *
 * Pcow = p_o - p_w from the morphological Pc(Sw) curve when given (pc_curve.h; interpolated,
 * constant beyond its ends, made non-increasing in Sw as SWOF expects), else 0 (stated). */
#ifndef MDPORE_UPSCALE_KR_SWOF_H
#define MDPORE_UPSCALE_KR_SWOF_H

#include "kr_select.h"
#include "kr_table.h"
#include "pc_curve.h"

#define KR_SWOF_DEFAULT_ROWS 41
#define KR_SWOF_MAX_CLIPPED 64
/* Sw is written with 6 decimals: end rows closer than this to a measured row are not added. */
#define KR_SWOF_SW_RESOLUTION 1e-6

typedef struct {
  int n;
  double *sw, *krw, *krow, *pcow; /* pcow in bar, or reduced units when pc_bar_factor is NAN */
  int measured;                   /* 1: rows from the measured points */
  int no_law;                     /* 1: measured points without a law (none accepted) */
  int head_row;                   /* no law: a row at Sw = 0 added */
  double first_krw_measured;      /* no law, no head row: the first row's krw before set to 0 */
  double last_krow_measured;      /* no law, no tail row: the last row's krow before set to 0 */
  int grid_rows;                  /* law: grid points from swc to 1 - sor */
  int tail_row;                   /* a last row at Sw = 1 added (law: sor > 0) */
  int n_clipped;                  /* rows with a kr above 1 clipped to it */
  int clipped_row[KR_SWOF_MAX_CLIPPED];
  double clipped_krw[KR_SWOF_MAX_CLIPPED], clipped_krow[KR_SWOF_MAX_CLIPPED]; /* unclipped */
  double kr_peak;           /* the largest kr before clipping */
  int n_isotonic;           /* measured: kr values moved by the isotonic regression */
  int n_pc_levelled;        /* Pcow values lowered to keep it non-increasing */
  double pc_bar_factor;     /* bar per unit of the Pc curve; NAN: reduced, no scale */
  double pc_pa_per_reduced; /* Pa per reduced pressure unit (kT/rc^3), NAN if unknown */
} kr_swof;

/* Builds the rows: the law on `rows` grid points (measured = 0) or the measured points with end
 * rows from the law (measured = 1); law NULL (no law accepted, docs/relperm.md section 5): the
 * measured points, made monotone, with end rows at Sw = 0 (krw = 0, krow held from the first row)
 * and Sw = 1 (krow = 0, krw held from the last row). pc may be NULL (Pcow = 0). Returns 0 or -1
 * with err. */
int kr_swof_build(const kr_table *t, const kr_law *law, int rows, int measured, const pc_curve *pc,
                  kr_swof *s, char *err, int errlen);
/* Writes the SWOF file (atomically). law_text: the law and its parameters in words; choice: the
 * selection test in words. Returns 0 or -1 with err. */
int kr_swof_write(const char *path, const kr_swof *s, const kr_table *t, const pc_curve *pc,
                  const char *law_text, const char *choice, char *err, int errlen);
void kr_swof_free(kr_swof *s);

#endif
