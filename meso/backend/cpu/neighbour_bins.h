/* The 3 x 3 rows of bins around a particle's bin: each row of up to 3 bins is contiguous in bin
 * order, so the neighbours are 9 slot ranges [lo, hi). Bins outside the grid are clipped. */
#ifndef MESO_BACKEND_CPU_NEIGHBOUR_BINS_H
#define MESO_BACKEND_CPU_NEIGHBOUR_BINS_H

#include "domain/cell_list.h"

static inline int neighbour_rows(const cell_list_t *cl, int cell, int lo[9], int hi[9]) {
  int b[3];
  cell_coords(cl, cell, b);
  const int x0 = b[0] > 0 ? b[0] - 1 : 0, x1 = b[0] + 1 < cl->nb[0] ? b[0] + 1 : b[0];
  const int y0 = b[1] > 0 ? b[1] - 1 : 0, y1 = b[1] + 1 < cl->nb[1] ? b[1] + 1 : b[1];
  const int z0 = b[2] > 0 ? b[2] - 1 : 0, z1 = b[2] + 1 < cl->nb[2] ? b[2] + 1 : b[2];
  int n = 0;
  for (int z = z0; z <= z1; z++)
    for (int y = y0; y <= y1; y++) {
      const int row = cl->nb[0] * (y + cl->nb[1] * z);
      lo[n] = cl->start[row + x0];
      hi[n] = cl->start[row + x1 + 1];
      n++;
    }
  return n;
}

/* Slots of all particles in the 27 bins around the particle at slot self (its bin: cell) with
 * r^2 < cut2, the particle itself excluded, in bin order, written to cand (room for 27 *
 * max_per_cell). The filter is branch-free: the slot is always stored and the count advances only
 * for a hit. Returns the number of candidates. */
static inline int gather_candidates(const cell_list_t *cl, int cell, int self, double xi, double yi,
                                    double zi, double cut2, int *cand) {
  int lo[9], hi[9];
  const int nrows = neighbour_rows(cl, cell, lo, hi);
  int m = 0;
  for (int r = 0; r < nrows; r++)
    for (int t = lo[r]; t < hi[r]; t++) {
      const double dx = xi - cl->px[t], dy = yi - cl->py[t], dz = zi - cl->pz[t];
      cand[m] = t;
      m += ((dx * dx + dy * dy + dz * dz) < cut2) & (t != self);
    }
  return m;
}

#endif
