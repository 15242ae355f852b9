/* YAML configuration reader for `mdpore darcy` (see darcy_config.h, docs/darcy-config.md). Every
 * mistake stops with "FILE:LINE:COL: key 'a.b': expected ... (got ...)" (common/yaml_tree.h). */
#include "common/memory_limit.h"
#include "darcy_config.h"
#include "darcy_config_keys.h"

#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/yaml_tree.h"
#include "twophase_config_read.h"
#include "darcy_k_dataset.h"
#include "darcy_units.h"
#include "darcy_upscale.h"
#include "fit_json_law.h"

#define TRY(x)                                                                                     \
  do {                                                                                             \
    if ((x) != 0) return -1;                                                                       \
  } while (0)

enum { PATH_LEN = 256, FILE_LEN = 4096 };

static const char *face_names[6] = {"x-", "x+", "y-", "y+", "z-", "z+"};
static const char *const unit_words[] = {"reduced", "SI", NULL}; /* index = si */
static const char *const model_words[] = {"chosen",      "darcy", "threshold",
                                          "forchheimer", "power", NULL};

static void join(char *out, size_t len, const char *path, const char *key) {
  snprintf(out, len, "%s%s%s", path, *path ? "." : "", key);
}

/* A file name at node n (key path `path`), relative to the config file's folder unless absolute. */
int darcy_key_file_name(ytree_t *t, yaml_node_t *n, const char *path, char *out, size_t len) {
  char rel[FILE_LEN], tmp[FILE_LEN];
  TRY(yt_string(t, n, path, rel, sizeof rel));
  snprintf(tmp, sizeof tmp, "%s", t->file);
  const char *dir = rel[0] == '/' ? "" : dirname(tmp);
  size_t nd = strlen(dir);
  const size_t nr = strlen(rel);
  if (nd + nr + 2 > len)
    return yt_error(t, n, path,
                    "expected a path of at most %zu characters with the config's folder (got %zu)",
                    len - 1, nd + 1 + nr);
  memcpy(out, dir, nd);
  if (nd) out[nd++] = '/';
  memcpy(out + nd, rel, nr + 1);
  return 0;
}

/* A required number map.key (full path path.key). */
static int need_number(ytree_t *t, yaml_node_t *map, const char *path, const char *key, double *v) {
  char sub[PATH_LEN];
  join(sub, sizeof sub, path, key);
  yaml_node_t *n = yt_need(t, map, key, sub, "a number");
  return n ? yt_double(t, n, sub, v) : -1;
}

/* A number with an optional unit at node n: "1e-15" (base unit of the system) or "10 mD". Under SI
 * a plain permeability above 1e-7 m^2 (100 kD, beyond any rock) gets a warning: it was probably
 * meant in another unit. */
int darcy_key_quantity(ytree_t *t, yaml_node_t *n, const char *path, darcy_quantity q, int si,
                       double *v) {
  char b[64], why[128] = "not a number", list[96];
  int had = 0;
  if (n && n->type == YAML_SCALAR_NODE && !yt_is_null(n) &&
      !darcy_unit_parse((const char *)n->data.scalar.value, q, si, v, &had, why, sizeof why)) {
    if (q == QTY_PERMEABILITY && si && !had && *v > 1e-7)
      yt_warn(t, n, path,
              "%g m^2 is more permeable than any rock (a plain number is in m^2 under "
              "units: SI; write e.g. '%g mD' for millidarcy)",
              *v, *v);
    return 0;
  }
  return yt_error(t, n, path,
                  "expected a %s: a number in %s or a number with a unit (%s) (got %s: %s)",
                  darcy_quantity_name(q), darcy_unit_label(q, si),
                  darcy_unit_list(q, si, list, sizeof list), yt_describe(n, b, sizeof b), why);
}

/* A required quantity map.key (full path path.key). */
static int need_quantity(ytree_t *t, yaml_node_t *map, const char *path, const char *key,
                         darcy_quantity q, int si, double *v) {
  char sub[PATH_LEN];
  join(sub, sizeof sub, path, key);
  yaml_node_t *n = yt_need(t, map, key, sub, "a number (with an optional unit)");
  return n ? darcy_key_quantity(t, n, sub, q, si, v) : -1;
}

/* A required text value map.key into out. */
static int need_string(ytree_t *t, yaml_node_t *map, const char *path, const char *key,
                       const char *what, char *out, int len) {
  char sub[PATH_LEN];
  join(sub, sizeof sub, path, key);
  yaml_node_t *n = yt_need(t, map, key, sub, what);
  return n ? yt_string(t, n, sub, out, len) : -1;
}

/* The law fitted by `mdpore fit`: {fit: FILE.json, model: chosen|NAME}. */
static int parse_fit_law(ytree_t *t, yaml_node_t *n, const char *path, darcy_config *c,
                         flow_law *law) {
  char fpath[PATH_LEN], mpath[PATH_LEN], full[FILE_LEN];
  join(fpath, sizeof fpath, path, "fit");
  join(mpath, sizeof mpath, path, "model");
  yaml_node_t *fn = yt_get(t, n, "fit"), *mn = yt_get(t, n, "model");
  TRY(darcy_key_file_name(t, fn, fpath, full, sizeof full));
  int m = mn ? yt_enum(t, mn, mpath, model_words) : 0;
  if (m < 0) return -1;
  int si;
  fluid_props ff;
  if (fit_json_law(full, model_words[m], law, &si, &ff, t->quiet))
    return yt_error(t, fn, fpath,
                    "expected a usable `mdpore fit` JSON file (got '%s': see the message above)",
                    full);
  if (si != c->si)
    return yt_error(t, fn, fpath, "expected a fit in %s units like this config (got '%s' in %s)",
                    c->si ? "SI" : "reduced", full, si ? "SI" : "reduced");
  if (fabs(ff.mu - c->problem.fluid.mu) > 1e-9 * ff.mu)
    yt_warn(t, fn, fpath, "fit '%s' used viscosity %g, the config has %g (the config's is used)",
            full, ff.mu, c->problem.fluid.mu);
  return 0;
}

/* One law at `path`: {law: NAME, params...} or {fit: FILE.json, model: chosen|NAME}. An extra key
 * allowed by the caller (e.g. "cells" in a layer) is passed in `extra`. */
static int parse_law(ytree_t *t, yaml_node_t *n, const char *path, darcy_config *c,
                     const char *extra, flow_law *law) {
  char b[64], sub[PATH_LEN], why[160];
  if (!n || n->type != YAML_MAPPING_NODE)
    return yt_error(t, n, path, "expected a law mapping like {law: darcy, k: 1e-15} (got %s)",
                    yt_describe(n, b, sizeof b));
  memset(law, 0, sizeof *law);
  if (yt_get(t, n, "fit")) {
    const char *keys[] = {"fit", "model", extra, NULL};
    TRY(yt_check_keys(t, n, path, keys));
    TRY(parse_fit_law(t, n, path, c, law));
  } else {
    join(sub, sizeof sub, path, "law");
    yaml_node_t *ln = yt_need(t, n, "law", sub, "a law: darcy, threshold, forchheimer or power");
    const int kind = ln ? yt_enum(t, ln, sub, flow_law_names) : -1;
    if (kind < 0) return -1;
    static const char *pk[LAW_COUNT][2] = {{"k", NULL}, {"k", "G0"}, {"k", "beta"}, {"K", "n"}};
    const char *allowed[] = {"law", pk[kind][0], pk[kind][1], extra, NULL};
    if (!pk[kind][1]) allowed[2] = extra, allowed[3] = NULL;
    TRY(yt_check_keys(t, n, path, allowed));
    law->kind = kind;
    double v0 = 0, v1 = 0;
    /* k, G0 and beta carry units; the power law's K (unit depends on n) and n are plain */
    static const int pq[LAW_COUNT][2] = {{QTY_PERMEABILITY, -1},
                                         {QTY_PERMEABILITY, QTY_GRADIENT},
                                         {QTY_PERMEABILITY, QTY_INV_LENGTH},
                                         {-1, -1}};
    for (int m = 0; m < 2 && pk[kind][m]; m++) {
      double *v = m ? &v1 : &v0;
      if (pq[kind][m] >= 0)
        TRY(need_quantity(t, n, path, pk[kind][m], (darcy_quantity)pq[kind][m], c->si, v));
      else
        TRY(need_number(t, n, path, pk[kind][m], v));
    }
    if (kind == LAW_POWER)
      law->K = v0, law->n = v1;
    else
      law->k = v0;
    if (kind == LAW_THRESHOLD) law->g0 = v1;
    if (kind == LAW_FORCHHEIMER) law->beta = v1;
  }
  if (flow_law_check(law, why, sizeof why))
    return yt_error(t, n, path, "expected the parameters of a valid law (%s)", why);
  return 0;
}

/* A block's law at `path`: a scalar law (parse_law: the same along every axis) or a diagonal one,
 * {x: LAW, y: LAW(, z: LAW)}, one scalar law per axis of the grid, each used for the faces normal to
 * its axis. law[a] gets the law along a (law[0] = law[1] = law[2] for a scalar law); *diagonal
 * says which form it was. */
static int parse_block_law(ytree_t *t, yaml_node_t *n, const char *path, darcy_config *c,
                           const char *extra, flow_law law[3], int *diagonal) {
  static const char *const axes[] = {"x", "y", "z"};
  const int dim = c->problem.dim;
  *diagonal = n && n->type == YAML_MAPPING_NODE &&
              (yt_get(t, n, "x") || yt_get(t, n, "y") || yt_get(t, n, "z"));
  if (!*diagonal) {
    TRY(parse_law(t, n, path, c, extra, &law[0]));
    law[1] = law[2] = law[0];
    return 0;
  }
  const char *keys[] = {"x", "y", dim == 3 ? "z" : extra, dim == 3 ? extra : NULL, NULL};
  TRY(yt_check_keys(t, n, path, keys));
  for (int a = 0; a < 3; a++) {
    char sub[PATH_LEN];
    join(sub, sizeof sub, path, axes[a]);
    if (a >= dim) {
      law[a] = law[0];
      continue;
    }
    yaml_node_t *an = yt_need(t, n, axes[a], sub,
                              dim == 3 ? "a law along each of x, y and z (a diagonal law)"
                                       : "a law along each of x and y (a diagonal law)");
    if (!an) return -1;
    TRY(parse_law(t, an, sub, c, NULL, &law[a]));
  }
  return 0;
}

/* Stores the law(s) of block b: a diagonal law gives the problem its per-axis law arrays
 * (darcy_problem_make_diagonal, filled with the scalar laws of the blocks set before). */
static int set_block_law(darcy_problem *p, long b, const flow_law law[3], int diagonal) {
  if (diagonal && !darcy_is_diagonal(p) && darcy_problem_make_diagonal(p)) return -1;
  p->laws[b] = law[0];
  for (int a = 1; a < 3; a++)
    if (p->laws_axis[a]) p->laws_axis[a][b] = law[a];
  return 0;
}

/* A required list of 2 or 3 numbers map.key, each a quantity qty (with an optional unit) or, qty < 0,
 * a plain number; the item nodes go to `at` (for later messages). */
static int need_number_list(ytree_t *t, yaml_node_t *map, const char *path, const char *key,
                            int qty, int si, double v[3], yaml_node_t *at[3], int *count) {
  char sub[PATH_LEN], item[PATH_LEN + 8], b[64];
  join(sub, sizeof sub, path, key);
  yaml_node_t *s = yt_need(t, map, key, sub, "a list of 2 or 3 numbers");
  if (!s) return -1;
  const int n = s->type == YAML_SEQUENCE_NODE ? yt_seq_size(s) : 0;
  if (s->type != YAML_SEQUENCE_NODE)
    return yt_error(t, s, sub, "expected a list of 2 or 3 numbers (got %s)",
                    yt_describe(s, b, sizeof b));
  if (n < 2 || n > 3)
    return yt_error(t, s, sub, "expected a list of 2 or 3 numbers (got a list of %d)", n);
  for (int i = 0; i < n; i++) {
    snprintf(item, sizeof item, "%s[%d]", sub, i);
    at[i] = yt_seq_item(t, s, i);
    if (qty >= 0)
      TRY(darcy_key_quantity(t, at[i], item, (darcy_quantity)qty, si, &v[i]));
    else
      TRY(yt_double(t, at[i], item, &v[i]));
  }
  *count = n;
  return 0;
}

static int parse_grid(ytree_t *t, yaml_node_t *root, darcy_config *c) {
  static const char *const keys[] = {"cells", "size", NULL};
  yaml_node_t *g = yt_need(t, root, "grid", "grid", "a mapping {cells: [...], size: [...]}");
  if (!g) return -1;
  TRY(yt_check_keys(t, g, "grid", keys));
  double cells[3], size[3];
  yaml_node_t *cn[3], *sn[3];
  int nc, ns;
  TRY(need_number_list(t, g, "grid", "cells", -1, c->si, cells, cn, &nc));
  TRY(need_number_list(t, g, "grid", "size", QTY_LENGTH, c->si, size, sn, &ns));
  if (nc != ns)
    return yt_error(t, yt_get(t, g, "size"), "grid.size",
                    "expected %d entries like grid.cells (got %d)", nc, ns);
  darcy_problem *p = &c->problem;
  p->dim = nc;
  for (int a = 0; a < 3; a++) {
    char sub[32];
    if (a >= nc) {
      p->n[a] = 1;
      p->h[a] = 1.0; /* 2D: unit depth */
      continue;
    }
    snprintf(sub, sizeof sub, "grid.cells[%d]", a);
    if (cells[a] < 1 || cells[a] != floor(cells[a]) || cells[a] > 1e5)
      return yt_error(t, cn[a], sub, "expected a positive integer up to 100000 (got %g)", cells[a]);
    snprintf(sub, sizeof sub, "grid.size[%d]", a);
    if (!(size[a] > 0))
      return yt_error(t, sn[a], sub, "expected a positive length (got %g)", size[a]);
    p->n[a] = (int)cells[a];
    p->h[a] = size[a] / cells[a];
  }
  if (darcy_nblocks(p) > 50000000L)
    return yt_error(t, yt_get(t, g, "cells"), "grid.cells", "expected at most 5e7 blocks (got %ld)",
                    darcy_nblocks(p));
  /* the per-block arrays of the problem (laws, k_lin, sources, one face of pressures) */
  const double bytes = (double)darcy_nblocks(p) * (sizeof(flow_law) + 3 * sizeof(double));
  const double limit = mdp_memory_limit();
  if (bytes > limit)
    return yt_error(t, yt_get(t, g, "cells"), "grid.cells",
                    "expected a grid that fits in memory (got %ld blocks, %.3g GB for the blocks "
                    "alone, more than the %.3g GB this machine allows: physical memory, or "
                    "MDPORE_MEMORY_LIMIT in bytes)",
                    darcy_nblocks(p), bytes / 1e9, limit / 1e9);
  return 0;
}

static int parse_boundary(ytree_t *t, yaml_node_t *root, darcy_config *c) {
  darcy_problem *p = &c->problem;
  yaml_node_t *b = yt_need(t, root, "boundary", "boundary",
                           "at least one face with a fixed pressure, like {x-: {pressure: P}}");
  if (!b) return -1;
  const char *keys[7] = {"x-", "x+", "y-", "y+", NULL, NULL, NULL};
  if (p->dim == 3) keys[4] = "z-", keys[5] = "z+";
  TRY(yt_check_keys(t, b, "boundary", keys));
  int any = 0;
  for (int f = 0; f < 2 * p->dim; f++) {
    yaml_node_t *fn = yt_get(t, b, face_names[f]);
    if (!fn) continue;
    static const char *const fk[] = {"pressure", NULL};
    char path[32];
    join(path, sizeof path, "boundary", face_names[f]);
    double v;
    TRY(yt_check_keys(t, fn, path, fk));
    TRY(need_quantity(t, fn, path, "pressure", QTY_PRESSURE, c->si, &v));
    long n = darcy_face_count(p, f);
    p->fixed[f] = 1;
    p->bc_p[f] = malloc(n * sizeof(double));
    if (!p->bc_p[f]) return yt_error(t, fn, path, "out of memory for %ld face values", n);
    for (long i = 0; i < n; i++) p->bc_p[f][i] = v;
    any = 1;
  }
  if (!any)
    return yt_error(t, b, "boundary",
                    "expected at least one face with a fixed pressure (got none: the pressure "
                    "would be undetermined)");
  return 0;
}

static int parse_sources(ytree_t *t, yaml_node_t *s, darcy_config *c) {
  darcy_problem *p = &c->problem;
  char b[64];
  if (!s) return 0;
  if (s->type != YAML_SEQUENCE_NODE)
    return yt_error(t, s, "sources", "expected a list of {block: [i, j(, k)], rate: Q} (got %s)",
                    yt_describe(s, b, sizeof b));
  p->source = calloc(darcy_nblocks(p), sizeof(double));
  if (!p->source)
    return yt_error(t, s, "sources", "out of memory for %ld blocks", darcy_nblocks(p));
  for (int i = 0; i < yt_seq_size(s); i++) {
    yaml_node_t *it = yt_seq_item(t, s, i), *at[3];
    static const char *const keys[] = {"block", "rate", NULL};
    char path[32], sub[64];
    snprintf(path, sizeof path, "sources[%d]", i);
    double idx[3] = {0, 0, 0}, rate;
    int ni;
    TRY(yt_check_keys(t, it, path, keys));
    TRY(need_number_list(t, it, path, "block", -1, c->si, idx, at, &ni));
    TRY(need_number(t, it, path, "rate", &rate));
    join(sub, sizeof sub, path, "block");
    if (ni != p->dim)
      return yt_error(t, yt_get(t, it, "block"), sub, "expected %d indices (got %d)", p->dim, ni);
    for (int a = 0; a < ni; a++)
      if (idx[a] < 0 || idx[a] >= p->n[a] || idx[a] != floor(idx[a])) {
        snprintf(sub, sizeof sub, "%s.block[%d]", path, a);
        return yt_error(t, at[a], sub, "expected an integer in [0, %d) (got %g)", p->n[a], idx[a]);
      }
    p->source[darcy_index(p, (int)idx[0], (int)idx[1], (int)idx[2])] += rate;
  }
  return 0;
}

/* laws.hdf5: {file: k.h5, dataset: name, unit: mD} -- Darcy permeability per block (darcy_k_dataset.h:
 * shape, unit attribute, axis_order attribute). */
static int read_k_dataset(ytree_t *t, yaml_node_t *n, darcy_config *c) {
  static const char *const keys[] = {"file", "dataset", "unit", NULL};
  char dset[PATH_LEN], full[FILE_LEN], unit[32] = "", msg[1024];
  TRY(yt_check_keys(t, n, "laws.hdf5", keys));
  yaml_node_t *fn = yt_need(t, n, "file", "laws.hdf5.file", "an HDF5 file name");
  if (!fn || darcy_key_file_name(t, fn, "laws.hdf5.file", full, sizeof full)) return -1;
  TRY(need_string(t, n, "laws.hdf5", "dataset", "a dataset name", dset, sizeof dset));
  yaml_node_t *un = yt_get(t, n, "unit");
  if (un) TRY(yt_string(t, un, "laws.hdf5.unit", unit, sizeof unit));
  darcy_problem *p = &c->problem;
  long nb = darcy_nblocks(p);
  double *k = malloc(nb * sizeof(double));
  if (!k) return yt_error(t, n, "laws.hdf5", "out of memory for %ld blocks", nb);
  kset_key key;
  int rc = darcy_k_dataset_read(full, dset, p, c->si, unit, k, msg, sizeof msg, &key);
  if (rc) {
    static const char *const paths[] = {"laws.hdf5.file", "laws.hdf5.dataset", "laws.hdf5.unit"};
    yaml_node_t *at = key == KSET_KEY_FILE   ? fn
                      : key == KSET_KEY_UNIT ? un
                                             : yt_get(t, n, "dataset");
    yt_error(t, at, paths[key], "%s", msg);
  } else {
    for (long b = 0; b < nb; b++) p->laws[b] = (flow_law){.kind = LAW_DARCY, .k = k[b]};
  }
  free(k);
  return rc;
}

/* layers: {axis: x|y|z, list: [LAW + {cells: N}, ...]} */
static int parse_layers(ytree_t *t, yaml_node_t *n, darcy_config *c) {
  static const char *const keys[] = {"axis", "list", NULL};
  static const char *const axes3[] = {"x", "y", "z", NULL}, *const axes2[] = {"x", "y", NULL};
  darcy_problem *p = &c->problem;
  char b[64];
  TRY(yt_check_keys(t, n, "laws.layers", keys));
  yaml_node_t *an = yt_need(t, n, "axis", "laws.layers.axis", "x, y or z");
  const int axis = an ? yt_enum(t, an, "laws.layers.axis", p->dim == 3 ? axes3 : axes2) : -1;
  if (axis < 0) return -1;
  const char *ax = axes3[axis];
  yaml_node_t *list = yt_need(t, n, "list", "laws.layers.list", "a list of laws with 'cells'");
  if (!list) return -1;
  if (list->type != YAML_SEQUENCE_NODE || !yt_seq_size(list))
    return yt_error(t, list, "laws.layers.list",
                    "expected a non-empty list of laws with 'cells' (got %s)",
                    yt_describe(list, b, sizeof b));
  int start = 0;
  for (int i = 0; i < yt_seq_size(list); i++) {
    yaml_node_t *it = yt_seq_item(t, list, i);
    char path[48], sub[64];
    snprintf(path, sizeof path, "laws.layers.list[%d]", i);
    join(sub, sizeof sub, path, "cells");
    flow_law law[3];
    int diagonal;
    long cells;
    TRY(parse_block_law(t, it, path, c, "cells", law, &diagonal));
    yaml_node_t *cn = yt_need(t, it, "cells", sub, "a number of cells along the axis");
    if (!cn || yt_long(t, cn, sub, &cells)) return -1;
    if (cells < 1 || start + cells > p->n[axis])
      return yt_error(t, cn, sub,
                      "expected 1 to %d cells (got %ld: overruns the %d cells along %s after "
                      "%d)",
                      p->n[axis] - start, cells, p->n[axis], ax, start);
    for (int k = 0; k < p->n[2]; k++)
      for (int j = 0; j < p->n[1]; j++)
        for (int ii = 0; ii < p->n[0]; ii++) {
          int c3[3] = {ii, j, k};
          if (c3[axis] >= start && c3[axis] < start + cells)
            TRY(set_block_law(p, darcy_index(p, ii, j, k), law, diagonal));
        }
    start += (int)cells;
  }
  if (start != p->n[axis])
    return yt_error(t, list, "laws.layers.list",
                    "expected layers adding up to the %d cells of the grid along %s (got layers "
                    "that cover %d cells)",
                    p->n[axis], ax, start);
  return 0;
}

static int parse_laws(ytree_t *t, yaml_node_t *root, darcy_config *c) {
  darcy_problem *p = &c->problem;
  static const char *const keys[] = {"uniform", "layers", "blocks", "hdf5", NULL};
  char b[64];
  yaml_node_t *l = yt_need(t, root, "laws", "laws", "one of uniform, layers, blocks, hdf5");
  if (!l) return -1;
  TRY(yt_check_keys(t, l, "laws", keys));
  if (yt_map_size(l) != 1)
    return yt_error(t, l, "laws", "expected exactly one of uniform, layers, blocks, hdf5 (got %d)",
                    yt_map_size(l));
  long nb = darcy_nblocks(p);
  p->laws = calloc(nb, sizeof(flow_law));
  p->k_lin = calloc(nb, sizeof(double));
  if (!p->laws || !p->k_lin) return yt_error(t, l, "laws", "out of memory for %ld blocks", nb);
  yaml_node_t *n;
  if ((n = yt_get(t, l, "uniform"))) {
    flow_law law[3];
    int diagonal;
    TRY(parse_block_law(t, n, "laws.uniform", c, NULL, law, &diagonal));
    for (long i = 0; i < nb; i++) TRY(set_block_law(p, i, law, diagonal));
  } else if ((n = yt_get(t, l, "layers"))) {
    TRY(parse_layers(t, n, c));
  } else if ((n = yt_get(t, l, "blocks"))) {
    if (n->type != YAML_SEQUENCE_NODE || yt_seq_size(n) != nb) {
      if (n->type == YAML_SEQUENCE_NODE) snprintf(b, sizeof b, "a list of %d", yt_seq_size(n));
      return yt_error(t, n, "laws.blocks",
                      "expected a list of %ld laws, one per block, x fastest (got %s)", nb,
                      n->type == YAML_SEQUENCE_NODE ? b : yt_describe(n, b, sizeof b));
    }
    for (long i = 0; i < nb; i++) {
      char path[48];
      snprintf(path, sizeof path, "laws.blocks[%ld]", i);
      flow_law law[3];
      int diagonal;
      TRY(parse_block_law(t, yt_seq_item(t, n, (int)i), path, c, NULL, law, &diagonal));
      TRY(set_block_law(p, i, law, diagonal));
    }
  } else {
    TRY(read_k_dataset(t, yt_get(t, l, "hdf5"), c));
  }
  return 0;
}

static int parse_output(ytree_t *t, yaml_node_t *root, darcy_config *c) {
  static const char *const keys[] = {"hdf5", "json", "json_blocks", NULL};
  yaml_node_t *o = yt_need(t, root, "output", "output", "a mapping {hdf5: FILE, json: FILE}"), *n;
  if (!o) return -1;
  TRY(yt_check_keys(t, o, "output", keys));
  if ((n = yt_get(t, o, "hdf5")))
    TRY(darcy_key_file_name(t, n, "output.hdf5", c->hdf5_path, sizeof c->hdf5_path));
  if ((n = yt_get(t, o, "json")))
    TRY(darcy_key_file_name(t, n, "output.json", c->json_path, sizeof c->json_path));
  if (!c->hdf5_path[0] && !c->json_path[0])
    return yt_error(t, o, "output", "expected an 'hdf5' and/or a 'json' file name (got neither)");
  c->json_blocks = darcy_nblocks(&c->problem) <= 10000;
  if ((n = yt_get(t, o, "json_blocks"))) TRY(yt_bool(t, n, "output.json_blocks", &c->json_blocks));
  return 0;
}

/* An optional number of solver in the open interval (0, 1). */
static int fraction(ytree_t *t, yaml_node_t *s, const char *key, double *v) {
  char sub[64];
  join(sub, sizeof sub, "solver", key);
  yaml_node_t *n = yt_get(t, s, key);
  if (!n) return 0;
  TRY(yt_double(t, n, sub, v));
  if (!(*v > 0 && *v < 1)) return yt_error(t, n, sub, "expected a number in (0, 1) (got %g)", *v);
  return 0;
}

static int parse_solver(ytree_t *t, yaml_node_t *s, darcy_config *c) {
  static const char *const keys[] = {"rtol", "max_iterations", "power_law_linear_below", NULL};
  c->problem.rtol = 1e-10;
  c->problem.max_it = 50;
  c->g_lin_fraction = 1e-6;
  if (!s) return 0;
  TRY(yt_check_keys(t, s, "solver", keys));
  TRY(fraction(t, s, "rtol", &c->problem.rtol));
  TRY(fraction(t, s, "power_law_linear_below", &c->g_lin_fraction));
  yaml_node_t *n = yt_get(t, s, "max_iterations");
  if (n) {
    long it;
    TRY(yt_long(t, n, "solver.max_iterations", &it));
    if (it < 1 || it > 1000000)
      return yt_error(t, n, "solver.max_iterations", "expected 1 to 1000000 iterations (got %ld)",
                      it);
    c->problem.max_it = (int)it;
  }
  return 0;
}

static int parse_fluid(ytree_t *t, yaml_node_t *root, darcy_config *c) {
  static const char *const keys[] = {"viscosity", "density", NULL};
  fluid_props *fl = &c->problem.fluid;
  yaml_node_t *f = yt_need(t, root, "fluid", "fluid", "a mapping {viscosity: MU, density: RHO}");
  if (!f) return -1;
  TRY(yt_check_keys(t, f, "fluid", keys));
  TRY(need_quantity(t, f, "fluid", "viscosity", QTY_VISCOSITY, c->si, &fl->mu));
  if (!(fl->mu > 0))
    return yt_error(t, yt_get(t, f, "viscosity"), "fluid.viscosity",
                    "expected a viscosity > 0 (got %g)", fl->mu);
  fl->rho = 0.0;
  yaml_node_t *d = yt_get(t, f, "density");
  return d ? darcy_key_quantity(t, d, "fluid.density", QTY_DENSITY, c->si, &fl->rho) : 0;
}

/* upscale: {conditions: [fixed, linear, periodic]} (default: all three). */
static int parse_upscale(ytree_t *t, yaml_node_t *u, darcy_config *c) {
  static const char *const keys[] = {"conditions", NULL};
  char b[64];
  if (!u) return 0;
  TRY(yt_check_keys(t, u, "upscale", keys));
  yaml_node_t *l = yt_get(t, u, "conditions");
  c->upscale = (1 << UPSCALE_COUNT) - 1;
  if (!l) return 0;
  if (l->type != YAML_SEQUENCE_NODE || !yt_seq_size(l))
    return yt_error(t, l, "upscale.conditions",
                    "expected a non-empty list of fixed, linear, periodic (got %s)",
                    yt_describe(l, b, sizeof b));
  c->upscale = 0;
  for (int i = 0; i < yt_seq_size(l); i++) {
    char path[48];
    snprintf(path, sizeof path, "upscale.conditions[%d]", i);
    int f = yt_enum(t, yt_seq_item(t, l, i), path, darcy_upscale_names);
    if (f < 0) return -1;
    c->upscale |= 1 << f;
  }
  return 0;
}

/* Upscaling: no sources, Darcy laws; the boundary section, if any, is not used. */
static int check_upscale(ytree_t *t, yaml_node_t *root, darcy_config *c) {
  char why[256];
  yaml_node_t *n;
  if ((n = yt_get(t, root, "sources")))
    return yt_error(t, n, "sources",
                    "expected no sources when upscaling (a permeability tensor is defined "
                    "without them; got a sources list)");
  if ((n = yt_get(t, root, "boundary")))
    yt_warn(t, n, "boundary",
            "not used when upscaling: each family (%s%s%s) sets its own boundary conditions",
            c->upscale & 1 ? "fixed " : "", c->upscale & 2 ? "linear " : "",
            c->upscale & 4 ? "periodic" : "");
  if (darcy_upscale_check(&c->problem, c->upscale, why, sizeof why))
    return yt_error(t, yt_get(t, root, "laws"), "laws", "expected laws that can be upscaled: %s",
                    why);
  return 0;
}

/* A two-phase config takes its viscosities and outputs from `twophase`; one with --upscale has no
 * displacement to compute. */
static int check_twophase_keys(ytree_t *t, yaml_node_t *root, yaml_node_t *twophase,
                               const darcy_config *c) {
  yaml_node_t *n;
  if (!twophase) return 0;
  if (c->upscale)
    return yt_error(t, twophase, "twophase",
                    "expected no two-phase block when upscaling (got one: --upscale or `upscale` "
                    "computes a single-phase permeability tensor)");
  if ((n = yt_get(t, root, "fluid")))
    return yt_error(t, n, "fluid",
                    "expected no `fluid` block with `twophase` (got one: the viscosities are "
                    "twophase.mu_w and twophase.mu_o)");
  if ((n = yt_get(t, root, "output")))
    return yt_error(t, n, "output",
                    "expected no top-level `output` with `twophase` (got one: the two-phase files "
                    "are named under twophase.output)");
  return 0;
}

static int parse_document(ytree_t *t, darcy_config *c, int upscale_cli) {
  static const char *const keys[] = {"units",  "grid",   "fluid",   "boundary", "sources", "laws",
                                     "solver", "output", "upscale", "twophase", NULL};
  darcy_problem *p = &c->problem;
  yaml_node_t *root = yt_root(t), *n;
  TRY(yt_check_keys(t, root, "", keys));
  if (!(n = yt_need(t, root, "units", "units", "SI or reduced"))) return -1;
  if ((c->si = yt_enum(t, n, "units", unit_words)) < 0) return -1;
  TRY(parse_upscale(t, yt_get(t, root, "upscale"), c));
  if (upscale_cli && !c->upscale) c->upscale = (1 << UPSCALE_COUNT) - 1;
  yaml_node_t *twophase = yt_get(t, root, "twophase");
  TRY(check_twophase_keys(t, root, twophase, c));
  if (!twophase) TRY(parse_fluid(t, root, c));
  TRY(parse_grid(t, root, c));
  if (!c->upscale) {
    TRY(parse_boundary(t, root, c));
    TRY(parse_sources(t, yt_get(t, root, "sources"), c));
  }
  TRY(parse_laws(t, root, c));
  if (c->upscale) TRY(check_upscale(t, root, c));
  TRY(parse_solver(t, yt_get(t, root, "solver"), c));
  if (twophase) {
    TRY(twophase_config_read(t, twophase, c));
    /* the pressure equation's viscosity: mobilities are scaled relative to mu_w
     * (twophase_impes.c) */
    p->fluid.mu = c->twophase.kr.mu_w;
  } else {
    TRY(parse_output(t, root, c));
  }
  for (int a = 0; a < 3; a++)
    for (long b = 0; b < darcy_nblocks(p); b++) {
      const flow_law *l = darcy_law(p, b, a);
      if (l->kind == LAW_FORCHHEIMER && l->beta > 0 && !(p->fluid.rho > 0)) {
        yaml_node_t *f = yt_get(t, root, "fluid"), *d = yt_get(t, f, "density");
        return yt_error(t, d ? d : f, "fluid.density",
                        "expected a density > 0 for the Forchheimer laws (got %g)", p->fluid.rho);
      }
    }
  darcy_problem_linearise(p, c->g_lin_fraction);
  return 0;
}

static int read_config(const char *path, darcy_config *c, int quiet, int upscale_cli) {
  memset(c, 0, sizeof *c);
  ytree_t t;
  if (yt_load(&t, path, quiet)) return -1;
  const int rc = parse_document(&t, c, upscale_cli);
  if (rc) {
    darcy_problem_free(&c->problem);
    twophase_config_free(&c->twophase);
  }
  yt_free(&t);
  return rc;
}

int darcy_config_read(const char *path, darcy_config *c, int quiet) {
  return read_config(path, c, quiet, 0);
}

int darcy_config_read_upscale(const char *path, darcy_config *c, int quiet) {
  return read_config(path, c, quiet, 1);
}
