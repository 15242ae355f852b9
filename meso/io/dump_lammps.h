/* LAMMPS-style text dump (OVITO reads it): frames appended to one file, particles sorted by id,
 *   ITEM: ATOMS id type x y z vx vy vz fx fy fz [rho]     (type = species + 1; rho when the engine
 * has it) */
#ifndef MESO_IO_DUMP_LAMMPS_H
#define MESO_IO_DUMP_LAMMPS_H

#include "engine/sim.h"

/* Collective: gather to rank 0 and append one frame (truncate = 1 starts a new file). 0 or -1. */
int dump_lammps_frame(const char *path, sim_t *sim, int truncate);

/* A restart at step `upto` (rank 0, before the run appends): cut an existing dump back to its
 * complete frames with TIMESTEP <= upto; a frame a killed run left half-written, and frames after
 * the checkpoint, are dropped (said on stderr). No file: nothing to do. 0 or -1 + message. */
int dump_lammps_trim(const char *path, long upto);

#endif
