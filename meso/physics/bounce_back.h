/* bounce_back, per particle (effects/bounce_back.c): the solid of a voxel image as a boundary. The
 * surface is the voxels' faces (the sign of the image's signed distance at voxel resolution, the
 * same staircase the wall builder and `mdpore foam --walls staircase` use). A mobile particle whose
 * drift ends in a solid voxel goes back to its position before the drift with its velocity reversed
 * relative to the wall of that voxel: v <- 2 u - v, u the velocity of the voxel's wall species (0
 * for walls at rest, v <- -v; species[].velocity for a moving wall, plane Couette). On average no
 * slip relative to the wall, and no particle ever stays inside the solid. */
#ifndef MESO_PHYSICS_BOUNCE_BACK_H
#define MESO_PHYSICS_BOUNCE_BACK_H

#include "hd.h"
#include "voxel_grid.h"

#include <stdint.h>

/* solid[] values: 0 pore; 1 + s a solid voxel of wall species s (s < MESO_MAX_SPECIES);
 * BOUNCE_BACK_SOLID_AT_REST a solid voxel of no species (at rest). */
#define BOUNCE_BACK_SOLID_AT_REST 255
typedef struct {
  const uint8_t *solid; /* [n0 n1 n2], box axes, x fastest: 0 = pore (plan-owned array) */
  voxel_grid_t grid;
  double wall_u[MESO_MAX_SPECIES][3]; /* velocity of each wall species (0 at rest) */
} bounce_back_params_t;

/* 1 when x lies in a solid voxel (periodic axes wrapped; outside a non-periodic face: not solid,
 * the box walls' business). */
MESO_HD int bounce_back_in_solid(const bounce_back_params_t *b, const double x[3]) {
  const long idx = voxel_grid_index(&b->grid, x);
  return idx >= 0 && b->solid[idx] != 0;
}

/* After the drift: back to x_old with v reversed when x is in the solid. Returns 1 when the
 * particle is in the solid even there (it was inside before the step: reported as lost). */
MESO_HD int bounce_back_after_drift(const bounce_back_params_t *b, int i, double x[3], double v[3],
                                    const double x_old[3]) {
  (void)i;
  const long idx = voxel_grid_index(&b->grid, x);
  if (idx < 0 || b->solid[idx] == 0) return 0;
  const int s = b->solid[idx] - 1;
  if (s < MESO_MAX_SPECIES) /* v' = 2 u - v: reversed relative to the wall the particle hit */
    for (int d = 0; d < 3; d++) {
      x[d] = x_old[d];
      v[d] = 2.0 * b->wall_u[s][d] - v[d];
    }
  else
    for (int d = 0; d < 3; d++) {
      x[d] = x_old[d];
      v[d] = -v[d];
    }
  return bounce_back_in_solid(b, x);
}

#endif
