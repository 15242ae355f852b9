/* A coordinate's periodic image in the box [box_lo, box_lo + box_len) along one axis, and whether
 * it lies in a slab [lo, hi) of it: the inlet force's slab (inlet_force.h), a flood's recolouring
 * slabs and census bins (engine/recolor.c, backend/cuda, analysis/flood.c). Both backends. */
#ifndef MESO_PHYSICS_PERIODIC_SLAB_H
#define MESO_PHYSICS_PERIODIC_SLAB_H

#include "hd.h"

#include <math.h>

MESO_HD double periodic_image(double u, double box_lo, double box_len) {
  double w = u - box_lo;
  w -= box_len * floor(w / box_len); /* into [0, L) */
  return box_lo + w;
}

MESO_HD int periodic_in_slab(double u, double lo, double hi, double box_lo, double box_len) {
  const double c = periodic_image(u, box_lo, box_len);
  return c >= lo && c < hi;
}

#endif
