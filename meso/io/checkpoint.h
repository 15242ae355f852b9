/* Checkpoint/restart: one HDF5 file holding, per rank, the owned particles in their local order
 * (id, species, x, v, f), with the step, the decomposition (rank count and subdomain bounds), the
 * seed and the scene's physics hash. Restarting on the same decomposition continues
 * bitwise-identically: the particles are re-added in the same order and the stored forces are used
 * for the first half-kick. Layout: /rank_counts (int64 nranks), /subdomain_lo, /subdomain_hi
 * (nranks x 3), /id, /species, /position, /velocity, /force (all particles, rank blocks one after
 * another); attributes step, time, nranks, seed, scene_hash, scene. Written by rank 0 into a
 * temporary file and renamed. Checksums: attribute crc32_<dataset> (CRC-32 of each dataset's
 * bytes) and crc32_header (of step, time, nranks, seed, scene_hash); a restart recomputes them and
 * refuses a file whose values differ, naming the file and the dataset (io/crc32.h). */
#ifndef MESO_IO_CHECKPOINT_H
#define MESO_IO_CHECKPOINT_H

#include "engine/sim.h"

/* Collective. 0 or -1. */
int checkpoint_write(const char *path, sim_t *sim);
/* Collective: fill an empty sim (after sim_create, before sim_setup) from a checkpoint; sets the
 * step and marks forces as loaded. Errors (decomposition or scene mismatch, missing file) name the
 * file. */
int checkpoint_read(const char *path, sim_t *sim);

#endif
