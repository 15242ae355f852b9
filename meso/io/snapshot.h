/* HDF5 snapshots of the whole system (gathered to rank 0, serial HDF5 API) and an XDMF index for
 * ParaView. File layout (sorted by id):
 *   /particles/id (int64 N), /particles/species (int32 N), /particles/position (N x 3),
 *   /particles/velocity (N x 3), /particles/density (N, when the engine has densities)
 *   attributes on /: step, time, box_lo, box_hi, scene, species (names, ';'-separated), kernel. */
#ifndef MESO_IO_SNAPSHOT_H
#define MESO_IO_SNAPSHOT_H

#include "engine/sim.h"
#include "io/particle_set.h"

/* Write one snapshot file (atomic) from a set on the calling rank. */
int snapshot_write_set(const char *path, const scene_t *scene, const particle_set_t *set, long step,
                       double time);
/* Read a snapshot file (serial). Species names must match the scene's. 0 or -1 + message. */
int snapshot_read(const char *path, const scene_t *scene, particle_set_t *out, long *step);
/* Rank 0 reads, every rank receives the set (collective). */
int snapshot_read_bcast(const char *path, const scene_t *scene, MPI_Comm comm, particle_set_t *out);

/* A series of snapshots "<base>_<step>.h5" with "<base>.xdmf" rewritten after each one. */
typedef struct {
  char base[1024];
  long *steps;
  double *times;
  long *counts;
  int n, cap;
  int has_rho;
} snapshot_series_t;

void snapshot_series_init(snapshot_series_t *ser, const char *base);
void snapshot_series_free(snapshot_series_t *ser);
/* Collective: gather, write the step's file and the XDMF index on rank 0. 0 or -1. */
int snapshot_series_write(snapshot_series_t *ser, sim_t *sim);
/* A restart at step `upto` (rank 0, after init): take the series' existing files up to that step
 * back into the index (the XDMF is rewritten with them) and remove the files a killed run wrote
 * after it (said on stderr). 0 or -1. */
int snapshot_series_resume(snapshot_series_t *ser, const scene_t *scene, long upto);
/* Path of the snapshot file of a step. */
void snapshot_series_path(const snapshot_series_t *ser, long step, char *out, size_t len);

#endif
