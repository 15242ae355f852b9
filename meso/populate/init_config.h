/* Initial configurations: fill regions (lattice or random), LAMMPS data files, HDF5 snapshots,
 * geometry images. Every rank generates or reads the same global set and offers each particle to
 * sim_add_particle, which keeps the ones in its subdomain; a geometry image is built rank-locally
 * instead (populate/image_walls.h: each rank generates the particles of the voxels overlapping its
 * subdomain, with the ids of the whole list). Velocities not given by the source are Maxwell-Boltzmann
 * at the scene's initial temperature, keyed on the particle id (independent of the decomposition),
 * with the centre-of-mass velocity of the mobile particles removed; frozen species get v = 0. */
#ifndef MESO_IO_INIT_CONFIG_H
#define MESO_IO_INIT_CONFIG_H

#include "engine/sim.h"
#include "io/particle_set.h"

/* Build the scene's initial configuration (scene.init) into sim (before sim_setup). 0 or -1 +
 * message. */
int init_configuration(sim_t *sim, const scene_t *scene);

/* Number of particles fill region k generates (its shape applied), the number of candidate sites
 * of its axis-aligned region, and the i-th candidate's position. */
long init_fill_count(const scene_t *scene, int k);
long init_fill_candidates(const scene_t *scene, int k);
void init_fill_position(const scene_t *scene, int k, long i, double x[3]);

/* Shaped fills (init_shape.c): the candidates that the region's cylinder or sphere keeps. Count
 * them (and store their indices in `kept` unless NULL); or a malloc'ed list of them (NULL: out of
 * memory). */
long init_fill_kept(const scene_t *scene, int k, long *kept);
long *init_fill_kept_list(const scene_t *scene, int k);

/* Maxwell-Boltzmann velocity of particle `id` of a species at temperature kT (0 for frozen
 * species). */
/* Is x inside the region's cylinder or sphere (outside it, with f->outside; 1 without a shape)?
 * The plain distance in the box frame, no periodic image (init_shape.c). */
int init_shape_keeps(const scene_fill_t *f, const double x[3]);

void init_mb_velocity(const scene_t *scene, int64_t id, int species, double kT, double v[3]);

/* Offer every particle of a global set to sim; velocities are generated when the set has none.
 * Checks that every particle landed on exactly one rank. Collective. 0 or -1 + message. */
int init_offer_set(sim_t *sim, const scene_t *scene, const particle_set_t *set, const char *source);

#endif
