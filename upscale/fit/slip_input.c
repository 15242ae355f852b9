/* Reading the permeabilities of `mdpore slip` (see slip_input.h). */
#include "slip_input.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/yaml_tree.h"
#include "common/text.h"

void slip_points_init(slip_points *ps, int shape) {
  memset(ps, 0, sizeof *ps);
  ps->shape = shape;
  if (shape >= 0) snprintf(ps->shape_from, sizeof ps->shape_from, "--shape");
}

void slip_points_free(slip_points *ps) {
  free(ps->p);
  memset(ps, 0, sizeof *ps);
}

static slip_point *add_point(slip_points *ps) {
  if (ps->n == ps->cap) {
    const int cap = ps->cap ? 2 * ps->cap : 16;
    slip_point *p = realloc(ps->p, cap * sizeof *p);
    if (!p) return NULL;
    ps->p = p;
    ps->cap = cap;
  }
  slip_point *q = &ps->p[ps->n++];
  memset(q, 0, sizeof *q);
  q->porosity = 1.0;
  q->rc_m = NAN;
  return q;
}

/* Sets or checks the shape of the set; where = "FILE:LINE" of the value. */
static int use_shape(slip_points *ps, const char *name, const char *where, char *err, int len) {
  const int s = slip_shape_from_name(name);
  if (s < 0) {
    snprintf(err, len, "%s: column 'shape': expected slit or tube, got '%s'", where, name);
    return -1;
  }
  if (ps->shape >= 0 && ps->shape != s) {
    snprintf(err, len, "%s: column 'shape': expected %s (set by %s; one shape per fit), got '%s'",
             where, slip_shape_names[ps->shape], ps->shape_from, name);
    return -1;
  }
  if (ps->shape < 0) snprintf(ps->shape_from, sizeof ps->shape_from, "%s", where);
  ps->shape = s;
  return 0;
}

/* A whole field as a double (nan and inf parse, and are refused later as non-finite). */
static int parse_number(const char *s, double *v) {
  char *end;
  if (!*s) return -1;
  *v = strtod(s, &end);
  return *text_trim(end) ? -1 : 0;
}

enum { COL_H, COL_K, COL_KERR, COL_SHAPE, COL_POROSITY, NCOL };
static const char *const col_names[NCOL] = {"h", "k", "k_err", "shape", "porosity"};

#define MAX_FIELDS 64

static int split(char *line, char **f) {
  int n = 0;
  for (char *tok = line;; n++) {
    char *c = strchr(tok, ',');
    if (c) *c = 0;
    if (n < MAX_FIELDS) f[n] = text_trim(tok);
    if (!c) return n + 1;
    tok = c + 1;
  }
}

static int read_csv(slip_points *ps, FILE *fp, const char *path, char *err, int len) {
  char line[4096], *f[MAX_FIELDS];
  int col[NCOL], ncols = 0, lineno = 0, rows = 0;
  for (int c = 0; c < NCOL; c++) col[c] = -1;
  while (fgets(line, sizeof line, fp)) {
    lineno++;
    char *s = text_trim(line);
    if (!*s || *s == '#') continue;
    const int nf = split(s, f);
    if (nf > MAX_FIELDS) {
      snprintf(err, len, "%s:%d: expected at most %d columns, got %d", path, lineno, MAX_FIELDS,
               nf);
      return -1;
    }
    if (!ncols) { /* the column line */
      ncols = nf;
      for (int i = 0; i < nf; i++)
        for (int c = 0; c < NCOL; c++)
          if (!strcmp(f[i], col_names[c])) {
            if (col[c] >= 0) {
              snprintf(err, len, "%s:%d: column '%s' given twice", path, lineno, col_names[c]);
              return -1;
            }
            col[c] = i;
          }
      for (int c = COL_H; c <= COL_KERR; c++)
        if (col[c] < 0) {
          snprintf(err, len,
                   "%s:%d: expected a column '%s' (the columns are h, k, k_err, optional shape "
                   "and porosity; got '%s'%s)",
                   path, lineno, col_names[c], f[0], nf > 1 ? ", ..." : "");
          return -1;
        }
      continue;
    }
    if (nf != ncols) {
      snprintf(err, len, "%s:%d: expected %d fields as in the column line, got %d", path, lineno,
               ncols, nf);
      return -1;
    }
    slip_point *q = add_point(ps);
    if (!q) {
      snprintf(err, len, "%s: out of memory", path);
      return -1;
    }
    snprintf(q->source, sizeof q->source, "%.480s:%d", path, lineno);
    if (col[COL_SHAPE] >= 0 && use_shape(ps, f[col[COL_SHAPE]], q->source, err, len)) return -1;
    double *dst[NCOL] = {&q->h, &q->k, &q->k_err, NULL, &q->porosity};
    for (int c = 0; c < NCOL; c++) {
      if (!dst[c] || col[c] < 0) continue;
      if (parse_number(f[col[c]], dst[c])) {
        snprintf(err, len, "%s: column '%s': expected a number, got '%s'", q->source, col_names[c],
                 f[col[c]]);
        return -1;
      }
    }
    rows++;
  }
  if (!ncols || !rows) {
    snprintf(err, len,
             "%s: expected a column line (h,k,k_err[,shape][,porosity]) and data rows, got %s",
             path, ncols ? "no data rows" : "no column line");
    return -1;
  }
  return 0;
}

/* h_hydraulic from campaign.txt beside a campaign's permeability.json, or NaN. */
static double campaign_h_hydraulic(const char *json_path, char *where, int wlen) {
  char dir[SLIP_SOURCE_LEN], line[1024];
  snprintf(dir, sizeof dir, "%s", json_path);
  char *slash = strrchr(dir, '/');
  if (slash)
    slash[1] = 0;
  else
    dir[0] = 0;
  snprintf(where, wlen, "%scampaign.txt", dir);
  FILE *fp = fopen(where, "r");
  double h = NAN;
  if (!fp) return h;
  while (fgets(line, sizeof line, fp))
    if (!strncmp(line, "h_hydraulic:", 12)) h = strtod(line + 12, NULL);
  fclose(fp);
  return h;
}

static int json_number_at(ytree_t *t, yaml_node_t *map, const char *key, const char *path,
                          double *v) {
  yaml_node_t *n = yt_need(t, map, key, path, "a number");
  return n ? yt_double(t, n, path, v) : -1;
}

static int read_campaign_json(slip_points *ps, const char *path, double size, const char *axis,
                              char *err, int len) {
  static const char *const formats[] = {"mdpore-permeability", NULL};
  ytree_t t;
  snprintf(err, len, "%s: not a readable mdpore-permeability JSON (see the message above)", path);
  if (yt_load(&t, path, 0)) return -1;
  int rc = -1;
  yaml_node_t *root = yt_root(&t), *n, *axes, *ax;
  if (yt_expect_map(&t, root, "")) goto done;
  if (!(n = yt_need(&t, root, "format", "format", "mdpore-permeability")) ||
      yt_enum(&t, n, "format", formats) < 0)
    goto done;
  slip_point q = {.rc_m = NAN};
  snprintf(q.source, sizeof q.source, "%s", path);
  if (json_number_at(&t, root, "porosity", "porosity", &q.porosity)) goto done;
  yaml_node_t *units = yt_get(&t, root, "units");
  if (units && (n = yt_get(&t, units, "rc_m")) && !yt_is_null(n) &&
      yt_double(&t, n, "units.rc_m", &q.rc_m))
    goto done;
  if (!(axes = yt_need(&t, root, "axes", "axes", "a mapping of axes")) ||
      yt_expect_map(&t, axes, "axes"))
    goto done;
  const char *name = axis;
  if (!name) {
    if (yt_map_size(axes) < 1) {
      yt_error(&t, axes, "axes", "expected at least one axis (got none)");
      goto done;
    }
    name = yt_get(&t, axes, "x") || yt_map_size(axes) > 1 ? "x" : yt_map_key(&t, axes, 0, NULL);
  }
  char apath[64], kpath[96];
  snprintf(apath, sizeof apath, "axes.%s", name);
  if (!(ax = yt_need(&t, axes, name, apath, "the axis' results (--axis)"))) goto done;
  snprintf(kpath, sizeof kpath, "%s.k_rc2", apath);
  if (json_number_at(&t, ax, "k_rc2", kpath, &q.k)) goto done;
  snprintf(kpath, sizeof kpath, "%s.k_rc2_err", apath);
  if (json_number_at(&t, ax, "k_rc2_err", kpath, &q.k_err)) goto done;
  snprintf(q.source, sizeof q.source, "%.440s (%.64s)", path, apath);
  if (isfinite(size)) {
    q.h = size;
  } else if (ps->shape == SLIP_SLIT) {
    char where[SLIP_SOURCE_LEN];
    q.h = campaign_h_hydraulic(path, where, sizeof where);
    if (!isfinite(q.h)) {
      snprintf(err, len,
               "%s: no pore size: expected the suffix %s@H (slit width) or key 'h_hydraulic' in "
               "%s",
               path, path, where);
      goto done;
    }
  } else {
    snprintf(err, len,
             "%s: no pore size: expected the suffix %s@%s (%s; a campaign's hydraulic size 2V/S "
             "is the width of a slit only)%s",
             path, path, ps->shape == SLIP_TUBE ? "R" : "H",
             ps->shape == SLIP_TUBE ? "the tube radius" : "the pore size",
             ps->shape < 0 ? ", or --shape slit" : "");
    goto done;
  }
  slip_point *dst = add_point(ps);
  if (!dst) {
    snprintf(err, len, "%s: out of memory", path);
    goto done;
  }
  *dst = q;
  rc = 0;
done:
  yt_free(&t);
  return rc;
}

const char *slip_input_size(const char *spec) {
  const char *at = strrchr(spec, '@');
  return at && !strchr(at, '/') ? at : NULL;
}

int slip_read_input(slip_points *ps, const char *spec, const char *axis, char *err, int len) {
  char path[SLIP_SOURCE_LEN];
  double size = NAN;
  snprintf(path, sizeof path, "%s", spec);
  char *at = slip_input_size(spec) ? path + (slip_input_size(spec) - spec) : NULL;
  if (at) {
    if (parse_number(at + 1, &size) || !(isfinite(size) && size > 0)) {
      snprintf(err, len, "%s: the size after '@': expected a pore size > 0 (rc), got '%s'", spec,
               at + 1);
      return -1;
    }
    *at = 0;
  }
  FILE *fp = fopen(path, "r");
  if (!fp) {
    snprintf(err, len, "%s: cannot open (expected a CSV h,k,k_err or a permeability.json)", path);
    return -1;
  }
  int c;
  while ((c = fgetc(fp)) != EOF && isspace(c)) {
  }
  char head[32] = {0};
  if (c != EOF) {
    head[0] = (char)c;
    if (!fgets(head + 1, sizeof head - 1, fp)) head[1] = 0;
  }
  rewind(fp);
  int rc;
  if (c == '{') {
    fclose(fp);
    return read_campaign_json(ps, path, size, axis, err, len);
  }
  if (!strncmp(head, "# mdpore flow table", 19)) {
    snprintf(err, len,
             "%s: a flow table (q against G): expected a permeability, i.e. the campaign's "
             "permeability.json (same folder) or a CSV h,k,k_err",
             path);
    rc = -1;
  } else if (isfinite(size)) {
    snprintf(err, len, "%s@%g: a size suffix is for a permeability.json; a CSV has column 'h'",
             path, size);
    rc = -1;
  } else {
    rc = read_csv(ps, fp, path, err, len);
  }
  fclose(fp);
  return rc;
}
