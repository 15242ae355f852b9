/* The flood's series, profiles and saturation maps (flood_log.h). */
#include "common/hdf5_lock.h"
#include "io/flood_log.h"
#include "common/atomic_file.h"
#include "io/h5_util.h"
#include "physics/periodic_slab.h"

#include <errno.h>
#include <hdf5.h>
#include <libgen.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The maps' grid: cells per axis (at least one) of edge about flood.maps.cell, exactly tiling the box. */
static void map_grid(const scene_t *s, int cells[3], double cell[3]) {
  for (int d = 0; d < 3; d++) {
    const double len = s->box_hi[d] - s->box_lo[d];
    cells[d] = (int)ceil(len / s->flood.map_cell - 1e-9);
    if (cells[d] < 1) cells[d] = 1;
    cell[d] = len / cells[d];
  }
}

static FILE *open_text(const char *path, const char *what) {
  FILE *fp = fopen(path, "w");
  if (!fp) fprintf(stderr, "%s: cannot write the flood %s: %s\n", path, what, strerror(errno));
  return fp;
}

static int flood_log_open_unlocked(flood_log_t *log, const scene_t *s, const flood_t *f, int rank) {
  memset(log, 0, sizeof *log);
  if (rank != 0 || !f->on) return 0;
  const scene_flood_t *o = &s->flood;
  const char ax = "xyz"[f->axis];
  const char *inv = s->species[f->inv].name, *def = s->species[f->def].name;
  log->active = 1;
  log->series = open_text(o->path, "series");
  if (!log->series) return -1;
  fprintf(log->series,
          "# mdpore flood: scene %s, axis %c, sample [%g, %g), invading %s, defending %s, start "
          "step %ld, census every %ld steps, dt %g\n"
          "# S_i = N_i / (N_inv + N_def) in the sample; q_i = sum_(j in i, sample) v_%c,j / (n "
          "V_sample): superficial velocity, V_sample = A_total L_sample = %.10g (solid included), "
          "n = %.6g from %s\n"
          "# recovery = 1 - N_def / N_def(start); pvi = pore volumes injected = int u dt / "
          "L_sample (u: mean %c velocity of the liquid in the sample); front = downstream edge "
          "of the farthest bin (of %d) with S_inv >= 1/2, from the inlet face; recolored = "
          "defending particles turned invading on the injection side and in the sink so far; "
          "N_inv_box, N_def_box: the two liquids' particles in the whole box (their sum is "
          "conserved)\n"
          "step,time,S_inv,S_def,N_inv,N_def,q_inv,q_def,recovery,pvi,front,recolored,N_inv_box,"
          "N_def_box\n",
          s->name, ax, f->lo, f->hi, inv, def, o->start, o->every, s->dt, ax, f->volume, f->n_fluid,
          f->density_source, ax, f->nbins);
  fflush(log->series);
  if (o->profile_path[0]) {
    log->profile = open_text(o->profile_path, "profiles");
    if (!log->profile) return -1;
    fprintf(log->profile,
            "# mdpore flood: invading (%s) saturation per bin across the sample along %c; the "
            "header gives each bin's centre measured from the inlet face (empty bin: nan)\nstep",
            inv, ax);
    for (int b = 0; b < f->nbins; b++) fprintf(log->profile, ",%.6g", (b + 0.5) * f->bin_w);
    fprintf(log->profile, "\n");
    fflush(log->profile);
  }
  if (o->map_every > 0) map_grid(s, log->cells, log->cell);
  return 0;
}

static void flood_log_row_unlocked(flood_log_t *log, const flood_t *f, long recolored) {
  if (!log->active) return;
  fprintf(log->series, "%ld,%.10g,%.8g,%.8g,%.0f,%.0f,%.8g,%.8g,%.8g,%.8g,%.6g,%ld,%.0f,%.0f\n",
          f->step, f->time, f->s_inv, 1.0 - f->s_inv, f->n_inv, f->n_def, f->q_inv, f->q_def,
          f->recovery, f->pvi, f->front, recolored, f->box_inv, f->box_def);
  fflush(log->series);
  if (log->profile) {
    fprintf(log->profile, "%ld", f->step);
    for (int b = 0; b < f->nbins; b++) fprintf(log->profile, ",%.5g", flood_bin_saturation(f, b));
    fprintf(log->profile, "\n");
    fflush(log->profile);
  }
}

/* XDMF 3 temporal collection of the map files (paths relative to the index beside them). */
static int write_xdmf(const flood_log_t *log, const scene_t *s) {
  const char *base = s->flood.map_path;
  char path[SCENE_PATH_LEN + 8], tmp[SCENE_PATH_LEN + 48], bcopy[SCENE_PATH_LEN];
  snprintf(path, sizeof path, "%s.xdmf", base);
  FILE *fp = atomic_open(path, tmp, sizeof tmp);
  if (!fp) return -1;
  snprintf(bcopy, sizeof bcopy, "%s", base);
  const char *stem = basename(bcopy);
  const int *c = log->cells;
  fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
              "  <Grid Name=\"flood\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  static const char *const fields[3] = {"saturation", "invading", "defending"};
  for (int k = 0; k < log->n_maps; k++) {
    fprintf(fp, "   <Grid Name=\"step_%ld\" GridType=\"Uniform\">\n    <Time Value=\"%.10g\"/>\n",
            log->map_steps[k], log->map_times[k]);
    /* cell-centred data on a grid of c + 1 nodes per axis, listed z y x (slowest first) */
    fprintf(fp,
            "    <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"%d %d %d\"/>\n"
            "    <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
            "     <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" "
            "Format=\"XML\">%.10g %.10g %.10g</DataItem>\n"
            "     <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" "
            "Format=\"XML\">%.10g %.10g %.10g</DataItem>\n    </Geometry>\n",
            c[2] + 1, c[1] + 1, c[0] + 1, s->box_lo[2], s->box_lo[1], s->box_lo[0], log->cell[2],
            log->cell[1], log->cell[0]);
    for (int q = 0; q < 3; q++)
      fprintf(fp,
              "    <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"Cell\">\n     "
              "<DataItem Dimensions=\"%d %d %d\" NumberType=\"Float\" Precision=\"4\" "
              "Format=\"HDF\">%s_%09ld.h5:/%s</DataItem>\n    </Attribute>\n",
              fields[q], c[2], c[1], c[0], stem, log->map_steps[k], fields[q]);
    fprintf(fp, "   </Grid>\n");
  }
  fprintf(fp, "  </Grid>\n </Domain>\n</Xdmf>\n");
  return atomic_commit(fp, tmp, path);
}

static int write_map_file(const char *path, const scene_t *s, const flood_t *f, const int cells[3],
                          const float *sat, const float *inv, const float *def) {
  char tmp[SCENE_PATH_LEN + 48];
  atomic_tmp_name(path, tmp, sizeof tmp);
  hid_t h = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (h < 0) {
    fprintf(stderr, "%s: cannot create the flood map\n", tmp);
    return -1;
  }
  h5_attr_long(h, "step", f->step);
  h5_attr_double(h, "time", &f->time, 1);
  h5_attr_double(h, "box_lo", s->box_lo, 3);
  h5_attr_double(h, "box_hi", s->box_hi, 3);
  const double dims[3] = {cells[0], cells[1], cells[2]};
  h5_attr_double(h, "cells_xyz", dims, 3);
  h5_attr_string(h, "layout",
                 "C order [z][y][x]; saturation = invading / (invading + defending), "
                 "NaN in cells without liquid; invading, defending: particles per "
                 "rc^3 of the cell");
  h5_attr_string(h, "invading", s->species[f->inv].name);
  h5_attr_string(h, "defending", s->species[f->def].name);
  const hsize_t n[3] = {(hsize_t)cells[2], (hsize_t)cells[1], (hsize_t)cells[0]};
  int rc = 0;
  const char *names[3] = {"saturation", "invading", "defending"};
  const float *data[3] = {sat, inv, def};
  for (int q = 0; q < 3 && !rc; q++) {
    hid_t space = H5Screate_simple(3, n, NULL);
    hid_t d = H5Dcreate2(h, names[q], H5T_IEEE_F32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (d < 0 || H5Dwrite(d, H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, data[q]) < 0) rc = -1;
    if (d >= 0) H5Dclose(d);
    H5Sclose(space);
  }
  if (H5Fclose(h) < 0) rc = -1;
  if (rc) {
    fprintf(stderr, "%s: cannot write the flood map\n", tmp);
    remove(tmp);
    return -1;
  }
  return atomic_rename(tmp, path);
}

static int flood_log_map_unlocked(flood_log_t *log, const scene_t *s, const flood_t *f, sim_t *sim,
                                  int rank) {
  MPI_Comm comm = sim_comm(sim);
  int cells[3];
  double cell[3];
  map_grid(s, cells, cell); /* (every rank: only rank 0 opened the log) */
  const size_t nc = (size_t)cells[0] * cells[1] * cells[2];
  float *cnt = calloc(2 * nc, sizeof *cnt), *sat = rank == 0 ? malloc(nc * sizeof *sat) : NULL;
  int bad = !cnt || (rank == 0 && !sat);
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm);
  if (bad) {
    free(cnt);
    free(sat);
    if (rank == 0) fprintf(stderr, "mdpore: out of memory for a flood map (%zu cells)\n", nc);
    return -1;
  }
  const particles_t *p = sim_particles(sim);
  for (int i = 0; i < p->n_local; i++) {
    const int sp = p->species[i];
    if (sp != f->inv && sp != f->def) continue;
    int ix[3];
    for (int d = 0; d < 3; d++) {
      const double len = s->box_hi[d] - s->box_lo[d];
      ix[d] = (int)((periodic_image(p->x[d][i], s->box_lo[d], len) - s->box_lo[d]) / cell[d]);
      if (ix[d] >= cells[d]) ix[d] = cells[d] - 1;
    }
    const size_t c = ((size_t)ix[2] * cells[1] + ix[1]) * cells[0] + ix[0];
    cnt[(sp == f->inv ? 0 : nc) + c] += 1.0f;
  }
  /* float counts are exact up to 2^24 particles per cell */
  MPI_Reduce(rank == 0 ? MPI_IN_PLACE : cnt, cnt, (int)(2 * nc), MPI_FLOAT, MPI_SUM, 0, comm);
  int rc = 0;
  if (rank == 0) {
    const float inv_vol = (float)(1.0 / (cell[0] * cell[1] * cell[2]));
    for (size_t c = 0; c < nc; c++) {
      const float a = cnt[c], b = cnt[nc + c];
      sat[c] = a + b > 0 ? a / (a + b) : NAN;
      cnt[c] = a * inv_vol;
      cnt[nc + c] = b * inv_vol;
    }
    char path[SCENE_PATH_LEN + 32];
    snprintf(path, sizeof path, "%s_%09ld.h5", s->flood.map_path, f->step);
    rc = write_map_file(path, s, f, cells, sat, cnt, cnt + nc);
    if (!rc && log->n_maps == log->cap_maps) {
      const int cap = log->cap_maps ? 2 * log->cap_maps : 16;
      long *st = realloc(log->map_steps, cap * sizeof *st);
      if (st) log->map_steps = st;
      double *tm = realloc(log->map_times, cap * sizeof *tm);
      if (tm) log->map_times = tm;
      if (!st || !tm)
        rc = -1;
      else
        log->cap_maps = cap;
    }
    if (!rc) {
      log->map_steps[log->n_maps] = f->step;
      log->map_times[log->n_maps] = f->time;
      log->n_maps++;
      rc = write_xdmf(log, s);
    }
  }
  free(cnt);
  free(sat);
  MPI_Bcast(&rc, 1, MPI_INT, 0, comm);
  return rc;
}

static void flood_log_close_unlocked(flood_log_t *log) {
  if (log->series) fclose(log->series);
  if (log->profile) fclose(log->profile);
  free(log->map_steps);
  free(log->map_times);
  memset(log, 0, sizeof *log);
}

/* The public entry points: each whole call under the HDF5 lock (common/hdf5_lock.h). */
int flood_log_open(flood_log_t *log, const scene_t *s, const flood_t *f, int rank) {
  hdf5_lock();
  const int rc = flood_log_open_unlocked(log, s, f, rank);
  hdf5_unlock();
  return rc;
}

void flood_log_row(flood_log_t *log, const flood_t *f, long recolored) {
  hdf5_lock();
  flood_log_row_unlocked(log, f, recolored);
  hdf5_unlock();
}

int flood_log_map(flood_log_t *log, const scene_t *s, const flood_t *f, sim_t *sim, int rank) {
  hdf5_lock();
  const int rc = flood_log_map_unlocked(log, s, f, sim, rank);
  hdf5_unlock();
  return rc;
}

void flood_log_close(flood_log_t *log) {
  hdf5_lock();
  flood_log_close_unlocked(log);
  hdf5_unlock();
}
