/* Permeability datasets with units and axis order (see darcy_k_dataset.h). */
#include "darcy_k_dataset.h"

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "darcy_units.h"

/* A string attribute (fixed or variable length) into out; 1 if read, 0 if absent, -1 if unreadable.
 */
static int string_attribute(hid_t d, const char *name, char *out, size_t len) {
  if (H5Aexists(d, name) <= 0) return 0;
  hid_t a = H5Aopen(d, name, H5P_DEFAULT), ty = a >= 0 ? H5Aget_type(a) : -1;
  int rc = -1;
  if (ty >= 0 && H5Tget_class(ty) == H5T_STRING) {
    hid_t mem = H5Tcopy(H5T_C_S1);
    if (H5Tis_variable_str(ty) > 0) {
      char *s = NULL;
      H5Tset_size(mem, H5T_VARIABLE);
      H5Tset_cset(mem, H5Tget_cset(ty));
      if (H5Aread(a, mem, &s) >= 0 && s) {
        snprintf(out, len, "%s", s);
        H5free_memory(s);
        rc = 1;
      }
    } else {
      size_t n = H5Tget_size(ty);
      char *s = calloc(n + 1, 1);
      H5Tset_size(mem, n + 1);
      if (s && H5Aread(a, mem, s) >= 0) {
        snprintf(out, len, "%s", s);
        rc = 1;
      }
      free(s);
    }
    H5Tclose(mem);
  }
  if (ty >= 0) H5Tclose(ty);
  if (a >= 0) H5Aclose(a);
  return rc;
}

static void shape_text(char *out, size_t len, int rank, const long *v) {
  size_t u = (size_t)snprintf(out, len, "(");
  for (int a = 0; a < rank && u < len; a++)
    u += (size_t)snprintf(out + u, len - u, "%s%ld", a ? ", " : "", v[a]);
  if (u < len) snprintf(out + u, len - u, ")");
}

/* axis_order text ("zyx", "z,y,x", "(z, y, x)") -> axes of the dimensions, slowest first. Returns
 * 0 if it names each of the grid's `rank` axes once. */
static int parse_axis_order(const char *text, int rank, int order[3]) {
  int n = 0, seen[3] = {0, 0, 0};
  for (const char *s = text; *s; s++) {
    if (*s == ',' || *s == ' ' || *s == '(' || *s == ')') continue;
    int a = *s == 'x' || *s == 'X'   ? 0
            : *s == 'y' || *s == 'Y' ? 1
            : *s == 'z' || *s == 'Z' ? 2
                                     : 3;
    if (a >= rank || n >= rank || seen[a]) return -1;
    seen[a] = 1;
    order[n++] = a;
  }
  return n == rank ? 0 : -1;
}

/* The dataset's unit (attribute and/or config) -> factor to the base unit. */
static int unit_factor(hid_t d, const char *file, const char *dset, int si, const char *config_unit,
                       double *factor, char *msg, size_t len, kset_key *key) {
  char attr[64] = "", list[96];
  darcy_unit_list(QTY_PERMEABILITY, si, list, sizeof list);
  int has = string_attribute(d, "unit", attr, sizeof attr);
  if (has < 0) {
    snprintf(msg, len,
             "expected a string 'unit' attribute on dataset '%s' of '%s' (got an "
             "unreadable attribute)",
             dset, file);
    return -1;
  }
  if (has && darcy_unit_factor(attr, QTY_PERMEABILITY, si, factor)) {
    snprintf(msg, len,
             "expected the 'unit' attribute of dataset '%s' of '%s' to be one of %s "
             "under units: %s (got '%s')",
             dset, file, list, si ? "SI" : "reduced", attr);
    return -1;
  }
  if (config_unit[0]) {
    double f;
    *key = KSET_KEY_UNIT;
    if (darcy_unit_factor(config_unit, QTY_PERMEABILITY, si, &f)) {
      snprintf(msg, len, "expected one of %s under units: %s (got '%s')", list,
               si ? "SI" : "reduced", config_unit);
      return -1;
    }
    if (has && strcmp(attr, config_unit)) {
      snprintf(msg, len,
               "expected the unit of dataset '%s' of '%s' (its 'unit' attribute says "
               "'%s'; got '%s')",
               dset, file, attr, config_unit);
      return -1;
    }
    *factor = f;
    return 0;
  }
  if (!has && si) {
    snprintf(msg, len,
             "expected a 'unit' attribute (%s) on dataset '%s' of '%s', or the unit "
             "stated in the config as laws.hdf5.unit (got neither: under units: SI a unit-less "
             "permeability is refused)",
             list, dset, file);
    return -1;
  }
  if (!has) *factor = 1.0; /* reduced: rc^2 */
  return 0;
}

static int read_open(hid_t d, const char *file, const char *dset, const darcy_problem *p, int si,
                     const char *config_unit, double *k, char *msg, size_t len, kset_key *key) {
  static const char *const order_c[2] = {"yx", "zyx"};
  double factor = 1.0;
  *key = KSET_KEY_DATASET;
  if (unit_factor(d, file, dset, si, config_unit, &factor, msg, len, key)) return -1;
  *key = KSET_KEY_DATASET;
  const int rank = p->dim;
  char order_text[64];
  int order[3] = {rank - 1, rank - 2, 0}; /* C order: z, y, x or y, x */
  int has_order = string_attribute(d, "axis_order", order_text, sizeof order_text);
  if (has_order < 0 || (has_order && parse_axis_order(order_text, rank, order))) {
    snprintf(msg, len,
             "expected the 'axis_order' attribute of dataset '%s' of '%s' to name each "
             "of the %d grid axes once, slowest first, like '%s' (got '%s')",
             dset, file, rank, order_c[rank - 2], has_order < 0 ? "unreadable" : order_text);
    return -1;
  }
  hid_t sp = H5Dget_space(d);
  hsize_t dims[8] = {0};
  int found = H5Sget_simple_extent_ndims(sp);
  if (found >= 0 && found <= 8) H5Sget_simple_extent_dims(sp, dims, NULL);
  H5Sclose(sp);
  long want[3], got[8];
  int ok = found == rank;
  for (int a = 0; a < rank; a++) want[a] = p->n[order[a]];
  for (int a = 0; a < found && a < 8; a++) {
    got[a] = (long)dims[a];
    if (a < rank) ok &= got[a] == want[a];
  }
  if (!ok) {
    char ws[64], gs[96], names[32] = "(";
    shape_text(ws, sizeof ws, rank, want);
    shape_text(gs, sizeof gs, found > 8 ? 0 : found, got);
    for (int a = 0; a < rank; a++)
      snprintf(names + strlen(names), sizeof names - strlen(names), "%sn%c", a ? ", " : "",
               "xyz"[order[a]]);
    strcat(names, ")");
    snprintf(
        msg, len, "expected dataset '%s' of '%s' of shape %s = %s %s (got shape %s%s)", dset, file,
        names, ws,
        has_order ? "from its axis_order attribute" : "to match grid.cells (C order, x fastest)",
        gs, has_order ? "" : "; a dataset stored x slowest needs an axis_order attribute 'xyz'");
    return -1;
  }
  long nb = darcy_nblocks(p);
  double *raw = malloc(nb * sizeof(double));
  if (!raw) {
    snprintf(msg, len, "out of memory for dataset '%s' of '%s' (%ld blocks)", dset, file, nb);
    return -1;
  }
  if (H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw) < 0) {
    snprintf(msg, len, "expected a dataset of numbers (cannot read dataset '%s' of '%s')", dset,
             file);
    free(raw);
    return -1;
  }
  long stride[3] = {1, 1, 1};
  for (int a = rank - 2; a >= 0; a--) stride[a] = stride[a + 1] * want[a + 1];
  int rc = 0;
  for (int kk = 0; kk < p->n[2] && !rc; kk++)
    for (int j = 0; j < p->n[1] && !rc; j++)
      for (int i = 0; i < p->n[0]; i++) {
        int c[3] = {i, j, kk};
        long m = 0;
        for (int a = 0; a < rank; a++) m += c[order[a]] * stride[a];
        double v = raw[m];
        if (!(v > 0 && isfinite(v))) {
          snprintf(msg, len,
                   "expected permeabilities > 0 (got %g at block (%d, %d, %d), element "
                   "%ld of dataset '%s' of '%s')",
                   v, i, j, kk, m, dset, file);
          rc = -1;
          break;
        }
        k[darcy_index(p, i, j, kk)] = v * factor;
      }
  free(raw);
  return rc;
}

int darcy_k_dataset_read(const char *file, const char *dset, const darcy_problem *p, int si,
                         const char *config_unit, double *k, char *msg, size_t len, kset_key *key) {
  H5E_auto2_t old;
  void *old_data;
  H5Eget_auto2(H5E_DEFAULT, &old, &old_data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  int rc = -1;
  hid_t f = H5Fopen(file, H5F_ACC_RDONLY, H5P_DEFAULT), d = -1;
  if (f < 0) {
    *key = KSET_KEY_FILE;
    snprintf(msg, len, "expected a readable HDF5 file (got '%s')", file);
  } else if ((d = H5Dopen2(f, dset, H5P_DEFAULT)) < 0) {
    *key = KSET_KEY_DATASET;
    snprintf(msg, len, "expected a dataset of '%s' (got '%s': no such dataset)", file, dset);
  } else {
    rc = read_open(d, file, dset, p, si, config_unit, k, msg, len, key);
  }
  if (d >= 0) H5Dclose(d);
  if (f >= 0) H5Fclose(f);
  H5Eset_auto2(H5E_DEFAULT, old, old_data);
  return rc;
}
