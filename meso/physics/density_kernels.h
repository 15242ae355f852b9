/* Local-density weight functions w_rho(r) of many-body DPD (physics.md section 1).
 * Both integrate to 1 over space; the self term (r = 0) is never added by the callers. */
#ifndef MESO_PHYSICS_DENSITY_KERNELS_H
#define MESO_PHYSICS_DENSITY_KERNELS_H

#include "hd.h"
#include <math.h>

enum meso_density_kernel { MESO_KERNEL_WARREN = 0, MESO_KERNEL_LUCY = 1 };

/* Warren 2003 / paper eq. 2: w = 15 / (2 pi rd^3) (1 - r/rd)^2 for r < rd. */
MESO_HD meso_real w_rho_warren(meso_real r, meso_real rd) {
  const meso_real q = MESO_R(1.0) - r / rd;
  return (meso_real)(15.0 / (2.0 * MESO_PI)) / (rd * rd * rd) * q * q;
}

/* Lucy kernel as LAMMPS pair mdpd/rhosum defines it (h = rd):
 * w = 105 / (16 pi h^3) (1 + 3 r/h) (1 - r/h)^3 for r < h. */
MESO_HD meso_real w_rho_lucy(meso_real r, meso_real h) {
  const meso_real s = r / h, q = MESO_R(1.0) - s;
  return (meso_real)(105.0 / (16.0 * MESO_PI)) / (h * h * h) * (MESO_R(1.0) + MESO_R(3.0) * s) * q *
         q * q;
}

MESO_HD meso_real w_rho(int kernel, meso_real r, meso_real rd) {
  return kernel == MESO_KERNEL_LUCY ? w_rho_lucy(r, rd) : w_rho_warren(r, rd);
}

/* The same kernels with the normalisation and 1/rd precomputed (hot loops): norm =
 * w_rho_norm(kernel, rd). */
MESO_HD meso_real w_rho_norm(int kernel, meso_real rd) {
  return kernel == MESO_KERNEL_LUCY ? (meso_real)(105.0 / (16.0 * MESO_PI)) / (rd * rd * rd)
                                    : (meso_real)(15.0 / (2.0 * MESO_PI)) / (rd * rd * rd);
}

MESO_HD meso_real w_rho_warren_inv(meso_real r, meso_real inv_rd, meso_real norm) {
  const meso_real q = MESO_R(1.0) - r * inv_rd;
  return norm * q * q;
}

MESO_HD meso_real w_rho_lucy_inv(meso_real r, meso_real inv_h, meso_real norm) {
  const meso_real s = r * inv_h, q = MESO_R(1.0) - s;
  return norm * (MESO_R(1.0) + MESO_R(3.0) * s) * q * q * q;
}

#endif
