/* body_force, per particle (effects/body_force.c): a constant force g per species, a pressure
 * gradient -dp/dx = n m g (physics.md section 4). With reverse_axis = k >= 0 the force is +g below
 * the box centre along k and -g above it: reverse Poiseuille flow (Backer et al. 2005). */
#ifndef MESO_PHYSICS_BODY_FORCE_H
#define MESO_PHYSICS_BODY_FORCE_H

#include "hd.h"

typedef struct {
  double g[MESO_MAX_SPECIES][3]; /* force per particle of each species */
  int reverse_axis;              /* -1: uniform; 0..2: the sign flips at the box centre along it */
  double centre;                 /* box centre along reverse_axis (set by the plan)            */
} body_force_params_t;

MESO_HD void body_force_particle_force(const body_force_params_t *b, int species, const double x[3],
                                       double f[3]) {
  /* (the coordinate picked by selects, not x[axis]: a runtime index would put x in the GPU
   * threads' local memory) */
  const int k = b->reverse_axis;
  const double xk = k == 0 ? x[0] : (k == 1 ? x[1] : x[2]);
  const double sign = (k >= 0 && xk >= b->centre) ? -1.0 : 1.0;
  for (int d = 0; d < 3; d++) f[d] += sign * b->g[species][d];
}

#endif
