/* Collect the owned particles of every rank on one rank (outputs write from rank 0 only). */
#ifndef MESO_IO_GATHER_H
#define MESO_IO_GATHER_H

#include "engine/sim.h"
#include "io/particle_set.h"

/* Collective. On `root`, `out` receives all owned particles in rank order, each rank's in local
 * order; per_rank (nranks entries, may be NULL) receives the counts. Other ranks get an empty set.
 * Forces are included when with_f; densities when the engine has them. 0 or -1 (allocation). */
int gather_particles(sim_t *sim, int root, int with_f, particle_set_t *out, long *per_rank);

/* Broadcast a set held by `root` to every rank (collective). 0 or -1. */
int particle_set_bcast(particle_set_t *set, int root, MPI_Comm comm);
#endif
