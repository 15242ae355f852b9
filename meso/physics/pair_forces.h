/* Pair force magnitudes of (many-body) DPD along e = r_ij / r (physics.md section 1, paper eq. 1):
 *   F_ij = [ A w_c(r) + B (rho_i + rho_j) w_d(r) ] e
 *          - gamma w_D(r) (e . v_ij) e + sigma w_R(r) xi / sqrt(dt) e
 * Each function returns the scalar that multiplies e; positive pushes i away from j. */
#ifndef MESO_PHYSICS_PAIR_FORCES_H
#define MESO_PHYSICS_PAIR_FORCES_H

#include "hd.h"
#include <math.h>

/* Conservative term A w_c(r), w_c = 1 - r/rc: mDPD attraction (A < 0) or standard DPD repulsion (a
 * > 0). */
MESO_HD meso_real pair_conservative(meso_real A, meso_real r, meso_real rc) {
  return A * (MESO_R(1.0) - r / rc);
}

/* Many-body repulsion B (rho_i + rho_j) w_d(r), w_d = 1 - r/rd (Warren 2003). */
MESO_HD meso_real pair_manybody(meso_real B, meso_real rho_i, meso_real rho_j, meso_real r,
                                meso_real rd) {
  return B * (rho_i + rho_j) * (MESO_R(1.0) - r / rd);
}

/* Thermostat weight w_R = (1 - r/rc)^s; w_D = w_R^2 (fluctuation-dissipation, Espanol & Warren
 * 1995). s < 1 widens the weight and raises the viscosity (Fan et al., Phys. Fluids 18, 063102,
 * 2006). For s != 1, q = 1 - r/rc may round to just below 0 at r ~ rc (pow would give NaN): 0 then. */
MESO_HD meso_real pair_weight_random(meso_real r, meso_real rc, meso_real s) {
  const meso_real q = MESO_R(1.0) - r / rc;
  if (s == MESO_R(1.0)) return q;
  return q > MESO_R(0.0) ? (meso_real)pow(q, s) : MESO_R(0.0);
}

/* Dissipative + random term: -gamma w_R^2 (e . v_ij) + sigma w_R xi / sqrt(dt), sigma^2 = 2 gamma
 * kT. */
MESO_HD meso_real pair_thermostat(meso_real gamma, meso_real sigma, meso_real wR, meso_real e_dot_v,
                                  meso_real xi, meso_real inv_sqrt_dt) {
  return -gamma * wR * wR * e_dot_v + sigma * wR * xi * inv_sqrt_dt;
}

/* Forms with precomputed reciprocal cutoffs for the hot loops (no division per pair). They evaluate
 * the same expressions as above with r/rc replaced by r * inv_rc. */
MESO_HD meso_real pair_conservative_inv(meso_real A, meso_real r, meso_real inv_rc) {
  return A * (MESO_R(1.0) - r * inv_rc);
}

MESO_HD meso_real pair_manybody_inv(meso_real B, meso_real rho_sum, meso_real r, meso_real inv_rd) {
  return B * rho_sum * (MESO_R(1.0) - r * inv_rd);
}

/* w_R = (1 - r/rc)^s of the pair (pair_coef_t.s_exp); s_is_one skips pow for the standard s = 1
 * (bitwise the s = 1 weight); q rounded below 0 gives 0 as above. */
MESO_HD meso_real pair_weight_random_inv(meso_real r, meso_real inv_rc, meso_real s, int s_is_one) {
  const meso_real q = MESO_R(1.0) - r * inv_rc;
  if (s_is_one) return q;
  return q > MESO_R(0.0) ? (meso_real)pow(q, s) : MESO_R(0.0);
}

#endif
