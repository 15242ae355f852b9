/* box_walls, per particle (effects/box_walls.c): specular reflection on the non-periodic faces of
 * the box. A particle that crossed x = lo in the drift is mirrored, x <- 2 lo - x, and its normal
 * velocity reversed, v_n <- -v_n (the tangential velocity is kept: a slip wall). */
#ifndef MESO_PHYSICS_BOX_WALLS_H
#define MESO_PHYSICS_BOX_WALLS_H

#include "hd.h"

#include <math.h>

typedef struct {
  double lo[3], hi[3]; /* the box */
  int reflect[3];      /* 1 on the non-periodic axes */
} box_walls_params_t;

/* Reflect after the drift (x_old: the position before it, unused by this flat wall). Returns 1 when
 * the particle is still outside the box (it moved more than a box length, or is not finite). */
MESO_HD int box_walls_after_drift(const box_walls_params_t *w, int i, double x[3], double v[3],
                                  const double x_old[3]) {
  (void)i, (void)x_old;
  int outside = 0;
  for (int d = 0; d < 3; d++) {
    if (!w->reflect[d]) continue;
    const double lo = w->lo[d], hi = w->hi[d];
    if (x[d] < lo) {
      x[d] = 2.0 * lo - x[d];
      v[d] = -v[d];
    } else if (x[d] >= hi) {
      x[d] = 2.0 * hi - x[d];
      v[d] = -v[d];
      if (x[d] >= hi) x[d] = nextafter(hi, lo); /* x == hi exactly: stay inside [lo, hi) */
    }
    if (!(x[d] >= lo && x[d] < hi)) outside = 1;
  }
  return outside;
}

#endif
