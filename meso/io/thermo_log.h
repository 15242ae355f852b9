/* Thermo time series, written by rank 0: CSV (".csv", metadata lines start with '#') or HDF5
 * (".h5", dataset /thermo of rows x 15 with a "columns" attribute). Columns: step, time, T, KE,
 * Pxx, Pyy, Pzz, Pxy, Pxz, Pyz, p, N, px, py, pz      (p = trace / 3), and with a `geometry:` image
 * penetrations, penetration_depth (mobile particles inside solid voxels). Rows are appended and flushed
 * as the run goes; a restart appends to an existing log after cutting it back to the rows up to the
 * checkpoint's step (rows a killed run wrote after its last checkpoint, and a half-written last
 * line, would otherwise come twice or garbled). */
#ifndef MESO_IO_THERMO_LOG_H
#define MESO_IO_THERMO_LOG_H

#include "engine/sim.h"

#include <hdf5.h>

typedef struct {
  int active; /* rank 0 and a thermo file is set */
  int hdf5;
  FILE *fp;
  hid_t file, dset;
  long rows;
  int ncol; /* 15, or 17 with the penetration columns of a geometry scene */
} thermo_log_t;

/* Rank 0 opens. restart_step >= 0: a restarted run continues an existing log, first cut back to
 * the rows with step <= restart_step (said on stderr when rows are dropped); < 0: a fresh log.
 * 0 or -1 + message. */
int thermo_log_open(thermo_log_t *log, const scene_t *scene, const char *path, long restart_step,
                    int rank);
void thermo_log_row(thermo_log_t *log, const thermo_t *t);
void thermo_log_close(thermo_log_t *log);

#endif
