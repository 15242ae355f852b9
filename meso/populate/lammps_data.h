/* LAMMPS data files, atomic style (for exchanging configurations with LAMMPS and OVITO):
 *   header: "N atoms", "M atom types", "xlo xhi", "ylo yhi", "zlo zhi"
 *   sections: "Masses" (checked against the scene), "Atoms" (id type x y z [ix iy iz]), optional
 *   "Velocities" (id vx vy vz). Atom types 1..M map to the scene's species in order. */
#ifndef MESO_IO_LAMMPS_DATA_H
#define MESO_IO_LAMMPS_DATA_H

#include "io/particle_set.h"
#include "scene/scene.h"

#include <mpi.h>

/* Read a data file (serial). Errors name the file, the line and what was expected. 0 or -1. */
int lammps_data_read(const char *path, const scene_t *scene, particle_set_t *out);
/* Rank 0 reads, every rank receives the set. Collective. */
int lammps_data_read_bcast(const char *path, const scene_t *scene, MPI_Comm comm,
                           particle_set_t *out);
/* Write a set (serial, atomic). Types are species + 1; masses and box from the scene. */
int lammps_data_write(const char *path, const scene_t *scene, const particle_set_t *set, long step);

#endif
