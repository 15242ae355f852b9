/* YAML configuration reader for `mdpore darcy` (see darcy_config.h, docs/darcy-config.md). */
#include "darcy_config.h"

#include <hdf5.h>
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/yaml_doc.h"
#include "fit_json_law.h"

static const char *face_names[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};

/* path relative to the config file's folder (unless absolute) */
static void resolve(const char *config, const char *rel, char *out, int len) {
  if (rel[0] == '/') {
    snprintf(out, len, "%s", rel);
    return;
  }
  char tmp[4096];
  snprintf(tmp, sizeof tmp, "%s", config);
  snprintf(out, len, "%s/%s", dirname(tmp), rel);
}

/* One law: {law: NAME, params...} or {fit: FILE.json, model: chosen|NAME}. Extra keys allowed by
 * the caller (e.g. "cells" in a layer) are passed in `extra`. */
static int parse_law(ydoc *y, const yaml_node_t *n, const char *what, darcy_config *c,
                     const char *extra, flow_law *law) {
  if (!ydoc_is_map(n))
    return ydoc_fail(y, n, "%s: expected a law mapping like {law: darcy, k: 1e-15}", what);
  memset(law, 0, sizeof *law);
  char why[160];
  if (ydoc_get(y, n, "fit")) {
    const char *keys[] = {"fit", "model", extra, NULL};
    if (ydoc_only_keys(y, n, what, keys)) return -1;
    const char *file = ydoc_string(y, n, "fit");
    yaml_node_t *mn = ydoc_get(y, n, "model");
    const char *model = mn ? ydoc_string(y, n, "model") : "chosen";
    if (!file || !model) return -1;
    char full[4096], err[1024];
    resolve(y->path, file, full, sizeof full);
    int si;
    fluid_props ff;
    if (fit_json_law(full, model, law, &si, &ff, err, sizeof err))
      return ydoc_fail(y, n, "%s: fit file: %s", what, err);
    if (si != c->si)
      return ydoc_fail(y, n, "%s: fit file '%s' is in %s units but this config is in %s units",
                       what, full, si ? "SI" : "reduced", c->si ? "SI" : "reduced");
    if (fabs(ff.mu - c->problem.fluid.mu) > 1e-9 * ff.mu)
      fprintf(stderr, "mdpore darcy: warning: %s:%d: fit '%s' used viscosity %g, config has %g\n",
              y->path, ydoc_line(n), full, ff.mu, c->problem.fluid.mu);
  } else {
    const char *name = ydoc_string(y, n, "law");
    if (!name) return -1;
    int kind = flow_law_from_name(name);
    if (kind < 0)
      return ydoc_fail(y, ydoc_get(y, n, "law"),
                       "%s: key 'law': expected darcy, threshold, forchheimer or power, got '%s'",
                       what, name);
    static const char *keys[LAW_COUNT][3] = {
        {"k", NULL, NULL}, {"k", "G0", NULL}, {"k", "beta", NULL}, {"K", "n", NULL}};
    const char *allowed[] = {"law", keys[kind][0], keys[kind][1], extra, NULL};
    if (!keys[kind][1]) allowed[2] = extra, allowed[3] = NULL;
    if (ydoc_only_keys(y, n, what, allowed)) return -1;
    law->kind = kind;
    double v0 = 0, v1 = 0;
    if (ydoc_number(y, n, keys[kind][0], &v0)) return -1;
    if (keys[kind][1] && ydoc_number(y, n, keys[kind][1], &v1)) return -1;
    if (kind == LAW_POWER)
      law->K = v0, law->n = v1;
    else
      law->k = v0;
    if (kind == LAW_THRESHOLD) law->g0 = v1;
    if (kind == LAW_FORCHHEIMER) law->beta = v1;
  }
  if (flow_law_check(law, why, sizeof why)) return ydoc_fail(y, n, "%s: %s", what, why);
  return 0;
}

static int read_number_list(ydoc *y, const yaml_node_t *map, const char *key, double *v,
                            int *count) {
  yaml_node_t *s = ydoc_get(y, map, key);
  if (!s) return ydoc_fail(y, map, "missing key '%s' (a list of 2 or 3 numbers)", key);
  int n = ydoc_seq_len(s);
  if (!ydoc_is_seq(s) || n < 2 || n > 3)
    return ydoc_fail(y, s, "key '%s': expected a list of 2 or 3 numbers", key);
  for (int i = 0; i < n; i++) {
    char what[64];
    snprintf(what, sizeof what, "key '%s' item %d", key, i + 1);
    if (ydoc_node_number(y, ydoc_seq_item(y, s, i), what, &v[i])) return -1;
  }
  *count = n;
  return 0;
}

static int parse_grid(ydoc *y, const yaml_node_t *g, darcy_config *c) {
  static const char *keys[] = {"cells", "size", NULL};
  if (!g) return ydoc_fail(y, NULL, "missing section 'grid'");
  if (ydoc_only_keys(y, g, "grid", keys)) return -1;
  double cells[3], size[3];
  int nc, ns;
  if (read_number_list(y, g, "cells", cells, &nc) || read_number_list(y, g, "size", size, &ns))
    return -1;
  if (nc != ns) return ydoc_fail(y, g, "grid: 'cells' has %d entries but 'size' has %d", nc, ns);
  darcy_problem *p = &c->problem;
  p->dim = nc;
  for (int a = 0; a < 3; a++) {
    if (a >= nc) {
      p->n[a] = 1;
      p->h[a] = 1.0; /* 2D: unit depth */
      continue;
    }
    if (cells[a] < 1 || cells[a] != floor(cells[a]) || cells[a] > 1e5)
      return ydoc_fail(y, ydoc_get(y, g, "cells"),
                       "grid: 'cells' entry %d: expected a positive integer", a + 1);
    if (!(size[a] > 0))
      return ydoc_fail(y, ydoc_get(y, g, "size"),
                       "grid: 'size' entry %d: expected a positive length", a + 1);
    p->n[a] = (int)cells[a];
    p->h[a] = size[a] / cells[a];
  }
  if (darcy_nblocks(p) > 50000000L) return ydoc_fail(y, g, "grid: more than 5e7 blocks");
  return 0;
}

static int parse_boundary(ydoc *y, const yaml_node_t *b, darcy_config *c) {
  darcy_problem *p = &c->problem;
  if (!b)
    return ydoc_fail(y, NULL,
                     "missing section 'boundary' (at least one face with a fixed pressure)");
  const char *keys[7] = {"x-", "x+", "y-", "y+", NULL, NULL, NULL};
  if (p->dim == 3) keys[4] = "z-", keys[5] = "z+";
  if (ydoc_only_keys(y, b, "boundary", keys)) return -1;
  int any = 0;
  for (int f = 0; f < 2 * p->dim; f++) {
    yaml_node_t *fn = ydoc_get(y, b, face_names[f]);
    if (!fn) continue;
    static const char *fk[] = {"pressure", NULL};
    char what[32];
    snprintf(what, sizeof what, "boundary '%s'", face_names[f]);
    double v;
    if (ydoc_only_keys(y, fn, what, fk) || ydoc_number(y, fn, "pressure", &v)) return -1;
    long n = darcy_face_count(p, f);
    p->fixed[f] = 1;
    p->bc_p[f] = malloc(n * sizeof(double));
    for (long i = 0; i < n; i++) p->bc_p[f][i] = v;
    any = 1;
  }
  if (!any)
    return ydoc_fail(y, b,
                     "boundary: no face has a fixed pressure (the pressure would be undetermined)");
  return 0;
}

static int parse_sources(ydoc *y, const yaml_node_t *s, darcy_config *c) {
  darcy_problem *p = &c->problem;
  if (!s) return 0;
  if (!ydoc_is_seq(s))
    return ydoc_fail(y, s, "sources: expected a list of {block: [i, j(, k)], rate: Q}");
  p->source = calloc(darcy_nblocks(p), sizeof(double));
  for (int i = 0; i < ydoc_seq_len(s); i++) {
    yaml_node_t *it = ydoc_seq_item(y, s, i);
    static const char *keys[] = {"block", "rate", NULL};
    char what[48];
    snprintf(what, sizeof what, "sources item %d", i + 1);
    double idx[3] = {0, 0, 0}, rate;
    int ni;
    if (ydoc_only_keys(y, it, what, keys) || read_number_list(y, it, "block", idx, &ni) ||
        ydoc_number(y, it, "rate", &rate))
      return -1;
    if (ni != p->dim) return ydoc_fail(y, it, "%s: 'block' needs %d indices", what, p->dim);
    for (int a = 0; a < ni; a++)
      if (idx[a] < 0 || idx[a] >= p->n[a] || idx[a] != floor(idx[a]))
        return ydoc_fail(y, it, "%s: block index %d must be an integer in [0, %d)", what, a + 1,
                         p->n[a]);
    p->source[darcy_index(p, (int)idx[0], (int)idx[1], (int)idx[2])] += rate;
  }
  return 0;
}

/* HDF5 dataset of Darcy permeabilities, shape (ny, nx) or (nz, ny, nx), C order = our block order.
 */
static int read_k_dataset(ydoc *y, const yaml_node_t *n, darcy_config *c) {
  static const char *keys[] = {"file", "dataset", NULL};
  if (ydoc_only_keys(y, n, "laws: hdf5", keys)) return -1;
  const char *file = ydoc_string(y, n, "file"), *dset = ydoc_string(y, n, "dataset");
  if (!file || !dset) return -1;
  char full[4096];
  resolve(y->path, file, full, sizeof full);
  darcy_problem *p = &c->problem;
  long nb = darcy_nblocks(p);
  double *k = malloc(nb * sizeof(double));
  int rc = -1;
  H5E_auto2_t old;
  void *old_data;
  H5Eget_auto2(H5E_DEFAULT, &old, &old_data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(full, H5F_ACC_RDONLY, H5P_DEFAULT), d = -1, sp = -1;
  if (f < 0) {
    ydoc_fail(y, n, "laws: hdf5: cannot open '%s'", full);
    goto out;
  }
  d = H5Dopen2(f, dset, H5P_DEFAULT);
  if (d < 0) {
    ydoc_fail(y, n, "laws: hdf5: no dataset '%s' in '%s'", dset, full);
    goto out;
  }
  sp = H5Dget_space(d);
  hsize_t dims[3] = {0, 0, 0};
  int rank = H5Sget_simple_extent_ndims(sp);
  H5Sget_simple_extent_dims(sp, dims, NULL);
  int ok = rank == p->dim;
  for (int a = 0; a < rank && ok; a++) ok = (long)dims[a] == p->n[rank - 1 - a];
  if (!ok) {
    ydoc_fail(y, n, "laws: hdf5: dataset '%s' must have shape %s(%d, %d) to match grid.cells", dset,
              p->dim == 3 ? "(nz, ny, nx) = " : "(ny, nx) = ", p->dim == 3 ? p->n[2] : p->n[1],
              p->dim == 3 ? p->n[1] : p->n[0]);
    goto out;
  }
  if (H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, k) < 0) {
    ydoc_fail(y, n, "laws: hdf5: cannot read '%s' as numbers", dset);
    goto out;
  }
  for (long b = 0; b < nb; b++) {
    if (!(k[b] > 0 && isfinite(k[b]))) {
      ydoc_fail(y, n, "laws: hdf5: dataset '%s' element %ld is %g; permeabilities must be > 0",
                dset, b, k[b]);
      goto out;
    }
    p->laws[b] = (flow_law){.kind = LAW_DARCY, .k = k[b]};
  }
  rc = 0;
out:
  if (sp >= 0) H5Sclose(sp);
  if (d >= 0) H5Dclose(d);
  if (f >= 0) H5Fclose(f);
  H5Eset_auto2(H5E_DEFAULT, old, old_data);
  free(k);
  return rc;
}

static int parse_laws(ydoc *y, const yaml_node_t *l, darcy_config *c) {
  darcy_problem *p = &c->problem;
  static const char *keys[] = {"uniform", "layers", "blocks", "hdf5", NULL};
  if (!l) return ydoc_fail(y, NULL, "missing section 'laws'");
  if (ydoc_only_keys(y, l, "laws", keys)) return -1;
  if (l->data.mapping.pairs.top - l->data.mapping.pairs.start != 1)
    return ydoc_fail(y, l, "laws: give exactly one of uniform, layers, blocks, hdf5");
  long nb = darcy_nblocks(p);
  p->laws = calloc(nb, sizeof(flow_law));
  p->k_lin = calloc(nb, sizeof(double));
  yaml_node_t *n;
  if ((n = ydoc_get(y, l, "uniform"))) {
    flow_law law;
    if (parse_law(y, n, "laws: uniform", c, NULL, &law)) return -1;
    for (long b = 0; b < nb; b++) p->laws[b] = law;
  } else if ((n = ydoc_get(y, l, "layers"))) {
    static const char *lk[] = {"axis", "list", NULL};
    if (ydoc_only_keys(y, n, "laws: layers", lk)) return -1;
    const char *ax = ydoc_string(y, n, "axis");
    if (!ax) return -1;
    int axis = !strcmp(ax, "x") ? 0 : !strcmp(ax, "y") ? 1 : !strcmp(ax, "z") ? 2 : -1;
    if (axis < 0 || axis >= p->dim)
      return ydoc_fail(y, ydoc_get(y, n, "axis"), "laws: layers: 'axis' must be x, y%s, got '%s'",
                       p->dim == 3 ? " or z" : "", ax);
    yaml_node_t *list = ydoc_get(y, n, "list");
    if (!ydoc_is_seq(list) || !ydoc_seq_len(list))
      return ydoc_fail(y, list ? list : n,
                       "laws: layers: 'list' must be a list of laws with 'cells'");
    int start = 0;
    for (int i = 0; i < ydoc_seq_len(list); i++) {
      yaml_node_t *it = ydoc_seq_item(y, list, i);
      char what[48];
      snprintf(what, sizeof what, "laws: layers item %d", i + 1);
      flow_law law;
      long cells;
      if (parse_law(y, it, what, c, "cells", &law) || ydoc_int(y, it, "cells", &cells)) return -1;
      if (cells < 1 || start + cells > p->n[axis])
        return ydoc_fail(y, it, "%s: 'cells' = %ld overruns the %d cells along %s", what, cells,
                         p->n[axis], ax);
      for (int k = 0; k < p->n[2]; k++)
        for (int j = 0; j < p->n[1]; j++)
          for (int ii = 0; ii < p->n[0]; ii++) {
            int c3[3] = {ii, j, k};
            if (c3[axis] >= start && c3[axis] < start + cells)
              p->laws[darcy_index(p, ii, j, k)] = law;
          }
      start += cells;
    }
    if (start != p->n[axis])
      return ydoc_fail(y, list,
                       "laws: layers: the layers cover %d cells but the grid has %d along %s",
                       start, p->n[axis], ax);
  } else if ((n = ydoc_get(y, l, "blocks"))) {
    if (!ydoc_is_seq(n) || ydoc_seq_len(n) != nb)
      return ydoc_fail(
          y, n, "laws: blocks: expected a list of %ld laws (one per block, x fastest), got %d", nb,
          ydoc_seq_len(n));
    for (long b = 0; b < nb; b++) {
      char what[48];
      snprintf(what, sizeof what, "laws: blocks item %ld", b + 1);
      if (parse_law(y, ydoc_seq_item(y, n, (int)b), what, c, NULL, &p->laws[b])) return -1;
    }
  } else if (read_k_dataset(y, ydoc_get(y, l, "hdf5"), c))
    return -1;
  return 0;
}

static int parse_output(ydoc *y, const yaml_node_t *o, darcy_config *c) {
  static const char *keys[] = {"hdf5", "json", "json_blocks", NULL};
  if (!o) return ydoc_fail(y, NULL, "missing section 'output' (hdf5: FILE and/or json: FILE)");
  if (ydoc_only_keys(y, o, "output", keys)) return -1;
  const char *h = ydoc_get(y, o, "hdf5") ? ydoc_string(y, o, "hdf5") : NULL;
  const char *j = ydoc_get(y, o, "json") ? ydoc_string(y, o, "json") : NULL;
  if (y->failed) return -1;
  if (!h && !j) return ydoc_fail(y, o, "output: name an 'hdf5' and/or a 'json' file");
  if (h) resolve(y->path, h, c->hdf5_path, sizeof c->hdf5_path);
  if (j) resolve(y->path, j, c->json_path, sizeof c->json_path);
  c->json_blocks = darcy_nblocks(&c->problem) <= 10000;
  yaml_node_t *jb = ydoc_get(y, o, "json_blocks");
  if (jb) {
    const char *s = ydoc_string(y, o, "json_blocks");
    if (!s || (strcmp(s, "true") && strcmp(s, "false")))
      return ydoc_fail(y, jb, "output: 'json_blocks': expected true or false");
    c->json_blocks = !strcmp(s, "true");
  }
  return 0;
}

static int parse_solver(ydoc *y, const yaml_node_t *s, darcy_config *c) {
  static const char *keys[] = {"rtol", "max_iterations", "power_law_linear_below", NULL};
  c->problem.rtol = 1e-10;
  c->problem.max_it = 50;
  c->g_lin_fraction = 1e-6;
  if (!s) return 0;
  if (ydoc_only_keys(y, s, "solver", keys)) return -1;
  if (ydoc_get(y, s, "rtol") && (ydoc_number(y, s, "rtol", &c->problem.rtol) ||
                                 !(c->problem.rtol > 0 && c->problem.rtol < 1)))
    return ydoc_fail(y, ydoc_get(y, s, "rtol"), "solver: 'rtol': expected a number in (0, 1)");
  long it;
  if (ydoc_get(y, s, "max_iterations")) {
    if (ydoc_int(y, s, "max_iterations", &it) || it < 1)
      return ydoc_fail(y, ydoc_get(y, s, "max_iterations"),
                       "solver: 'max_iterations': expected >= 1");
    c->problem.max_it = (int)it;
  }
  if (ydoc_get(y, s, "power_law_linear_below") &&
      (ydoc_number(y, s, "power_law_linear_below", &c->g_lin_fraction) ||
       !(c->g_lin_fraction > 0 && c->g_lin_fraction < 1)))
    return ydoc_fail(y, ydoc_get(y, s, "power_law_linear_below"),
                     "solver: 'power_law_linear_below': expected a fraction in (0, 1)");
  return 0;
}

int darcy_config_read(const char *path, darcy_config *c, char *err, int errlen) {
  memset(c, 0, sizeof *c);
  ydoc y;
  yaml_node_t *root = ydoc_load(&y, path, err, errlen);
  if (!root) return -1;
  static const char *keys[] = {"units", "grid",   "fluid",  "boundary", "sources",
                               "laws",  "solver", "output", NULL};
  static const char *fk[] = {"viscosity", "density", NULL};
  darcy_problem *p = &c->problem;
  int rc = -1;
  if (ydoc_only_keys(&y, root, "top level", keys)) goto done;
  const char *units = ydoc_string(&y, root, "units");
  if (!units) goto done;
  if (strcmp(units, "SI") && strcmp(units, "reduced")) {
    ydoc_fail(&y, ydoc_get(&y, root, "units"), "key 'units': expected SI or reduced, got '%s'",
              units);
    goto done;
  }
  c->si = !strcmp(units, "SI");
  yaml_node_t *fl = ydoc_get(&y, root, "fluid");
  if (!fl) {
    ydoc_fail(&y, root, "missing section 'fluid' (viscosity, density)");
    goto done;
  }
  if (ydoc_only_keys(&y, fl, "fluid", fk) || ydoc_number(&y, fl, "viscosity", &p->fluid.mu))
    goto done;
  if (!(p->fluid.mu > 0)) {
    ydoc_fail(&y, fl, "fluid: 'viscosity' must be > 0");
    goto done;
  }
  p->fluid.rho = 0.0;
  if (ydoc_get(&y, fl, "density") && ydoc_number(&y, fl, "density", &p->fluid.rho)) goto done;
  if (parse_grid(&y, ydoc_get(&y, root, "grid"), c) ||
      parse_boundary(&y, ydoc_get(&y, root, "boundary"), c) ||
      parse_sources(&y, ydoc_get(&y, root, "sources"), c) ||
      parse_laws(&y, ydoc_get(&y, root, "laws"), c) ||
      parse_solver(&y, ydoc_get(&y, root, "solver"), c) ||
      parse_output(&y, ydoc_get(&y, root, "output"), c))
    goto done;
  for (long b = 0; b < darcy_nblocks(p); b++)
    if (p->laws[b].kind == LAW_FORCHHEIMER && p->laws[b].beta > 0 && !(p->fluid.rho > 0)) {
      ydoc_fail(&y, fl, "fluid: Forchheimer laws need 'density' > 0");
      goto done;
    }
  darcy_problem_linearise(p, c->g_lin_fraction);
  rc = 0;
done:
  if (rc) darcy_problem_free(p);
  ydoc_free(&y);
  return rc;
}
