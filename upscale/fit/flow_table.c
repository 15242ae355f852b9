/* Flow-table reader and validator (docs/flow-table.md). */
#include "flow_table.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { COL_G, COL_Q, COL_SIGMA, COL_RUN, NCOLS };
static const char *col_names[NCOLS] = {"pressure_gradient", "darcy_velocity",
                                       "darcy_velocity_stderr", "run_length"};

static int fail(char *err, int errlen, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, errlen, fmt, ap);
  va_end(ap);
  return -1;
}

static char *trim(char *s) {
  while (isspace((unsigned char)*s)) s++;
  char *e = s + strlen(s);
  while (e > s && isspace((unsigned char)e[-1])) *--e = 0;
  return s;
}

/* Parses a whole field as a finite double. */
static int parse_number(const char *s, double *v) {
  if (!*s) return -1;
  char *end;
  errno = 0;
  *v = strtod(s, &end);
  if (*end || errno == ERANGE || !isfinite(*v)) return -1;
  return 0;
}

/* Splits a CSV line in place at commas (no quoting: fields are numbers or plain names). */
static int split(char *line, char **fields, int max) {
  int n = 0;
  char *p = line;
  for (;;) {
    char *c = strchr(p, ',');
    if (c) *c = 0;
    if (n < max) fields[n] = trim(p);
    n++;
    if (!c) break;
    p = c + 1;
  }
  return n;
}

/* "# key: value" header lines. Returns 0 if handled (or plain comment), -1 on a bad value. */
static int header_line(flow_table *t, char *text, int lineno, int *seen, char *err, int errlen) {
  char *colon = strchr(text, ':');
  if (!colon) return 0; /* free comment */
  *colon = 0;
  char *key = trim(text), *val = trim(colon + 1);
  static const char *text_keys[] = {"sample", "axis", "length_unit", "unit_system"};
  static const char *num_keys[] = {"viscosity", "density", "voxel_size", "length_unit_m"};
  for (int i = 0; i < 4; i++) {
    if (strcmp(key, text_keys[i])) continue;
    seen[i] = 1;
    if (!*val) return fail(err, errlen, "%s:%d: header '%s' is empty", t->path, lineno, key);
    if (i == 0) snprintf(t->sample, sizeof t->sample, "%s", val);
    if (i == 1) {
      if (strcmp(val, "x") && strcmp(val, "y") && strcmp(val, "z"))
        return fail(err, errlen, "%s:%d: header 'axis': expected x, y or z, got '%s'", t->path,
                    lineno, val);
      snprintf(t->axis, sizeof t->axis, "%s", val);
    }
    if (i == 2) snprintf(t->length_unit, sizeof t->length_unit, "%s", val);
    if (i == 3) {
      if (!strcmp(val, "SI") || !strcmp(val, "si"))
        t->si = 1;
      else if (!strcmp(val, "reduced"))
        t->si = 0;
      else
        return fail(err, errlen,
                    "%s:%d: header 'unit_system': expected 'reduced' or 'SI', got '%s'", t->path,
                    lineno, val);
    }
    return 0;
  }
  for (int i = 0; i < 4; i++) {
    if (strcmp(key, num_keys[i])) continue;
    double v;
    seen[4 + i] = 1;
    if (parse_number(val, &v) || !(v > 0))
      return fail(err, errlen, "%s:%d: header '%s': expected a positive number, got '%s'", t->path,
                  lineno, key, val);
    if (i == 0) t->viscosity = v;
    if (i == 1) t->density = v;
    if (i == 2) t->voxel_size = v;
    if (i == 3) t->length_unit_m = v;
    return 0;
  }
  return 0; /* other "key: value" comments are kept as free text */
}

static int push_row(flow_table *t, int *cap, const double *v, int lineno) {
  if (t->n == *cap) {
    *cap = *cap ? 2 * *cap : 16;
    t->G = realloc(t->G, *cap * sizeof(double));
    t->q = realloc(t->q, *cap * sizeof(double));
    t->sigma = realloc(t->sigma, *cap * sizeof(double));
    t->run_length = realloc(t->run_length, *cap * sizeof(double));
    t->line = realloc(t->line, *cap * sizeof(int));
    if (!t->G || !t->q || !t->sigma || !t->run_length || !t->line) return -1;
  }
  t->G[t->n] = v[COL_G];
  t->q[t->n] = v[COL_Q];
  t->sigma[t->n] = v[COL_SIGMA];
  t->run_length[t->n] = v[COL_RUN];
  t->line[t->n] = lineno;
  t->n++;
  return 0;
}

int flow_table_read(const char *path, flow_table *t, char *err, int errlen) {
  memset(t, 0, sizeof *t);
  snprintf(t->path, sizeof t->path, "%s", path);
  t->voxel_size = NAN;
  t->length_unit_m = NAN;
  FILE *f = fopen(path, "r");
  if (!f) return fail(err, errlen, "%s: cannot open: %s", path, strerror(errno));
  char buf[8192];
  int lineno = 0, have_header = 0, cap = 0, rc = 0, ncols = 0;
  int seen[8] = {0};
  int where[NCOLS]; /* field index of each required column */
  char *fields[256];
  while (fgets(buf, sizeof buf, f)) {
    lineno++;
    if (!strchr(buf, '\n') && !feof(f)) {
      rc =
          fail(err, errlen, "%s:%d: line longer than %d characters", path, lineno, (int)sizeof buf);
      break;
    }
    char *line = trim(buf);
    if (!*line) continue;
    if (*line == '#') {
      if (have_header) continue; /* comments between rows are allowed, metadata is not */
      if ((rc = header_line(t, line + 1, lineno, seen, err, errlen))) break;
      continue;
    }
    int nf = split(line, fields, 256);
    if (!have_header) { /* the column header */
      if (nf > 256) {
        rc = fail(err, errlen, "%s:%d: more than 256 columns", path, lineno);
        break;
      }
      ncols = nf;
      for (int c = 0; c < NCOLS; c++) {
        where[c] = -1;
        for (int i = 0; i < nf; i++) {
          int match = !strcmp(fields[i], col_names[c]) ||
                      (c == COL_G && !strcmp(fields[i], "body_force_density"));
          if (match && where[c] >= 0) {
            rc = fail(err, errlen, "%s:%d: column '%s' appears twice", path, lineno, fields[i]);
            break;
          }
          if (match) where[c] = i;
        }
        if (rc) break;
        if (where[c] < 0) {
          rc = fail(err, errlen,
                    "%s:%d: missing column '%s'%s (header must name: pressure_gradient (or "
                    "body_force_density), darcy_velocity, darcy_velocity_stderr, run_length)",
                    path, lineno, col_names[c], c == COL_G ? " (or 'body_force_density')" : "");
          break;
        }
      }
      if (rc) break;
      snprintf(t->driving_column, sizeof t->driving_column, "%s", fields[where[COL_G]]);
      have_header = 1;
      continue;
    }
    if (nf != ncols) {
      rc = fail(err, errlen, "%s:%d: expected %d comma-separated fields (as in the header), got %d",
                path, lineno, ncols, nf);
      break;
    }
    double v[NCOLS];
    for (int c = 0; c < NCOLS && !rc; c++) {
      const char *s = fields[where[c]];
      const char *name = c == COL_G ? t->driving_column : col_names[c];
      if (parse_number(s, &v[c]))
        rc = fail(err, errlen, "%s:%d: column %d '%s': expected a number, got '%s'", path, lineno,
                  where[c] + 1, name, s);
      else if (c == COL_SIGMA && !(v[c] > 0))
        rc =
            fail(err, errlen, "%s:%d: column %d '%s': expected a positive standard error, got '%s'",
                 path, lineno, where[c] + 1, name, s);
      else if (c == COL_RUN && !(v[c] > 0))
        rc = fail(err, errlen, "%s:%d: column %d '%s': expected a positive run length, got '%s'",
                  path, lineno, where[c] + 1, name, s);
    }
    if (rc) break;
    if (push_row(t, &cap, v, lineno)) {
      rc = fail(err, errlen, "%s: out of memory", path);
      break;
    }
  }
  fclose(f);
  if (!rc) {
    static const char *required[] = {"sample",      "axis",      "length_unit",
                                     "unit_system", "viscosity", "density"};
    for (int i = 0; i < 6 && !rc; i++)
      if (!seen[i])
        rc = fail(err, errlen, "%s: missing header line '# %s: ...'", path, required[i]);
    if (!rc && !have_header)
      rc = fail(err, errlen, "%s: no column header line (and no data)", path);
    if (!rc && t->n == 0) rc = fail(err, errlen, "%s: the table has no data rows", path);
  }
  if (rc) flow_table_free(t);
  return rc;
}

void flow_table_free(flow_table *t) {
  free(t->G);
  free(t->q);
  free(t->sigma);
  free(t->run_length);
  free(t->line);
  t->G = t->q = t->sigma = t->run_length = NULL;
  t->line = NULL;
  t->n = 0;
}
