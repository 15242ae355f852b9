/* Flow-table writer (docs/flow-table.md): checks the table as the reader would, then writes it
 * atomically with every number as %.17g, so that flow_table_read gives back the same doubles. */
#include "flowdata/flow_table.h"

#include "common/atomic_file.h"
#include "flowdata/flow_table_format.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Why `v` cannot be written and read back (NULL if it can): the reader takes finite numbers only,
 * and glibc's strtod flags subnormal ones as out of range. `positive`: it must also be > 0. */
static const char *number_problem(double v, int positive) {
  if (!isfinite(v)) return "expected a finite number";
  if (fpclassify(v) == FP_SUBNORMAL) return "a subnormal number (the reader refuses it)";
  if (positive && !(v > 0)) return "expected a positive number";
  return NULL;
}

/* Why `s` cannot be a header value or comment that reads back unchanged (NULL if it can). */
static const char *text_problem(const char *s, int may_be_empty) {
  size_t n = strlen(s);
  if (!n) return may_be_empty ? NULL : "is empty";
  if (isspace((unsigned char)s[0]) || isspace((unsigned char)s[n - 1]))
    return "starts or ends with white space (the reader trims it)";
  if (strpbrk(s, "\n\r")) return "contains a line break";
  if (n + 16 >= FLOW_TABLE_MAX_LINE) return "is longer than the reader's line limit";
  return NULL;
}

/* The metadata key a comment would be read back as ("" for the format line), or NULL if none. */
static const char *comment_reads_as(const char *c) {
  if (!strcmp(c, FLOW_TABLE_FORMAT_LINE)) return "";
  const char *colon = strchr(c, ':');
  if (!colon) return NULL;
  const char *k = c, *e = colon;
  while (k < e && isspace((unsigned char)*k)) k++;
  while (e > k && isspace((unsigned char)e[-1])) e--;
  for (int i = 0; i < 8; i++) {
    const char *key = i < 4 ? flow_table_text_keys[i] : flow_table_num_keys[i - 4];
    if (strlen(key) == (size_t)(e - k) && !strncmp(k, key, (size_t)(e - k))) return key;
  }
  return NULL;
}

/* Everything the reader checks, so that a written table always reads back. */
static int check_table(const char *path, const flow_table *t, char *err, int errlen) {
  const char *why;
  if (t->n < 1)
    return flow_table_fail(err, errlen, "%s: the table has no data rows (nothing to write)", path);
  if ((why = text_problem(t->sample, 0)))
    return flow_table_fail(err, errlen, "%s: metadata 'sample' %s", path, why);
  if (strcmp(t->axis, "x") && strcmp(t->axis, "y") && strcmp(t->axis, "z"))
    return flow_table_fail(err, errlen, "%s: metadata 'axis': expected x, y or z, got '%s'", path,
                           t->axis);
  if ((why = text_problem(t->length_unit, 0)))
    return flow_table_fail(err, errlen, "%s: metadata 'length_unit' %s", path, why);
  if (t->si != 0 && t->si != 1)
    return flow_table_fail(err, errlen,
                           "%s: metadata 'unit_system': expected si 0 (reduced) or 1 (SI), got %d",
                           path, t->si);
  const double num[4] = {t->viscosity, t->density, t->voxel_size, t->length_unit_m};
  for (int i = 0; i < 4; i++) {
    if (i >= 2 && isnan(num[i])) continue; /* optional, not given */
    if ((why = number_problem(num[i], 1)))
      return flow_table_fail(err, errlen, "%s: metadata '%s': %s, got %.17g", path,
                             flow_table_num_keys[i], why, num[i]);
  }
  if (strcmp(t->driving_column, "pressure_gradient") &&
      strcmp(t->driving_column, "body_force_density"))
    return flow_table_fail(
        err, errlen,
        "%s: driving column: expected 'pressure_gradient' or 'body_force_density', got '%s'", path,
        t->driving_column);
  for (int c = 0; c < t->n_comments; c++) {
    const char *key = comment_reads_as(t->comments[c]);
    if ((why = text_problem(t->comments[c], 1)))
      return flow_table_fail(err, errlen, "%s: comment %d %s", path, c + 1, why);
    if (key)
      return flow_table_fail(err, errlen, "%s: comment %d '%s' would be read back as %s%s%s", path,
                             c + 1, t->comments[c], *key ? "metadata '" : "the format line", key,
                             *key ? "'" : "");
  }
  for (int r = 0; r < t->n; r++) {
    const double v[FLOW_NCOLS] = {t->G[r], t->q[r], t->sigma[r], t->run_length[r]};
    for (int c = 0; c < FLOW_NCOLS; c++) {
      if (!(why = number_problem(v[c], c == FLOW_COL_SIGMA || c == FLOW_COL_RUN))) continue;
      const char *name = c == FLOW_COL_G ? t->driving_column : flow_table_columns[c];
      return flow_table_fail(err, errlen, "%s: row %d, column '%s': %s, got %.17g", path, r + 1,
                             name, why, v[c]);
    }
  }
  return 0;
}

int flow_table_write(const char *path, const flow_table *t, char *err, int errlen) {
  if (check_table(path, t, err, errlen)) return -1;
  char tmp[4200];
  if (strlen(path) > 4096) return flow_table_fail(err, errlen, "%.100s...: path too long", path);
  atomic_tmp_name(path, tmp, sizeof tmp);
  FILE *f = fopen(tmp, "w");
  if (!f)
    return flow_table_fail(err, errlen, "%s: cannot write the temporary file %s: %s", path, tmp,
                           strerror(errno));
  fprintf(f, "# %s\n", FLOW_TABLE_FORMAT_LINE);
  fprintf(f, "# sample: %s\n# axis: %s\n# unit_system: %s\n# length_unit: %s\n", t->sample, t->axis,
          t->si ? "SI" : "reduced", t->length_unit);
  if (!isnan(t->length_unit_m)) fprintf(f, "# length_unit_m: %.17g\n", t->length_unit_m);
  fprintf(f, "# viscosity: %.17g\n# density: %.17g\n", t->viscosity, t->density);
  if (!isnan(t->voxel_size)) fprintf(f, "# voxel_size: %.17g\n", t->voxel_size);
  for (int c = 0; c < t->n_comments; c++)
    fprintf(f, "#%s%s\n", *t->comments[c] ? " " : "", t->comments[c]);
  fprintf(f, "%s,%s,%s,%s\n", t->driving_column, flow_table_columns[FLOW_COL_Q],
          flow_table_columns[FLOW_COL_SIGMA], flow_table_columns[FLOW_COL_RUN]);
  for (int r = 0; r < t->n; r++)
    fprintf(f, "%.17g,%.17g,%.17g,%.17g\n", t->G[r], t->q[r], t->sigma[r], t->run_length[r]);
  if (atomic_commit(f, tmp, path))
    return flow_table_fail(err, errlen, "%s: writing %s or renaming it over the table failed", path,
                           tmp);
  return 0;
}
