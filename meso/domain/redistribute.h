/* Redistribution: every owned particle to the rank whose subdomain holds it, however far away (one
 * all-to-all). Used after the cuts move (load balancing); migration (migrate.h) is the per-step
 * move to a face neighbour. Local order stays deterministic: arrivals in the order of their source
 * ranks, each source's particles in its local order. */
#ifndef MESO_DOMAIN_REDISTRIBUTE_H
#define MESO_DOMAIN_REDISTRIBUTE_H

#include "decomp.h"
#include "particles.h"

#include <stddef.h>

/* Collective over dc->cart. Ghosts are dropped. 0, or -1 with a message (out of memory, a count
 * beyond what one all-to-all can carry); the same answer on every rank. */
int redistribute_particles(const decomp_t *dc, particles_t *p, char *err, size_t errlen);

#endif
