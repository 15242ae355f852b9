/* The flux time series of output.flux (analysis/flux.h has the definitions), written by rank 0: CSV
 * (".csv", '#' lines state the definitions) or HDF5 (".h5", dataset /flux of rows x 7 with a
 * "columns" attribute and the definitions as attributes). Columns: step, time, q, Q, G, u, N, and
 * with output.flux.phases one q_<species> per phase (its superficial velocity, analysis/flux.h).
 * Rows are appended and flushed as the run goes. A restarted run first cuts the file back to the
 * rows up to its checkpoint's step (rows a killed run wrote after its last checkpoint would come
 * twice) and hands them back, so that the steady-state analysis sees the whole series. */
#ifndef MESO_IO_FLUX_LOG_H
#define MESO_IO_FLUX_LOG_H

#include "analysis/block_average.h"
#include "analysis/flux.h"

#include <hdf5.h>
#include <stdio.h>

#define FLUX_LOG_NCOL 7 /* the columns without phases */
#define FLUX_LOG_MAX_COLS (FLUX_LOG_NCOL + SCENE_MAX_SPECIES)

typedef struct {
  int active; /* rank 0 and output.flux set */
  int hdf5;
  int ncol; /* FLUX_LOG_NCOL + the phases */
  FILE *fp;
  hid_t file, dset;
  long rows;
} flux_log_t;

/* Rank 0 opens `path`. With `restart_step` >= 0 (a restarted run) an existing file is kept up to
 * that step and its rows' steps and q are pushed to `steps` and `q` (and each phase's q to
 * q_phase[k], k < def->n_phases); otherwise it is replaced. 0 or -1 + message. */
int flux_log_open(flux_log_t *log, const scene_t *scene, const flux_def_t *def, const char *path,
                  long restart_step, series_t *steps, series_t *q, series_t *q_phase);
void flux_log_row(flux_log_t *log, const flux_sample_t *r);
void flux_log_close(flux_log_t *log);

#endif
