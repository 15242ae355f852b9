/* Cell (bin) lists over owned particles and ghosts, rebuilt every step. Bins are at least the
 * cutoff wide, so every neighbour of a particle within the cutoff lies in the 3 x 3 x 3 bins around
 * its own. Positions are copied in bin order (px, py, pz) so the pair loops stream through memory.
 */
#ifndef MESO_ENGINE_CELL_LIST_H
#define MESO_ENGINE_CELL_LIST_H

#include "particles.h"

typedef struct {
  int nb[3]; /* bins per axis */
  int ncell;
  double origin[3];   /* lower corner of bin (0, 0, 0): subdomain lo - rcut */
  double inv_size[3]; /* 1 / bin width */
  int *start;   /* [ncell + 1]: particles of bin c are [start[c], start[c + 1]) in bin order */
  int *idx;     /* [n]: particle index of each bin-ordered slot */
  int *cell_of; /* [n]: bin of each particle (by particle index) */
  double *px, *py, *pz; /* [n]: positions in bin order */
  int max_per_cell; /* largest bin population (sizes the candidate buffers of the pair passes) */
  int cap_cells, cap_part;
} cell_list_t;

/* Bin all particles (owned + ghosts) of p for a subdomain [lo, hi) with ghost width rcut. 0 or -1.
 */
int cell_list_build(cell_list_t *cl, const particles_t *p, const double lo[3], const double hi[3],
                    double rcut);
void cell_list_free(cell_list_t *cl);

/* Bin coordinates of bin c. */
static inline void cell_coords(const cell_list_t *cl, int c, int b[3]) {
  b[0] = c % cl->nb[0];
  b[1] = (c / cl->nb[0]) % cl->nb[1];
  b[2] = c / (cl->nb[0] * cl->nb[1]);
}

#endif
