/* Flow-table reader and validator (docs/flow-table.md), and the in-memory table (init, rows,
 * comments, free) that the writer (flow_table_write.c) takes. */
#include "flowdata/flow_table.h"

#include "flowdata/flow_table_format.h"
#include "common/text.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const flow_table_columns[FLOW_NCOLS] = {"pressure_gradient", "darcy_velocity",
                                                    "darcy_velocity_stderr", "run_length"};
const char *const flow_table_text_keys[4] = {"sample", "axis", "length_unit", "unit_system"};
const char *const flow_table_num_keys[4] = {"viscosity", "density", "voxel_size", "length_unit_m"};

int flow_table_fail(char *err, int errlen, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, errlen, fmt, ap);
  va_end(ap);
  return -1;
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
    if (n < max) fields[n] = text_trim(p);
    n++;
    if (!c) break;
    p = c + 1;
  }
  return n;
}

/* A metadata key given a second time: an error naming both lines (a later line must not silently
 * override an earlier one). seen[i] is the line of the first occurrence, 0 if none yet. */
static int repeated_key(const flow_table *t, const char *key, int lineno, int first, char *err,
                        int errlen) {
  return flow_table_fail(err, errlen, "%s:%d: key '%s' given again (first at line %d)", t->path,
                         lineno, key, first);
}

/* The metadata key of a "# key: value" line (index into seen[]: text keys 0..3, numeric keys 4..7),
 * or -1 if it is not one. */
static int metadata_key(const char *text) {
  const char *colon = strchr(text, ':');
  if (!colon) return -1;
  const char *k = text, *e = colon;
  while (k < e && isspace((unsigned char)*k)) k++;
  while (e > k && isspace((unsigned char)e[-1])) e--;
  for (int i = 0; i < 8; i++) {
    const char *key = i < 4 ? flow_table_text_keys[i] : flow_table_num_keys[i - 4];
    if (strlen(key) == (size_t)(e - k) && !strncmp(k, key, (size_t)(e - k))) return i;
  }
  return -1;
}

/* "# key: value" header lines. Returns 0 if handled (metadata, the format line or a free comment,
 * which is kept in t->comments), -1 on a bad value, a repeated metadata key, or when out of memory.
 * seen[0..3] (text keys) and seen[4..7] (numeric keys) hold the line of each key, 0 if not seen. */
static int header_line(flow_table *t, char *text, int lineno, int *seen, char *err, int errlen) {
  text = text_trim(text);
  if (!strcmp(text, FLOW_TABLE_FORMAT_LINE)) return 0;
  char whole[FLOW_TABLE_MAX_LINE]; /* the comment as written, kept if it is not metadata */
  snprintf(whole, sizeof whole, "%s", text);
  char *colon = strchr(text, ':');
  char *key = text, *val = NULL;
  if (colon) {
    *colon = 0;
    key = text_trim(text), val = text_trim(colon + 1);
  }
  for (int i = 0; i < 4 && colon; i++) {
    if (strcmp(key, flow_table_text_keys[i])) continue;
    if (seen[i]) return repeated_key(t, key, lineno, seen[i], err, errlen);
    seen[i] = lineno;
    if (!*val)
      return flow_table_fail(err, errlen, "%s:%d: header '%s' is empty", t->path, lineno, key);
    if (i == 0) snprintf(t->sample, sizeof t->sample, "%s", val);
    if (i == 1) {
      if (strcmp(val, "x") && strcmp(val, "y") && strcmp(val, "z"))
        return flow_table_fail(err, errlen, "%s:%d: header 'axis': expected x, y or z, got '%s'",
                               t->path, lineno, val);
      snprintf(t->axis, sizeof t->axis, "%s", val);
    }
    if (i == 2) snprintf(t->length_unit, sizeof t->length_unit, "%s", val);
    if (i == 3) {
      if (!strcmp(val, "SI") || !strcmp(val, "si"))
        t->si = 1;
      else if (!strcmp(val, "reduced"))
        t->si = 0;
      else
        return flow_table_fail(err, errlen,
                               "%s:%d: header 'unit_system': expected 'reduced' or 'SI', got '%s'",
                               t->path, lineno, val);
    }
    return 0;
  }
  for (int i = 0; i < 4 && colon; i++) {
    if (strcmp(key, flow_table_num_keys[i])) continue;
    double v;
    if (seen[4 + i]) return repeated_key(t, key, lineno, seen[4 + i], err, errlen);
    seen[4 + i] = lineno;
    if (parse_number(val, &v) || !(v > 0))
      return flow_table_fail(err, errlen,
                             "%s:%d: header '%s': expected a positive number, got '%s'", t->path,
                             lineno, key, val);
    if (i == 0) t->viscosity = v;
    if (i == 1) t->density = v;
    if (i == 2) t->voxel_size = v;
    if (i == 3) t->length_unit_m = v;
    return 0;
  }
  /* a free comment, or a "key: value" line with another key: kept as free text */
  if (flow_table_add_comment(t, whole))
    return flow_table_fail(err, errlen, "%s:%d: out of memory", t->path, lineno);
  return 0;
}

/* Grows a row array to `cap` entries; on failure the old array stays in place (freed later). */
static int grow_doubles(double **a, int cap) {
  double *p = realloc(*a, (size_t)cap * sizeof *p);
  if (p) *a = p;
  return p ? 0 : -1;
}

static int push_row(flow_table *t, const double *v, int lineno) {
  if (t->n == t->capacity) {
    int cap = t->capacity ? 2 * t->capacity : 16;
    if (grow_doubles(&t->G, cap) || grow_doubles(&t->q, cap) || grow_doubles(&t->sigma, cap) ||
        grow_doubles(&t->run_length, cap))
      return -1;
    int *line = realloc(t->line, (size_t)cap * sizeof *line);
    if (!line) return -1;
    t->line = line;
    t->capacity = cap;
  }
  t->G[t->n] = v[FLOW_COL_G];
  t->q[t->n] = v[FLOW_COL_Q];
  t->sigma[t->n] = v[FLOW_COL_SIGMA];
  t->run_length[t->n] = v[FLOW_COL_RUN];
  t->line[t->n] = lineno;
  t->n++;
  return 0;
}

void flow_table_init(flow_table *t) {
  memset(t, 0, sizeof *t);
  snprintf(t->driving_column, sizeof t->driving_column, "%s", flow_table_columns[FLOW_COL_G]);
  t->voxel_size = NAN;
  t->length_unit_m = NAN;
}

int flow_table_add_row(flow_table *t, double G, double q, double sigma, double run_length) {
  double v[FLOW_NCOLS];
  v[FLOW_COL_G] = G, v[FLOW_COL_Q] = q, v[FLOW_COL_SIGMA] = sigma, v[FLOW_COL_RUN] = run_length;
  return push_row(t, v, 0);
}

int flow_table_add_comment(flow_table *t, const char *text) {
  char *copy = strdup(text);
  char **c = copy ? realloc(t->comments, (size_t)(t->n_comments + 1) * sizeof *c) : NULL;
  if (!c) {
    free(copy);
    return -1;
  }
  t->comments = c;
  t->comments[t->n_comments++] = copy;
  return 0;
}

int flow_table_read(const char *path, flow_table *t, char *err, int errlen) {
  flow_table_init(t);
  snprintf(t->path, sizeof t->path, "%s", path);
  FILE *f = fopen(path, "r");
  if (!f) return flow_table_fail(err, errlen, "%s: cannot open: %s", path, strerror(errno));
  char buf[FLOW_TABLE_MAX_LINE];
  int lineno = 0, have_header = 0, rc = 0, ncols = 0;
  int seen[8] = {0};
  int where[FLOW_NCOLS]; /* field index of each required column */
  char *fields[256];
  while (fgets(buf, sizeof buf, f)) {
    lineno++;
    if (!strchr(buf, '\n') && !feof(f)) {
      rc = flow_table_fail(err, errlen, "%s:%d: line longer than %d characters", path, lineno,
                           (int)sizeof buf);
      break;
    }
    char *line = text_trim(buf);
    if (!*line) continue;
    if (*line == '#') {
      if (have_header) { /* comments between rows are allowed, metadata is not */
        const int k = metadata_key(line + 1);
        if (k >= 0 && seen[k]) {
          rc = repeated_key(t, k < 4 ? flow_table_text_keys[k] : flow_table_num_keys[k - 4], lineno,
                            seen[k], err, errlen);
          break;
        }
        continue;
      }
      if ((rc = header_line(t, line + 1, lineno, seen, err, errlen))) break;
      continue;
    }
    int nf = split(line, fields, 256);
    if (!have_header) { /* the column header */
      if (nf > 256) {
        rc = flow_table_fail(err, errlen, "%s:%d: more than 256 columns", path, lineno);
        break;
      }
      ncols = nf;
      for (int c = 0; c < FLOW_NCOLS; c++) {
        where[c] = -1;
        for (int i = 0; i < nf; i++) {
          int match = !strcmp(fields[i], flow_table_columns[c]) ||
                      (c == FLOW_COL_G && !strcmp(fields[i], "body_force_density"));
          if (match && where[c] >= 0) {
            rc = flow_table_fail(err, errlen, "%s:%d: column '%s' appears twice", path, lineno,
                                 fields[i]);
            break;
          }
          if (match) where[c] = i;
        }
        if (rc) break;
        if (where[c] < 0) {
          rc = flow_table_fail(
              err, errlen,
              "%s:%d: missing column '%s'%s (header must name: pressure_gradient (or "
              "body_force_density), darcy_velocity, darcy_velocity_stderr, run_length)",
              path, lineno, flow_table_columns[c],
              c == FLOW_COL_G ? " (or 'body_force_density')" : "");
          break;
        }
      }
      if (rc) break;
      snprintf(t->driving_column, sizeof t->driving_column, "%s", fields[where[FLOW_COL_G]]);
      have_header = 1;
      continue;
    }
    if (nf != ncols) {
      rc = flow_table_fail(err, errlen,
                           "%s:%d: expected %d comma-separated fields (as in the header), got %d",
                           path, lineno, ncols, nf);
      break;
    }
    double v[FLOW_NCOLS];
    for (int c = 0; c < FLOW_NCOLS && !rc; c++) {
      const char *s = fields[where[c]];
      const char *name = c == FLOW_COL_G ? t->driving_column : flow_table_columns[c];
      if (parse_number(s, &v[c]))
        rc = flow_table_fail(err, errlen, "%s:%d: column %d '%s': expected a number, got '%s'",
                             path, lineno, where[c] + 1, name, s);
      else if (c == FLOW_COL_SIGMA && !(v[c] > 0))
        rc = flow_table_fail(err, errlen,
                             "%s:%d: column %d '%s': expected a positive standard error, got '%s'",
                             path, lineno, where[c] + 1, name, s);
      else if (c == FLOW_COL_RUN && !(v[c] > 0))
        rc = flow_table_fail(err, errlen,
                             "%s:%d: column %d '%s': expected a positive run length, got '%s'",
                             path, lineno, where[c] + 1, name, s);
    }
    if (rc) break;
    if (push_row(t, v, lineno)) {
      rc = flow_table_fail(err, errlen, "%s: out of memory", path);
      break;
    }
  }
  fclose(f);
  if (!rc) {
    static const char *required[] = {"sample",      "axis",      "length_unit",
                                     "unit_system", "viscosity", "density"};
    for (int i = 0; i < 6 && !rc; i++)
      if (!seen[i])
        rc = flow_table_fail(err, errlen, "%s: missing header line '# %s: ...'", path, required[i]);
    if (!rc && !have_header)
      rc = flow_table_fail(err, errlen, "%s: no column header line (and no data)", path);
    if (!rc && t->n == 0) rc = flow_table_fail(err, errlen, "%s: the table has no data rows", path);
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
  for (int i = 0; i < t->n_comments; i++) free(t->comments[i]);
  free(t->comments);
  t->G = t->q = t->sigma = t->run_length = NULL;
  t->line = NULL;
  t->comments = NULL;
  t->n = t->capacity = t->n_comments = 0;
}
