/* Thermo time series in CSV or HDF5 (see thermo_log.h). */
#include "common/hdf5_lock.h"
#include "io/thermo_log.h"
#include "io/h5_util.h"
#include "physics/density_kernels.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define NCOL_MAX 17
static const char *const columns = "step,time,T,KE,Pxx,Pyy,Pzz,Pxy,Pxz,Pyz,p,N,px,py,pz";
/* With a geometry image: mobile particles inside solid voxels, and the deepest one's depth (rc). */
static const char *const columns_geometry =
    "step,time,T,KE,Pxx,Pyy,Pzz,Pxy,Pxz,Pyz,p,N,px,py,pz,penetrations,penetration_depth";

/* A restarted CSV log: cut the file at the first data row with a step after `upto`, or at a last
 * line without its newline (a killed write). Rows are in step order. 0 or -1. */
static int csv_trim(const char *path, long upto) {
  FILE *fp = fopen(path, "r");
  if (!fp) return -1;
  char line[4096];
  long keep = 0, dropped = 0;
  int cut = 0;
  while (!cut && fgets(line, sizeof line, fp)) {
    const size_t L = strlen(line);
    char *end;
    const long step = strtol(line, &end, 10);
    const int data = line[0] != '#' && end != line && *end == ',';
    if (L == 0 || line[L - 1] != '\n' || (data && step > upto)) {
      cut = 1;
      break;
    }
    keep = ftell(fp);
  }
  if (cut) {
    dropped = 1;
    while (fgets(line, sizeof line, fp))
      if (line[strlen(line) - 1] == '\n') dropped++;
  }
  fclose(fp);
  if (!cut) return 0;
  if (truncate(path, keep) != 0) {
    fprintf(stderr, "%s: cannot cut the thermo log back to step %ld: %s\n", path, upto,
            strerror(errno));
    return -1;
  }
  fprintf(stderr, "mdpore: %s: restart at step %ld: dropped %ld row(s) written after it\n", path,
          upto, dropped);
  return 0;
}

/* A restarted HDF5 log: keep the rows with step <= upto. 0 or -1. */
static int h5_trim(thermo_log_t *log, const char *path, long upto) {
  const long rows = log->rows;
  if (rows <= 0) return 0;
  double *all = malloc((size_t)rows * (size_t)log->ncol * sizeof *all);
  if (!all || h5_read_dataset(log->file, "thermo", H5T_NATIVE_DOUBLE, all, (hsize_t)rows,
                              (hsize_t)log->ncol, path)) {
    free(all);
    return -1;
  }
  long keep = 0;
  while (keep < rows && all[keep * log->ncol] <= (double)upto) keep++;
  free(all);
  if (keep == rows) return 0;
  hsize_t dims[2] = {(hsize_t)keep, (hsize_t)log->ncol};
  if (H5Dset_extent(log->dset, dims) < 0) return -1;
  fprintf(stderr, "mdpore: %s: restart at step %ld: dropped %ld row(s) written after it\n", path,
          upto, rows - keep);
  log->rows = keep;
  return 0;
}

static int thermo_log_open_unlocked(thermo_log_t *log, const scene_t *s, const char *path,
                                    long restart_step, int rank) {
  memset(log, 0, sizeof *log);
  log->file = log->dset = -1;
  if (rank != 0 || !path[0]) return 0;
  const int append = restart_step >= 0;
  log->ncol = s->geometry.on ? 17 : 15;
  const char *const names = s->geometry.on ? columns_geometry : columns;
  const int NCOL = log->ncol;
  const size_t L = strlen(path);
  log->hdf5 = L > 3 && !strcmp(path + L - 3, ".h5");
  const int exists = access(path, F_OK) == 0;
  if (!log->hdf5) {
    if (append && exists && csv_trim(path, restart_step)) return -1;
    log->fp = fopen(path, append && exists ? "a" : "w");
    if (!log->fp) {
      fprintf(stderr, "%s: cannot write thermo log: %s\n", path, strerror(errno));
      return -1;
    }
    if (!(append && exists))
      fprintf(log->fp,
              "# mdpore thermo: scene %s, kernel %s, dt %g, seed %llu; P = full virial pressure "
              "tensor\n%s\n",
              s->name, s->density_kernel == MESO_KERNEL_LUCY ? "lucy" : "warren", s->dt,
              (unsigned long long)s->seed, names);
    fflush(log->fp);
  } else {
    if (append && exists) {
      log->file = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
      if (log->file >= 0) {
        log->dset = H5Dopen2(log->file, "thermo", H5P_DEFAULT);
        log->rows = h5_dataset_rows(log->file, "thermo");
        if (log->dset >= 0 && h5_trim(log, path, restart_step)) {
          fprintf(stderr, "%s: cannot cut the HDF5 thermo log back to step %ld\n", path,
                  restart_step);
          thermo_log_close(log);
          return -1;
        }
      }
    } else {
      log->file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
      if (log->file >= 0) {
        log->dset = h5_create_row_table(log->file, "thermo", (hsize_t)NCOL);
        if (log->dset >= 0) h5_attr_string(log->dset, "columns", names);
        h5_attr_string(log->file, "scene", s->name);
      }
    }
    if (log->file < 0 || log->dset < 0) {
      fprintf(stderr, "%s: cannot write HDF5 thermo log\n", path);
      thermo_log_close(log);
      return -1;
    }
  }
  log->active = 1;
  return 0;
}

static void thermo_log_row_unlocked(thermo_log_t *log, const thermo_t *t) {
  if (!log->active) return;
  const double *P = t->pressure;
  const int NCOL = log->ncol;
  const double row[NCOL_MAX] = {(double)t->step,
                                t->time,
                                t->temperature,
                                t->ke,
                                P[0],
                                P[1],
                                P[2],
                                P[3],
                                P[4],
                                P[5],
                                (P[0] + P[1] + P[2]) / 3.0,
                                (double)t->n_total,
                                t->momentum[0],
                                t->momentum[1],
                                t->momentum[2],
                                (double)t->penetrations,
                                t->penetration_depth};
  if (!log->hdf5) {
    fprintf(log->fp, "%ld,%.10g", t->step, t->time);
    for (int k = 2; k < NCOL; k++) {
      if (k == 11)
        fprintf(log->fp, ",%ld", t->n_total);
      else if (k == 15)
        fprintf(log->fp, ",%ld", t->penetrations);
      else
        fprintf(log->fp, ",%.10g", row[k]);
    }
    fputc('\n', log->fp);
    fflush(log->fp);
    return;
  }
  h5_append_row(log->file, log->dset, log->rows++, (hsize_t)NCOL, row);
}

static void thermo_log_close_unlocked(thermo_log_t *log) {
  if (log->fp) fclose(log->fp);
  if (log->dset >= 0) H5Dclose(log->dset);
  if (log->file >= 0) H5Fclose(log->file);
  memset(log, 0, sizeof *log);
  log->file = log->dset = -1;
}

/* The public entry points: each whole call under the HDF5 lock (common/hdf5_lock.h). */
int thermo_log_open(thermo_log_t *log, const scene_t *s, const char *path, long restart_step,
                    int rank) {
  hdf5_lock();
  const int rc = thermo_log_open_unlocked(log, s, path, restart_step, rank);
  hdf5_unlock();
  return rc;
}

void thermo_log_row(thermo_log_t *log, const thermo_t *t) {
  hdf5_lock();
  thermo_log_row_unlocked(log, t);
  hdf5_unlock();
}

void thermo_log_close(thermo_log_t *log) {
  hdf5_lock();
  thermo_log_close_unlocked(log);
  hdf5_unlock();
}
