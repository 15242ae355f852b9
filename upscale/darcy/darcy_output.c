/* HDF5 + JSON output of the continuum solve (see darcy_output.h). */
#include "darcy_output.h"

#include <hdf5.h>
#include <stdio.h>
#include <string.h>

#include "common/atomic_file.h"
#include "common/json_out.h"

static const char *axis_name[3] = {"x", "y", "z"};

/* dataset with dims in C order (slowest first) and a "unit"/"description" attribute pair */
static int write_dataset(hid_t f, const char *name, int rank, const hsize_t *dims,
                         const double *data, const char *description) {
  hid_t sp = H5Screate_simple(rank, dims, NULL);
  hid_t d = H5Dcreate2(f, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  int rc =
      (d < 0 || H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) ? -1 : 0;
  if (d >= 0) {
    hid_t ts = H5Screate(H5S_SCALAR), ty = H5Tcopy(H5T_C_S1);
    H5Tset_size(ty, strlen(description) + 1);
    hid_t at = H5Acreate2(d, "description", ty, ts, H5P_DEFAULT, H5P_DEFAULT);
    if (at < 0 || H5Awrite(at, ty, description) < 0) rc = -1;
    if (at >= 0) H5Aclose(at);
    H5Tclose(ty);
    H5Sclose(ts);
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
  int rank = p->dim;
  hsize_t dims[4];
  /* C order: (nz,) ny, nx */
  for (int a2 = 0; a2 < rank; a2++) dims[a2] = p->n[rank - 1 - a2];
  int rc = write_dataset(f, "pressure", rank, dims, pressure, "block-centre pressure");
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
    rc |= write_dataset(f, name, rank, fd, post->flux[ax], desc);
    snprintf(name, sizeof name, "face_pressure_%s", axis_name[ax]);
    rc |= write_dataset(f, name, rank, fd, post->face_p[ax],
                        "pressure on each face (two-point flux)");
  }
  for (int a2 = 0; a2 < rank; a2++) dims[a2] = p->n[rank - 1 - a2];
  dims[rank] = 3;
  rc |= write_dataset(f, "block_pressure_drop", rank + 1, dims, post->block_dp,
                      "per block and axis (x, y, z): p(minus face) - p(plus face)");
  rc |= write_dataset(f, "block_gradient", rank + 1, dims, post->block_grad,
                      "per block and axis: mean driving gradient G = -dp/dx = drop / cell size");
  if (H5Fclose(f) < 0) rc = -1;
  if (rc) {
    fprintf(stderr, "mdpore darcy: error writing '%s'\n", tmp);
    remove(tmp);
    return -1;
  }
  return atomic_rename(tmp, path);
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
  json_object(&j, "effective_permeability");
  for (int ax = 0; ax < p->dim; ax++) {
    if (post->keff_defined[ax])
      json_number(&j, axis_name[ax], post->keff[ax]);
    else
      json_null(&j, axis_name[ax]);
  }
  json_object_end(&j);
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
