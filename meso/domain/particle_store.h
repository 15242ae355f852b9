/* Allocation and bookkeeping of the particle arrays (particles.h): optional arrays exist only when
 * the plan needs them; every array has the same capacity. */
#ifndef MESO_ENGINE_PARTICLE_STORE_H
#define MESO_ENGINE_PARTICLE_STORE_H

#include "particles.h"

/* Empty storage; rho and vpred are allocated only when asked for. Returns 0 or -1 (out of memory).
 */
int pstore_init(particles_t *p, int with_rho, int with_vpred);
void pstore_free(particles_t *p);
/* Make room for n particles (owned + ghosts), keeping the contents. 0 or -1. */
int pstore_reserve(particles_t *p, int n);
/* Allocate (on = 1) or free the per-particle virial array. 0 or -1. */
int pstore_set_virial(particles_t *p, int on);
/* Copy the state that travels with an owned particle (id, species, x, v, f) from index src to dst.
 */
void pstore_copy(particles_t *p, int dst, int src);

#endif
