/* inlet_force, per particle (effects/inlet_force.c): a constant force g per species on the particles
 * whose coordinate along `axis` lies in the slab [lo, hi) of the periodic box (an inlet region).
 * Pressure-driven flow: at steady state the slab's total force F = g N_slab is carried by a
 * pressure step across the slab, dp = F / A (momentum balance of the fluid between two planes that
 * enclose the slab; physics.md section 4), which then pushes the fluid through the sample. */
#ifndef MESO_PHYSICS_INLET_FORCE_H
#define MESO_PHYSICS_INLET_FORCE_H

#include "hd.h"
#include "periodic_slab.h"

#include <math.h>

typedef struct {
  double g[MESO_MAX_SPECIES][3]; /* force per particle of each species inside the slab */
  int axis;                      /* 0..2: the slab's normal                           */
  double lo, hi;                 /* the slab [lo, hi) along axis (box coordinates)     */
  double box_lo, box_len;        /* the box along axis (set by the plan: periodic wrap) */
} inlet_force_params_t;

/* 1 when coordinate u along the axis (any periodic image) lies in [lo, hi). */
MESO_HD int inlet_force_in_slab(const inlet_force_params_t *b, double u) {
  return periodic_in_slab(u, b->lo, b->hi, b->box_lo, b->box_len);
}

MESO_HD void inlet_force_particle_force(const inlet_force_params_t *b, int species,
                                        const double x[3], double f[3]) {
  /* (the coordinate picked by selects: a runtime index would put x in GPU local memory) */
  const double u = b->axis == 0 ? x[0] : (b->axis == 1 ? x[1] : x[2]);
  if (!inlet_force_in_slab(b, u)) return;
  for (int d = 0; d < 3; d++) f[d] += b->g[species][d];
}

#endif
