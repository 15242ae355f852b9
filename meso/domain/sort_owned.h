/* Spatial ordering of the owned particles: a stable counting sort by the bin they fall in (same
 * bins as the cell list), done after every migration. Neighbours then sit near each other in every
 * per-particle array (rho, v, id, species are read by index in the pair loops), and ghosts, which
 * are copies of neighbours' owned particles, arrive in the same order. The order is a deterministic
 * function of the positions and the previous order, and sorting an already sorted set changes
 * nothing, so a restart from a checkpoint (which stores the local order) continues bitwise. */
#ifndef MESO_ENGINE_SORT_OWNED_H
#define MESO_ENGINE_SORT_OWNED_H

#include "particles.h"

typedef struct {
  int *key, *count, *perm;
  void *tmp;
  int cap, cap_cells;
} sort_scratch_t;

/* Reorder owned particles (id, species, x, v, f) of a subdomain [lo, hi) by bin of width >= rcut.
 * 0 or -1 (out of memory; the order is then left unchanged). */
int sort_owned_by_bin(particles_t *p, const double lo[3], const double hi[3], double rcut,
                      sort_scratch_t *s);
void sort_scratch_free(sort_scratch_t *s);

#endif
