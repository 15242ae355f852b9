/* Reader of the relative-permeability table (see kr_table.h). */
#include "kr_table.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { COL_SW, COL_SW_ERR, COL_KRW, COL_KRW_ERR, COL_KRO, COL_KRO_ERR, N_COLS };
static const char *const col_names[N_COLS] = {"Sw", "Sw_err", "krw", "krw_err", "kro", "kro_err"};
#define MAX_FIELDS 64

static int fail(char *err, int errlen, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, errlen, fmt, ap);
  va_end(ap);
  return -1;
}

static char *trim(char *s) {
  while (*s == ' ' || *s == '\t') s++;
  char *e = s + strlen(s);
  while (e > s && (e[-1] == '\n' || e[-1] == '\r' || e[-1] == ' ' || e[-1] == '\t')) *--e = 0;
  return s;
}

/* Splits a comma-separated line in place, keeping empty fields; returns the count. */
static int split_fields(char *s, char **f) {
  int n = 0;
  for (;;) {
    char *c = strchr(s, ',');
    if (n < MAX_FIELDS) f[n] = trim(s);
    n++;
    if (!c) break;
    *c = 0;
    s = c + 1;
  }
  return n;
}

/* "# key: value" metadata, and rc written in words ("... rc = 8.2e-10 m; ...", as `mdpore relperm`
 * states it) when no rc_m line gave it. */
static int read_metadata(kr_table *t, const char *text, int lineno, char *err, int errlen) {
  const char *w = strstr(text, "rc = ");
  if (w && !isfinite(t->rc_m)) {
    char *end;
    const double v = strtod(w + 5, &end);
    if (end != w + 5 && isfinite(v) && v > 0 && !strncmp(end, " m", 2) &&
        (end[2] == 0 || end[2] == ';' || end[2] == ',' || end[2] == ' ' || end[2] == ')'))
      t->rc_m = v;
  }
  static const char *const keys[] = {"rc_m", "length_unit_m", "temperature_K", "M"};
  for (int k = 0; k < 4; k++) {
    size_t len = strlen(keys[k]);
    if (strncmp(text, keys[k], len) || text[len] != ':') continue;
    char *end;
    double v = strtod(text + len + 1, &end);
    if (end == text + len + 1) continue; /* words, not a value: a comment */
    if (!isfinite(v) || !(v > 0))
      return fail(err, errlen, "%s:%d: metadata '%s': expected a finite number > 0 (got '%.40s')",
                  t->path, lineno, keys[k], text + len + 1 + strspn(text + len + 1, " \t"));
    if (k <= 1)
      t->rc_m = v;
    else if (k == 2)
      t->temperature_K = v;
    else
      t->M = v;
  }
  return 0;
}

static int grow(kr_table *t, int *cap) {
  if (t->n < *cap) return 0;
  *cap = *cap ? 2 * *cap : 32;
  double **cols[N_COLS] = {&t->sw, &t->sw_err, &t->krw, &t->krw_err, &t->kro, &t->kro_err};
  for (int c = 0; c < N_COLS; c++) {
    double *p = realloc(*cols[c], (size_t)*cap * sizeof(double));
    if (!p) return -1;
    *cols[c] = p;
  }
  int *l = realloc(t->line, (size_t)*cap * sizeof(int));
  if (!l) return -1;
  t->line = l;
  return 0;
}

/* One field of a row: a finite number (an error column may be empty: NAN). */
static int parse_field(const kr_table *t, int lineno, int c, const char *s, double *v, char *err,
                       int errlen) {
  const int is_err = c == COL_SW_ERR || c == COL_KRW_ERR || c == COL_KRO_ERR;
  if (!*s) {
    if (is_err) return *v = NAN, 0;
    return fail(err, errlen, "%s:%d: column '%s': expected a number (got an empty field)", t->path,
                lineno, col_names[c]);
  }
  char *end;
  *v = strtod(s, &end);
  if (end == s || *end)
    return fail(err, errlen, "%s:%d: column '%s': expected a number (got '%s')", t->path, lineno,
                col_names[c], s);
  if (!isfinite(*v))
    return fail(err, errlen, "%s:%d: column '%s': expected a finite number (got '%s')", t->path,
                lineno, col_names[c], s);
  if (is_err && *v < 0)
    return fail(err, errlen, "%s:%d: column '%s': expected a standard error >= 0 (got %g)", t->path,
                lineno, col_names[c], *v);
  return 0;
}

/* Physical checks of row i (after parsing). */
static int check_row(const kr_table *t, int i, char *err, int errlen) {
  const int lineno = t->line[i];
  if (!(t->sw[i] >= 0.0 && t->sw[i] <= 1.0))
    return fail(err, errlen, "%s:%d: column 'Sw': expected a saturation in [0, 1] (got %g)",
                t->path, lineno, t->sw[i]);
  if (i > 0 && t->sw[i] < t->sw[i - 1])
    return fail(err, errlen,
                "%s:%d: column 'Sw': expected rows sorted by Sw (got %g after %g on line %d)",
                t->path, lineno, t->sw[i], t->sw[i - 1], t->line[i - 1]);
  const double kr[2] = {t->krw[i], t->kro[i]}, se[2] = {t->krw_err[i], t->kro_err[i]};
  for (int p = 0; p < 2; p++) {
    if (kr[p] >= 0) continue;
    const char *name = col_names[p ? COL_KRO : COL_KRW];
    if (!(se[p] > 0))
      return fail(err, errlen,
                  "%s:%d: column '%s': expected a relative permeability >= 0 (got %g, with no "
                  "standard error to call it noise)",
                  t->path, lineno, name, kr[p]);
    if (kr[p] < -KR_NEGATIVE_SIGMA * se[p])
      return fail(err, errlen,
                  "%s:%d: column '%s': expected a relative permeability >= 0 within %g standard "
                  "errors (got %g +- %g: %.1f errors below 0)",
                  t->path, lineno, name, KR_NEGATIVE_SIGMA, kr[p], se[p], -kr[p] / se[p]);
  }
  return 0;
}

int kr_table_read(const char *path, kr_table *t, char *err, int errlen) {
  memset(t, 0, sizeof *t);
  snprintf(t->path, sizeof t->path, "%s", path);
  t->rc_m = t->temperature_K = t->M = NAN;
  FILE *f = fopen(path, "r");
  if (!f) return fail(err, errlen, "%s: cannot open the relative-permeability table", path);
  char line[4096], *fields[MAX_FIELDS];
  int lineno = 0, cap = 0, ncols = 0, header_line = 0, col_of[N_COLS], rc = 0;
  for (int c = 0; c < N_COLS; c++) col_of[c] = -1;
  while (!rc && fgets(line, sizeof line, f)) {
    lineno++;
    if (strlen(line) == sizeof line - 1 && line[sizeof line - 2] != '\n') {
      rc = fail(err, errlen, "%s:%d: expected lines of at most %d characters", path, lineno,
                (int)sizeof line - 2);
      break;
    }
    char *s = trim(line);
    if (*s == '#') {
      char *text = trim(s + 1);
      if ((rc = read_metadata(t, text, lineno, err, errlen))) break;
      if (t->n_comments < KR_TABLE_MAX_COMMENTS) t->comments[t->n_comments++] = strdup(text);
      continue;
    }
    if (!*s) continue;
    int nf = split_fields(s, fields);
    if (!header_line) { /* the header */
      header_line = lineno;
      ncols = nf;
      for (int k = 0; k < nf && k < MAX_FIELDS; k++)
        for (int c = 0; c < N_COLS; c++)
          if (!strcmp(fields[k], col_names[c])) col_of[c] = k;
      const int need[3] = {COL_SW, COL_KRW, COL_KRO};
      for (int q = 0; q < 3 && !rc; q++)
        if (col_of[need[q]] < 0)
          rc = fail(err, errlen,
                    "%s:%d: header: expected a column '%s' (the header must name Sw, krw and kro; "
                    "docs/relperm.md section 3)",
                    path, lineno, col_names[need[q]]);
      if (!rc && nf > MAX_FIELDS)
        rc = fail(err, errlen, "%s:%d: header: expected at most %d columns (got %d)", path, lineno,
                  MAX_FIELDS, nf);
      continue;
    }
    if (nf != ncols) {
      rc = fail(err, errlen,
                "%s:%d: expected %d comma-separated fields as in the header on line %d "
                "(got %d)",
                path, lineno, ncols, header_line, nf);
      break;
    }
    if (grow(t, &cap)) {
      rc = fail(err, errlen, "%s: out of memory", path);
      break;
    }
    double *dst[N_COLS] = {t->sw, t->sw_err, t->krw, t->krw_err, t->kro, t->kro_err};
    for (int c = 0; c < N_COLS && !rc; c++) {
      if (col_of[c] < 0)
        dst[c][t->n] = NAN;
      else
        rc = parse_field(t, lineno, c, fields[col_of[c]], &dst[c][t->n], err, errlen);
    }
    if (rc) break;
    t->line[t->n] = lineno;
    rc = check_row(t, t->n, err, errlen);
    t->n++;
  }
  fclose(f);
  if (!rc && !header_line)
    rc = fail(err, errlen, "%s: expected a header line naming the columns Sw, krw, kro (got none)",
              path);
  else if (!rc && t->n == 0)
    rc = fail(err, errlen, "%s: expected rows after the header on line %d (got none)", path,
              header_line);
  if (rc) kr_table_free(t);
  return rc;
}

void kr_table_free(kr_table *t) {
  free(t->sw);
  free(t->sw_err);
  free(t->krw);
  free(t->krw_err);
  free(t->kro);
  free(t->kro_err);
  free(t->line);
  for (int i = 0; i < t->n_comments; i++) free(t->comments[i]);
  t->sw = t->sw_err = t->krw = t->krw_err = t->kro = t->kro_err = NULL;
  t->line = NULL;
  t->n = t->n_comments = 0;
}
