/* Water/oil relative permeabilities of the two-phase Darcy solve (docs/twophase-darcy.md): Corey
 * laws or a table in the Eclipse SWOF column order (Sw, krw, kro, Pc), and the water fractional flow
 *   f_w(S) = (krw/mu_w) / (krw/mu_w + kro/mu_o)        (no capillary pressure, no gravity). */
#ifndef MDPORE_UPSCALE_TWOPHASE_RELPERM_H
#define MDPORE_UPSCALE_TWOPHASE_RELPERM_H

enum { RELPERM_COREY = 0, RELPERM_TABLE };

typedef struct {
  int kind;
  /* Corey: krw = krw_max Se^nw, kro = kro_max (1 - Se)^no, Se = (Sw - swc) / (1 - swc - sor)
   * clamped to [0, 1] */
  double nw, no, swc, sor, krw_max, kro_max;
  /* table: rows of increasing Sw, linear interpolation, constant beyond the first and last rows */
  int rows;
  double *sw, *krw, *kro;
  double mu_w, mu_o; /* phase viscosities */
} relperm;

/* krw and kro at water saturation s. */
void relperm_eval(const relperm *r, double s, double *krw, double *kro);
/* Total mobility lambda_t = krw/mu_w + kro/mu_o. */
double relperm_total_mobility(const relperm *r, double s);
/* Water fractional flow f_w(s). */
double relperm_fw(const relperm *r, double s);
/* The largest |df_w/dS| over [s_lo, s_hi], by differences on a fine grid (sets the CFL step). */
double relperm_max_dfw(const relperm *r, double s_lo, double s_hi);
/* The saturation range the law spans: [swc, 1 - sor] (Corey) or [first Sw, last Sw] (table). */
void relperm_range(const relperm *r, double *s_min, double *s_max);

/* Reads a SWOF-like table: whitespace- or comma-separated columns Sw krw kro [Pc] (Pc read and not
 * used), lines starting with '#' or '--' and blank lines skipped, an optional trailing '/' ends the
 * table. Checks Sw in [0, 1] strictly increasing, krw and kro in [0, 1], krw non-decreasing, kro
 * non-increasing, krw + kro > 0 on every row, at least 2 rows. Returns 0, or -1 with
 * "FILE:LINE: ... (got ...)" in why. *had_pc tells whether a non-zero Pc column was present. */
int relperm_read_table(const char *path, relperm *r, int *had_pc, char *why, int why_len);
/* Checks the Corey parameters; returns 0, or -1 with the key and reason in why. */
int relperm_check_corey(const relperm *r, char *why, int why_len);
void relperm_free(relperm *r);

#endif
