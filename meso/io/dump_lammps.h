/* LAMMPS-style text dump (OVITO reads it): frames appended to one file, particles sorted by id,
 *   ITEM: ATOMS id type x y z vx vy vz fx fy fz [rho]     (type = species + 1; rho when the engine
 * has it) */
#ifndef MESO_IO_DUMP_LAMMPS_H
#define MESO_IO_DUMP_LAMMPS_H

#include "engine/sim.h"

/* Collective: gather to rank 0 and append one frame (truncate = 1 starts a new file). 0 or -1. */
int dump_lammps_frame(const char *path, sim_t *sim, int truncate);

#endif
