/* HDF5 + JSON output of the continuum solve (see darcy_output.h). */
#include "darcy_output.h"

#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "common/atomic_file.h"
#include "common/json_out.h"
#include "darcy_units.h"

static const char *axis_name[3] = {"x", "y", "z"};

static int string_attribute(hid_t d, const char *name, const char *value) {
  hid_t ts = H5Screate(H5S_SCALAR), ty = H5Tcopy(H5T_C_S1);
  H5Tset_size(ty, strlen(value) + 1);
  hid_t at = H5Acreate2(d, name, ty, ts, H5P_DEFAULT, H5P_DEFAULT);
  int rc = (at < 0 || H5Awrite(at, ty, value) < 0) ? -1 : 0;
  if (at >= 0) H5Aclose(at);
  H5Tclose(ty);
  H5Sclose(ts);
  return rc;
}

/* dataset with dims in C order (slowest first) and "description", "unit" and "axis_order" string
 * attributes (axis_order: the axes of the first dimensions, e.g. "zyx"; NULL: none) */
static int write_dataset(hid_t f, const char *name, int rank, const hsize_t *dims,
                         const double *data, const char *description, const char *unit,
                         const char *axis_order) {
  hid_t sp = H5Screate_simple(rank, dims, NULL);
  hid_t d = H5Dcreate2(f, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  int rc =
      (d < 0 || H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) ? -1 : 0;
  if (d >= 0) {
    rc |= string_attribute(d, "description", description);
    rc |= string_attribute(d, "unit", unit);
    if (axis_order) rc |= string_attribute(d, "axis_order", axis_order);
    H5Dclose(d);
  }
  H5Sclose(sp);
  return rc;
}

int darcy_write_hdf5(const char *path, const darcy_config *c, const double *pressure,
                     const darcy_post *post) {
  const darcy_problem *p = &c->problem;
  char tmp[4200];
  atomic_tmp_name(path, tmp, sizeof tmp);
  hid_t f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) {
    fprintf(stderr, "mdpore darcy: cannot create '%s'\n", tmp);
    return -1;
  }
  int rank = p->dim, si = c->si;
  const char *order = rank == 3 ? "zyx" : "yx";
  const char *pu = darcy_unit_label(QTY_PRESSURE, si);
  const char *ru = darcy_unit_label(rank == 3 ? QTY_RATE : QTY_RATE_2D, si);
  hsize_t dims[4];
  /* C order: (nz,) ny, nx */
  for (int a2 = 0; a2 < rank; a2++) dims[a2] = p->n[rank - 1 - a2];
  int rc = write_dataset(f, "pressure", rank, dims, pressure, "block-centre pressure", pu, order);
  char desc[256];
  for (int ax = 0; ax < p->dim; ax++) {
    hsize_t fd[3];
    for (int a2 = 0; a2 < rank; a2++) fd[a2] = p->n[rank - 1 - a2] + (rank - 1 - a2 == ax);
    char name[32];
    snprintf(name, sizeof name, "flux_%s", axis_name[ax]);
    snprintf(desc, sizeof desc,
             "volumetric flow rate through each %s-face, positive along +%s "
             "(per unit depth in 2D)",
             axis_name[ax], axis_name[ax]);
    rc |= write_dataset(f, name, rank, fd, post->flux[ax], desc, ru, order);
    snprintf(name, sizeof name, "face_pressure_%s", axis_name[ax]);
    rc |= write_dataset(f, name, rank, fd, post->face_p[ax],
                        "pressure on each face (two-point flux)", pu, order);
  }
  for (int a2 = 0; a2 < rank; a2++) dims[a2] = p->n[rank - 1 - a2];
  dims[rank] = 3;
  rc |= write_dataset(f, "block_pressure_drop", rank + 1, dims, post->block_dp,
                      "per block and axis (x, y, z): p(minus face) - p(plus face)", pu, order);
  rc |= write_dataset(f, "block_gradient", rank + 1, dims, post->block_grad,
                      "per block and axis: mean driving gradient G = -dp/dx = drop / cell size",
                      darcy_unit_label(QTY_GRADIENT, si), order);
  if (H5Fclose(f) < 0) rc = -1;
  if (rc) {
    fprintf(stderr, "mdpore darcy: error writing '%s'\n", tmp);
    remove(tmp);
    return -1;
  }
  return atomic_rename(tmp, path);
}

/* "units": the unit of every number of the file. */
static void write_units(json_out *j, const darcy_config *c) {
  int si = c->si;
  json_object(j, "units");
  json_string(j, "permeability", darcy_unit_label(QTY_PERMEABILITY, si));
  json_string(j, "pressure", darcy_unit_label(QTY_PRESSURE, si));
  json_string(j, "gradient", darcy_unit_label(QTY_GRADIENT, si));
  json_string(j, "flow_rate", darcy_unit_label(c->problem.dim == 3 ? QTY_RATE : QTY_RATE_2D, si));
  json_string(j, "length", darcy_unit_label(QTY_LENGTH, si));
  json_string(j, "viscosity", darcy_unit_label(QTY_VISCOSITY, si));
  json_object_end(j);
}

int darcy_write_json(const char *path, const char *config_path, const darcy_config *c,
                     const double *pressure, const darcy_post *post, const darcy_stats *st,
                     int nranks) {
  const darcy_problem *p = &c->problem;
  char tmp[4200];
  FILE *fp = atomic_open(path, tmp, sizeof tmp);
  if (!fp) return -1;
  json_out j;
  json_begin(&j, fp);
  json_string(&j, "format", "mdpore-darcy");
  json_int(&j, "version", 1);
  json_string(&j, "config", config_path);
  json_string(&j, "unit_system", c->si ? "SI" : "reduced");
  json_int(&j, "dim", p->dim);
  json_numbers(&j, "cells", (double[]){p->n[0], p->n[1], p->n[2]}, p->dim);
  json_numbers(&j, "cell_size", p->h, p->dim);
  json_int(&j, "ranks", nranks);
  json_object(&j, "solver");
  json_string(&j, "method",
              st->linear ? "KSP (all blocks Darcy)" : "SNES Newton, analytic Jacobian");
  json_bool(&j, "converged", st->converged);
  json_string(&j, "reason", st->reason);
  json_int(&j, "newton_iterations", st->newton_its);
  json_int(&j, "linear_iterations", st->linear_its);
  json_number(&j, "residual_norm", st->residual);
  json_object_end(&j);
  json_string(&j, "convention",
              "G = -dp/dx; block_gradient[axis] = (p(minus face) - p(plus face)) / "
              "cell size; flux positive along +axis; k_eff = mu Q L / (A dp)");
  write_units(&j, c);
  for (int mD = 0; mD <= c->si; mD++) {
    json_object(&j, mD ? "effective_permeability_mD" : "effective_permeability");
    for (int ax = 0; ax < p->dim; ax++) {
      if (post->keff_defined[ax])
        json_number(&j, axis_name[ax], post->keff[ax] / (mD ? DARCY_MD_IN_M2 : 1.0));
      else
        json_null(&j, axis_name[ax]);
    }
    json_object_end(&j);
  }
  json_numbers(&j, "inflow_minus_faces", post->q_in, p->dim);
  json_numbers(&j, "outflow_plus_faces", post->q_out, p->dim);
  json_number(&j, "total_source", post->total_source);
  json_number(&j, "mass_balance_relative_error", post->mass_balance_rel);
  json_number(&j, "pressure_min", post->pmin);
  json_number(&j, "pressure_max", post->pmax);
  if (c->json_blocks) {
    json_array(&j, "blocks");
    for (int k = 0; k < p->n[2]; k++)
      for (int jj = 0; jj < p->n[1]; jj++)
        for (int i = 0; i < p->n[0]; i++) {
          long b = darcy_index(p, i, jj, k);
          json_object(&j, NULL);
          json_numbers(&j, "index", (double[]){i, jj, k}, p->dim);
          json_string(&j, "law", flow_law_name(p->laws[b].kind));
          json_number(&j, "pressure", pressure[b]);
          json_numbers(&j, "pressure_drop", &post->block_dp[3 * b], p->dim);
          json_numbers(&j, "gradient", &post->block_grad[3 * b], p->dim);
          json_object_end(&j);
        }
    json_array_end(&j);
  }
  json_end(&j);
  return atomic_commit(fp, tmp, path);
}

/* One family's tensor, K[i][j] (NaN where the family does not define it), divided by `unit`. */
static void tensor(const darcy_upscale_result *r, int f, double unit, double *out) {
  for (int i = 0; i < r->dim; i++)
    for (int jj = 0; jj < r->dim; jj++)
      out[i * r->dim + jj] = r->defined[f][i][jj] ? r->k[f][i][jj] / unit : NAN;
}

int darcy_write_upscale_json(const char *path, const char *config_path, const darcy_config *c,
                             const darcy_upscale_result *r, int nranks) {
  const darcy_problem *p = &c->problem;
  char tmp[4200];
  FILE *fp = atomic_open(path, tmp, sizeof tmp);
  if (!fp) return -1;
  json_out j;
  json_begin(&j, fp);
  json_string(&j, "format", "mdpore-darcy-upscale");
  json_int(&j, "version", 1);
  json_string(&j, "config", config_path);
  json_string(&j, "unit_system", c->si ? "SI" : "reduced");
  json_int(&j, "dim", p->dim);
  json_numbers(&j, "cells", (double[]){p->n[0], p->n[1], p->n[2]}, p->dim);
  json_numbers(&j, "cell_size", p->h, p->dim);
  json_string(&j, "cell_size_unit", darcy_unit_label(QTY_LENGTH, c->si));
  json_int(&j, "ranks", nranks);
  json_string(&j, "method",
              "two-point flux finite volumes, harmonic face means; K_ij = mu <q_i> "
              "/ G_j, <q_i> the volume-mean Darcy velocity for a mean driving "
              "gradient G_j along j");
  json_string(&j, "permeability_unit", darcy_unit_label(QTY_PERMEABILITY, c->si));
  json_object(&j, "permeability");
  for (int f = 0; f < UPSCALE_COUNT; f++) {
    if (!r->done[f]) continue;
    double t[9];
    json_object(&j, darcy_upscale_names[f]);
    json_string(&j, "conditions", darcy_upscale_conditions(f));
    json_string(&j, "layout",
                p->dim == 3 ? "row-major [[xx, xy, xz], [yx, yy, yz], [zx, zy, zz]]"
                            : "row-major [[xx, xy], [yx, yy]]");
    tensor(r, f, 1.0, t);
    json_numbers(&j, "tensor", t, p->dim * p->dim);
    if (c->si) {
      tensor(r, f, DARCY_MD_IN_M2, t);
      json_numbers(&j, "tensor_mD", t, p->dim * p->dim);
    }
    json_number(&j, "asymmetry", r->asymmetry[f]);
    json_bool(&j, "converged", r->converged[f]);
    json_string(&j, "reason", r->reason[f]);
    json_int(&j, "linear_iterations", r->linear_its[f]);
    json_number(&j, "seconds", r->seconds[f]);
    json_object_end(&j);
  }
  json_object_end(&j);
  json_end(&j);
  return atomic_commit(fp, tmp, path);
}

int darcy_write_upscale_hdf5(const char *path, const darcy_config *c,
                             const darcy_upscale_result *r) {
  char tmp[4200], name[64], desc[512];
  atomic_tmp_name(path, tmp, sizeof tmp);
  hid_t f = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) {
    fprintf(stderr, "mdpore darcy: cannot create '%s'\n", tmp);
    return -1;
  }
  int rc = 0;
  const hsize_t dims[2] = {(hsize_t)r->dim, (hsize_t)r->dim};
  for (int fam = 0; fam < UPSCALE_COUNT; fam++) {
    if (!r->done[fam]) continue;
    double t[9];
    tensor(r, fam, 1.0, t);
    snprintf(name, sizeof name, "permeability_%s", darcy_upscale_names[fam]);
    snprintf(desc, sizeof desc,
             "effective permeability tensor K[i][j] (row i: flow, column j: "
             "driving gradient; NaN: not defined by these conditions); %s",
             darcy_upscale_conditions(fam));
    rc |= write_dataset(f, name, 2, dims, t, desc, darcy_unit_label(QTY_PERMEABILITY, c->si), NULL);
  }
  if (H5Fclose(f) < 0) rc = -1;
  if (rc) {
    fprintf(stderr, "mdpore darcy: error writing '%s'\n", tmp);
    remove(tmp);
    return -1;
  }
  return atomic_rename(tmp, path);
}
