/* The relative-permeability table that `mdpore fit relperm` reads (docs/relperm.md section 3, the
 * relperm.csv of `mdpore relperm`): '#' comment lines (those of the form "# key: value" with key
 * rc_m, length_unit_m, temperature_K or M are read as metadata, and "rc = VALUE m" inside a comment
 * gives rc_m too), a header naming the columns (order
 * free: Sw, krw, kro required; Sw_err, krw_err, kro_err optional; others ignored), then one
 * comma-separated row per saturation, sorted by Sw. */
#ifndef MDPORE_UPSCALE_KR_TABLE_H
#define MDPORE_UPSCALE_KR_TABLE_H

#define KR_TABLE_MAX_COMMENTS 64

/* A kr more than this many of its standard errors below 0 is refused; closer to 0 it is noise. */
#define KR_NEGATIVE_SIGMA 3.0

typedef struct {
  char path[4096];
  int n;                                               /* rows */
  double *sw, *sw_err, *krw, *krw_err, *kro, *kro_err; /* errors NAN where empty or absent */
  int *line;                                           /* file line of each row (messages) */
  double rc_m, temperature_K, M;                       /* metadata, NAN when not given */
  int n_comments;
  char *comments[KR_TABLE_MAX_COMMENTS]; /* the comment lines without '#', for the SWOF header */
} kr_table;

/* Reads and checks the table. Refused with "FILE:LINE: column 'NAME': expected ... (got ...)":
 * a missing required column, a row with a different number of fields than the header, a field that
 * is not a number, NaN or inf, Sw outside [0, 1], an error < 0, rows not sorted by Sw, kr < 0 beyond
 * KR_NEGATIVE_SIGMA standard errors (any kr < 0 without an error), no rows. Returns 0 or -1. */
int kr_table_read(const char *path, kr_table *t, char *err, int errlen);
void kr_table_free(kr_table *t);

#endif
