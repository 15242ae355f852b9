/* Reader of the morphological Pc(Sw) curve (see pc_curve.h). */
#include "pc_curve.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

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

static int parse(const char *path, int lineno, const char *name, const char *s, double *v,
                 char *err, int errlen) {
  char *end;
  *v = strtod(s, &end);
  if (!*s || end == s || *end)
    return fail(err, errlen, "%s:%d: column '%s': expected a number (got '%s')", path, lineno, name,
                s);
  if (!isfinite(*v))
    return fail(err, errlen, "%s:%d: column '%s': expected a finite number (got '%s')", path,
                lineno, name, s);
  return 0;
}

/* Sorts the rows by Sw (drainage curves are written by decreasing Sw) and merges rows of equal Sw
 * into one with the largest Pc: a drainage curve holds Sw = 1 over every Pc below the entry
 * pressure, and the entry pressure is the Pc at which that saturation is left. */
typedef struct {
  double sw, pc;
} pc_row;

static int by_sw(const void *a, const void *b) {
  const double x = ((const pc_row *)a)->sw, y = ((const pc_row *)b)->sw;
  return (x > y) - (x < y);
}

static int sort_rows(pc_curve *c) {
  pc_row *rows = malloc((size_t)(c->n > 0 ? c->n : 1) * sizeof *rows);
  if (!rows) return -1;
  for (int i = 0; i < c->n; i++) rows[i].sw = c->sw[i], rows[i].pc = c->pc[i];
  qsort(rows, (size_t)c->n, sizeof *rows, by_sw); /* O(n log n): any length of file */
  for (int i = 0; i < c->n; i++) c->sw[i] = rows[i].sw, c->pc[i] = rows[i].pc;
  free(rows);
  int m = 0;
  for (int i = 0; i < c->n; i++) {
    if (m > 0 && c->sw[i] == c->sw[m - 1]) {
      c->pc[m - 1] = fmax(c->pc[m - 1], c->pc[i]);
      c->merged++;
      continue;
    }
    c->sw[m] = c->sw[i], c->pc[m] = c->pc[i], m++;
  }
  c->n = m;
  return 0;
}

/* One Pc field: a finite number, or empty (NAN) where allowed (pc_Pa is empty when the image has no
 * physical voxel size). */
static int parse_pc(const char *path, int lineno, const char *name, const char *s, int may_be_empty,
                    double *v, char *err, int errlen) {
  if (!*s && may_be_empty) return *v = NAN, 0;
  return parse(path, lineno, name, s, v, err, errlen);
}

int pc_curve_read(const char *path, pc_curve *c, char *err, int errlen) {
  memset(c, 0, sizeof *c);
  snprintf(c->path, sizeof c->path, "%s", path);
  FILE *f = fopen(path, "r");
  if (!f) return fail(err, errlen, "%s: cannot open the capillary-pressure curve", path);
  char line[4096], *fields[MAX_FIELDS];
  int lineno = 0, header = 0, ncols = 0, col_sw = -1, col_pa = -1, col_red = -1, cap = 0, rc = 0;
  int pa_empty = 0; /* rows whose pc_Pa is empty */
  double *pa = NULL, *red = NULL;
  while (!rc && fgets(line, sizeof line, f)) {
    lineno++;
    if (strlen(line) == sizeof line - 1 && line[sizeof line - 2] != '\n') {
      rc = fail(err, errlen, "%s:%d: expected lines of at most %d characters", path, lineno,
                (int)sizeof line - 2);
      break;
    }
    char *s = trim(line);
    if (*s == '#' || !*s) continue;
    const int nf = split_fields(s, fields);
    if (!header) {
      header = lineno, ncols = nf;
      for (int k = 0; k < nf && k < MAX_FIELDS; k++) {
        if (!strcasecmp(fields[k], "Sw")) col_sw = k;
        if (!strcasecmp(fields[k], "pc_Pa")) col_pa = k;
        if (!strcasecmp(fields[k], "pc")) col_red = k;
      }
      if (col_sw < 0 || (col_pa < 0 && col_red < 0))
        rc = fail(err, errlen,
                  "%s:%d: header: expected columns 'Sw' and 'pc_Pa' or 'pc' (the pc_morph.csv of "
                  "mdpore image drainage)",
                  path, lineno);
      continue;
    }
    if (nf != ncols) {
      rc = fail(err, errlen, "%s:%d: expected %d fields as in the header (got %d)", path, lineno,
                ncols, nf);
      break;
    }
    if (c->n == cap) {
      cap = cap ? 2 * cap : 32;
      double *g[3] = {realloc(c->sw, (size_t)cap * sizeof(double)),
                      realloc(pa, (size_t)cap * sizeof(double)),
                      realloc(red, (size_t)cap * sizeof(double))};
      if (g[0]) c->sw = g[0];
      if (g[1]) pa = g[1];
      if (g[2]) red = g[2];
      if (!g[0] || !g[1] || !g[2]) {
        rc = fail(err, errlen, "%s:%d: out of memory (%d rows)", path, lineno, c->n);
        break;
      }
    }
    pa[c->n] = red[c->n] = NAN;
    rc = parse(path, lineno, "Sw", fields[col_sw], &c->sw[c->n], err, errlen);
    if (!rc && col_pa >= 0)
      rc = parse_pc(path, lineno, "pc_Pa", fields[col_pa], col_red >= 0, &pa[c->n], err, errlen);
    if (!rc && col_red >= 0)
      rc = parse_pc(path, lineno, "pc", fields[col_red], col_pa >= 0 && isfinite(pa[c->n]),
                    &red[c->n], err, errlen);
    if (!rc && !(c->sw[c->n] >= 0 && c->sw[c->n] <= 1))
      rc = fail(err, errlen, "%s:%d: column 'Sw': expected a saturation in [0, 1] (got %g)", path,
                lineno, c->sw[c->n]);
    if (!rc && col_pa >= 0 && !isfinite(pa[c->n])) pa_empty++;
    if (!rc && !isfinite(pa[c->n]) && !isfinite(red[c->n]))
      rc = fail(err, errlen,
                "%s:%d: columns 'pc_Pa' and 'pc': expected a number in one (got both "
                "empty)",
                path, lineno);
    c->n++;
  }
  fclose(f);
  /* Pa where every row has it, else the reduced column */
  c->in_pa = col_pa >= 0 && pa_empty == 0;
  if (!rc && !c->in_pa)
    for (int i = 0; i < c->n && !rc; i++)
      if (!isfinite(red[i]))
        rc = fail(err, errlen,
                  "%s: column 'pc': expected a number on every row where 'pc_Pa' is "
                  "empty",
                  path);
  c->pc = c->in_pa ? pa : red;
  free(c->in_pa ? red : pa);
  if (!rc && sort_rows(c)) rc = fail(err, errlen, "%s: out of memory sorting the rows", path);
  if (!rc && c->n < 2)
    rc = fail(err, errlen, "%s: expected at least 2 rows of different Sw (got %d)", path, c->n);
  if (rc) {
    pc_curve_free(c);
    return -1;
  }
  return 0;
}

double pc_curve_at(const pc_curve *c, double sw) {
  if (sw <= c->sw[0]) return c->pc[0];
  if (sw >= c->sw[c->n - 1]) return c->pc[c->n - 1];
  int i = 1;
  while (c->sw[i] < sw) i++;
  const double span = c->sw[i] - c->sw[i - 1];
  const double w = span > 0 ? (sw - c->sw[i - 1]) / span : 1.0;
  return c->pc[i - 1] + w * (c->pc[i] - c->pc[i - 1]);
}

void pc_curve_free(pc_curve *c) {
  free(c->sw);
  free(c->pc);
  c->sw = c->pc = NULL;
  c->n = 0;
}
