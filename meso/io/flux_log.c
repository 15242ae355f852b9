/* Flux time series in CSV or HDF5 (see flux_log.h). */
#include "common/hdf5_lock.h"
#include "io/flux_log.h"
#include "common/atomic_file.h"
#include "io/h5_util.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *const columns = "step,time,q,Q,G,u,N";

/* The header: the columns, then q_<species> per phase. */
static void column_names(const scene_t *s, const flux_def_t *d, char *out, size_t len) {
  snprintf(out, len, "%s", columns);
  for (int k = 0; k < d->n_phases; k++) {
    const size_t u = strlen(out);
    snprintf(out + u, len - u, ",q_%s", s->species[d->phase[k]].name);
  }
}

/* The definitions, one line each (CSV comments, HDF5 attribute "definitions"). */
static void definitions(const scene_t *s, const flux_def_t *d, char *out, size_t len) {
  const char ax = "xyz"[d->axis];
  char species[512] = "";
  for (int sp = 0; sp < s->n_species; sp++) {
    if (!(d->mask >> sp & 1u)) continue;
    const size_t u = strlen(species);
    snprintf(species + u, sizeof species - u, "%s%s (N = %.0f, n = %.6g)", u ? ", " : "",
             s->species[sp].name, d->count[sp], d->n[sp]);
  }
  snprintf(out, len,
           "mdpore flux: scene %s, axis %c, every %ld steps, dt %g\n"
           "q = Q / A_total: superficial (Darcy) velocity; A_total = %.10g = V / L_%c, the WHOLE "
           "box cross-section normal to %c, solid included\n"
           "Q = (1/L_%c) sum_s sum_{i in s} v_%c,i / n_s: volumetric flow rate; L_%c = %.10g; "
           "species %s; n from %s; fluid fraction phi = sum_s N_s / (n_s V) = %.6g\n"
           "G = -dp/d%c: %s%s\n"
           "u = mean v_%c of the counted particles (q = phi u for one species); N = counted "
           "particles\n",
           s->name, ax, s->flux.every, s->dt, d->area, ax, ax, ax, ax, ax, d->length, species,
           flux_density_source_name(d->density_source), d->fluid_fraction, ax,
           flux_gradient_source_name(d->gradient_source),
           d->gradient_source == FLUX_G_BODY_FORCE ? " (constant)" : "", ax);
  if (d->n_phases > 0) {
    const size_t u = strlen(out);
    snprintf(out + u, len - u,
             "q_<species> = (1/V) (1/n_s) sum_{i in s} v_%c,i: that phase's superficial velocity "
             "(its share of q; the phases' q add up to q when they are all the counted species)\n",
             ax);
  }
}

/* A CSV restart: keep the rows up to `upto` (rewritten atomically), push their step, q and the
 * phases' q. */
static int csv_cut(const char *path, long upto, int ncol, series_t *steps, series_t *q,
                   series_t *q_phase) {
  FILE *in = fopen(path, "r");
  if (!in) return -1;
  char tmp[SCENE_PATH_LEN + 32];
  FILE *out = atomic_open(path, tmp, sizeof tmp);
  if (!out) {
    fclose(in);
    return -1;
  }
  char line[4096];
  while (fgets(line, sizeof line, in)) {
    if (line[0] == '#' || !strncmp(line, "step,", 5)) {
      fputs(line, out);
      continue;
    }
    char *end;
    const long step = strtol(line, &end, 10);
    if (end == line || *end != ',' || step > upto) continue;
    double row[FLUX_LOG_MAX_COLS] = {0};
    char *c = end;
    for (int k = 1; k < ncol && *c == ','; k++) row[k] = strtod(c + 1, &c);
    series_push(steps, (double)step);
    series_push(q, row[2]);
    for (int k = FLUX_LOG_NCOL; k < ncol; k++) series_push(&q_phase[k - FLUX_LOG_NCOL], row[k]);
    fputs(line, out);
  }
  fclose(in);
  return atomic_commit(out, tmp, path);
}

static int open_csv(flux_log_t *log, const char *head, const char *names, const char *path,
                    int append, series_t *steps, series_t *q, series_t *q_phase, long upto) {
  if (append && csv_cut(path, upto, log->ncol, steps, q, q_phase)) {
    fprintf(stderr, "%s: cannot read back the flux log of the restarted run\n", path);
    return -1;
  }
  log->fp = fopen(path, append ? "a" : "w");
  if (!log->fp) {
    fprintf(stderr, "%s: cannot write the flux log: %s\n", path, strerror(errno));
    return -1;
  }
  if (!append) {
    for (const char *p = head; *p;) {
      const char *nl = strchr(p, '\n');
      fprintf(log->fp, "# %.*s\n", (int)(nl - p), p);
      p = nl + 1;
    }
    fprintf(log->fp, "%s\n", names);
  }
  fflush(log->fp);
  return 0;
}

static int open_h5(flux_log_t *log, const scene_t *s, const flux_def_t *d, const char *head,
                   const char *names, const char *path, int append, series_t *steps, series_t *q,
                   series_t *q_phase, long upto) {
  const int nc = log->ncol;
  if (append) {
    log->file = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (log->file >= 0) log->dset = H5Dopen2(log->file, "flux", H5P_DEFAULT);
    const long rows = log->dset >= 0 ? h5_dataset_rows(log->file, "flux") : -1;
    double *all = rows > 0 ? malloc((size_t)rows * nc * sizeof *all) : NULL;
    if (rows < 0 || (rows > 0 && (!all || h5_read_dataset(log->file, "flux", H5T_NATIVE_DOUBLE, all,
                                                          (hsize_t)rows, nc, path)))) {
      free(all);
      return -1;
    }
    long keep = 0;
    while (keep < rows && all[keep * nc] <= (double)upto) {
      series_push(steps, all[keep * nc]);
      series_push(q, all[keep * nc + 2]);
      for (int k = FLUX_LOG_NCOL; k < nc; k++)
        series_push(&q_phase[k - FLUX_LOG_NCOL], all[keep * nc + k]);
      keep++;
    }
    free(all);
    hsize_t dims[2] = {(hsize_t)keep, (hsize_t)nc};
    H5Dset_extent(log->dset, dims);
    log->rows = keep;
    return 0;
  }
  log->file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (log->file < 0) return -1;
  log->dset = h5_create_row_table(log->file, "flux", nc);
  if (log->dset < 0) return -1;
  h5_attr_string(log->dset, "columns", names);
  h5_attr_string(log->dset, "definitions", head);
  h5_attr_string(log->file, "scene", s->name);
  char ax[2] = {"xyz"[d->axis], 0};
  h5_attr_string(log->dset, "axis", ax);
  h5_attr_double(log->dset, "area_total", &d->area, 1);
  h5_attr_double(log->dset, "length", &d->length, 1);
  h5_attr_double(log->dset, "fluid_fraction", &d->fluid_fraction, 1);
  return 0;
}

static int flux_log_open_unlocked(flux_log_t *log, const scene_t *s, const flux_def_t *d,
                                  const char *path, long restart_step, series_t *steps, series_t *q,
                                  series_t *q_phase) {
  memset(log, 0, sizeof *log);
  log->file = log->dset = -1;
  log->ncol = FLUX_LOG_NCOL + d->n_phases;
  if (!path[0]) return 0;
  const size_t L = strlen(path);
  log->hdf5 = L > 3 && !strcmp(path + L - 3, ".h5");
  const int append = restart_step >= 0 && access(path, F_OK) == 0;
  char head[4096], names[64 + SCENE_MAX_SPECIES * (SCENE_NAME_LEN + 4)];
  definitions(s, d, head, sizeof head);
  column_names(s, d, names, sizeof names);
  const int rc =
      log->hdf5 ? open_h5(log, s, d, head, names, path, append, steps, q, q_phase, restart_step)
                : open_csv(log, head, names, path, append, steps, q, q_phase, restart_step);
  if (rc) {
    if (log->hdf5) fprintf(stderr, "%s: cannot write the HDF5 flux log\n", path);
    flux_log_close(log);
    return -1;
  }
  log->active = 1;
  return 0;
}

static void flux_log_row_unlocked(flux_log_t *log, const flux_sample_t *r) {
  if (!log->active) return;
  double row[FLUX_LOG_MAX_COLS] = {(double)r->step, r->time, r->q, r->Q, r->G, r->u, r->N};
  for (int k = FLUX_LOG_NCOL; k < log->ncol; k++) row[k] = r->q_phase[k - FLUX_LOG_NCOL];
  if (!log->hdf5) {
    fprintf(log->fp, "%ld,%.10g,%.10g,%.10g,%.10g,%.10g,%.0f", r->step, r->time, r->q, r->Q, r->G,
            r->u, r->N);
    for (int k = FLUX_LOG_NCOL; k < log->ncol; k++) fprintf(log->fp, ",%.10g", row[k]);
    fputc('\n', log->fp);
    fflush(log->fp);
    return;
  }
  h5_append_row(log->file, log->dset, log->rows++, log->ncol, row);
}

static void flux_log_close_unlocked(flux_log_t *log) {
  if (log->fp) fclose(log->fp);
  if (log->dset >= 0) H5Dclose(log->dset);
  if (log->file >= 0) H5Fclose(log->file);
  memset(log, 0, sizeof *log);
  log->file = log->dset = -1;
}

/* The public entry points: each whole call under the HDF5 lock (common/hdf5_lock.h). */
int flux_log_open(flux_log_t *log, const scene_t *s, const flux_def_t *d, const char *path,
                  long restart_step, series_t *steps, series_t *q, series_t *q_phase) {
  hdf5_lock();
  const int rc = flux_log_open_unlocked(log, s, d, path, restart_step, steps, q, q_phase);
  hdf5_unlock();
  return rc;
}

void flux_log_row(flux_log_t *log, const flux_sample_t *r) {
  hdf5_lock();
  flux_log_row_unlocked(log, r);
  hdf5_unlock();
}

void flux_log_close(flux_log_t *log) {
  hdf5_lock();
  flux_log_close_unlocked(log);
  hdf5_unlock();
}
