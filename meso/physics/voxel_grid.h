/* The voxels of a scene's geometry image laid over the box (box axes, x fastest): which voxel holds a
 * position. Shared by the bounce_back boundary (both backends) and the penetration count. */
#ifndef MESO_PHYSICS_VOXEL_GRID_H
#define MESO_PHYSICS_VOXEL_GRID_H

#include "hd.h"

#include <math.h>

typedef struct {
  int n[3];        /* voxels along the box axes */
  double lo[3];    /* box corner */
  double inv_h;    /* 1 / voxel edge (rc) */
  int periodic[3]; /* periodic box axes wrap */
} voxel_grid_t;

/* Linear index of the voxel holding x (periodic axes wrapped), or -1 outside a non-periodic face. */
MESO_HD long voxel_grid_index(const voxel_grid_t *g, const double x[3]) {
  long idx = 0, stride = 1;
  for (int d = 0; d < 3; d++) {
    long i = (long)floor((x[d] - g->lo[d]) * g->inv_h);
    if (g->periodic[d])
      i = ((i % g->n[d]) + g->n[d]) % g->n[d];
    else if (i < 0 || i >= g->n[d])
      return -1;
    idx += i * stride;
    stride *= g->n[d];
  }
  return idx;
}

#endif
