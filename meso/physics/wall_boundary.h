/* wall_boundary, per particle and per pair (effects/wall_boundary.c): the boundary of walls of any
 * shape made of frozen particles (Li, Bian, Tang, Karniadakis, J. Comput. Phys. 355 (2018) 534;
 * physics.md section 3).
 *
 *  - Wall volume fraction seen by a mobile particle i, from the frozen particles j within r_phi:
 *        phi_i = (1 / rho_wall) sum_j W(r_ij),  W(r) = 105 / (16 pi h^3) (1 + 3 s)(1 - s)^3,
 *    s = r / h, h = r_phi (the Lucy kernel; phi = 1/2 on a flat wall's surface), and its gradient
 *        grad phi_i = (1 / rho_wall) sum_j W'(r) e_ij = -(12 N / (h^2 rho_wall)) sum_j (1 - s)^2 r_ij
 *    (N the normalisation, r_ij = x_i - x_j, e_ij = r_ij / r); the wall normal into the fluid is
 *    n = -grad phi / |grad phi|.
 *  - Reflection: a particle whose drift takes it past phi_c (0.5) is put on a path from its OLD
 *    position, x = x_old + dt v', with v' = -v + 2 max(0, v.n) n (tangential part reversed, normal
 *    part into the fluid), v taken relative to the wall's velocity u when walls move (u + that
 *    reflection of v - u; u the W-weighted mean velocity of the frozen neighbours' species). phi at the new position is phi_i + grad phi_i . (x - x_old), the field of
 *    the last force evaluation (at x_old) carried one drift by its gradient: walls do not move, a
 *    drift is ~0.02 rc, so the neglected second-order term is ~1e-3 of phi_c.
 *  - No slip: the dissipation of the pairs with wall particles grows near the surface, with
 *    phi = min(phi_i, 1/2), h/rc = max(0.025, 1 - (2.088 phi^3 + 1.478 phi)^(1/4)) and
 *        ratio = 1 + 0.187 (rc/h - 1) - 0.093 (1 - h/rc)^3,
 *    gamma_iw <- ratio gamma_iw and sigma_iw <- sqrt(ratio) sigma_iw (fluctuation-dissipation kept
 *    pair by pair).
 *  - Stability cap (ours, not Li's): the wall pairs' dissipation acts on v_i as -D v_i with
 *    trace D = S_i = sum_{wall j} gamma_ij w_D(r_ij); the explicit kicks are stable while
 *    dt lambda_max(D) < 2. A fluid particle in a dense spot of a frozen wall has S_i ~ 15-25, so
 *    ratio S_i dt reaches 2 at dt = 0.01 (measured: runs of 10 M particles blew up within 50 steps).
 *    The ratio is therefore capped at max(1, 1 / (dt S_i)), which keeps dt ratio S_i <= 1. At a flat
 *    wall of density 8 (S ~ 7.5 at the surface, ratio 8.2) the cap does not act at dt <= 0.016. */
#ifndef MESO_PHYSICS_WALL_BOUNDARY_H
#define MESO_PHYSICS_WALL_BOUNDARY_H

#include "hd.h"

#include <math.h>

/* The wall field of one particle (36 bytes; 40 on the GPU, 8-byte aligned). */
typedef struct
#ifdef __CUDACC__
    __align__(8)
#endif
{
  float phi, gx, gy, gz;   /* phi_i and grad phi_i */
  float ratio, sqrt_ratio; /* the no-slip dissipation ratio of its wall pairs (capped) */
  float ux, uy, uz;        /* the wall's velocity there (W-weighted mean; 0 unless walls move) */
}
wall_field_t;

typedef struct {
  /* Per owned particle, in the backend's current particle order, written by its wall-field pass
   * (not a plan array: the backend allocates it and sets this pointer). */
  wall_field_t *field;
  double r_phi2; /* r_phi^2: the range of the wall field */
  double inv_h;  /* 1 / r_phi */
  double w_norm; /* N / rho_wall, N = 105 / (16 pi r_phi^3) */
  double g_norm; /* 12 N / (r_phi^2 rho_wall) */
  double phi_c;  /* the surface phi = phi_c */
  double dt;     /* x = x_old + dt v' after a reflection */
  int moving;    /* some frozen species moves (species[].velocity): the field carries its u */
  double wall_u[MESO_MAX_SPECIES][3]; /* velocity of each frozen species (0 at rest) */
} wall_boundary_params_t;

/* Accumulators of the wall-field pass: acc[0..3] the phi sums, acc[4] = S_i (stability cap),
 * acc[5..7] sum_j W(r_ij) u_j (moving walls only). */
#define WALL_FIELD_ACC 8

/* Accumulate the contribution of one wall particle at separation (dx, dy, dz) = x_i - x_j,
 * r2 < r_phi^2: acc[0] += (1 + 3 s)(1 - s)^3, acc[1..3] += (1 - s)^2 r_ij. Returns the weight added
 * to acc[0] (for the wall velocity, wall_field_add_velocity). */
MESO_HD meso_real wall_field_add(meso_real inv_h, meso_real r2, meso_real dx, meso_real dy,
                                 meso_real dz, meso_real acc[4]) {
  const meso_real s = meso_sqrt(r2) * inv_h, q = MESO_R(1.0) - s, q2 = q * q;
  const meso_real weight = (MESO_R(1.0) + MESO_R(3.0) * s) * q2 * q;
  acc[0] += weight;
  acc[1] += q2 * dx;
  acc[2] += q2 * dy;
  acc[3] += q2 * dz;
  return weight;
}

/* Moving walls: acc[5..7] += weight u_j, u_j the velocity of wall particle j's species. */
MESO_HD void wall_field_add_velocity(const wall_boundary_params_t *w, int species_j,
                                     meso_real weight, meso_real acc[WALL_FIELD_ACC]) {
  acc[5] += weight * (meso_real)w->wall_u[species_j][0];
  acc[6] += weight * (meso_real)w->wall_u[species_j][1];
  acc[7] += weight * (meso_real)w->wall_u[species_j][2];
}

/* The dissipation ratio of the pairs with wall particles at wall fraction phi (Li et al. 2018). */
MESO_HD meso_real wall_dissipation_ratio(meso_real phi) {
  const meso_real p = phi < MESO_R(0.5) ? (phi > MESO_R(0.0) ? phi : MESO_R(0.0)) : MESO_R(0.5);
  const meso_real a = MESO_R(2.088) * p * p * p + MESO_R(1.478) * p;
  meso_real h = MESO_R(1.0) - meso_sqrt(meso_sqrt(a)); /* h / rc */
  if (h < MESO_R(0.025)) h = MESO_R(0.025);
  const meso_real u = MESO_R(1.0) - h;
  return MESO_R(1.0) + MESO_R(0.187) * (MESO_R(1.0) / h - MESO_R(1.0)) - MESO_R(0.093) * u * u * u;
}

/* The field from the accumulated sums (acc[4] = S_i = sum_{wall j} gamma_ij w_D(r_ij)). */
MESO_HD wall_field_t wall_field_finish(const wall_boundary_params_t *w,
                                       const meso_real acc[WALL_FIELD_ACC]) {
  wall_field_t f;
  f.phi = (float)(w->w_norm * acc[0]);
  f.gx = (float)(-w->g_norm * acc[1]);
  f.gy = (float)(-w->g_norm * acc[2]);
  f.gz = (float)(-w->g_norm * acc[3]);
  meso_real ratio = wall_dissipation_ratio((meso_real)f.phi);
  const meso_real dts = (meso_real)w->dt * acc[4];
  if (ratio * dts > MESO_R(1.0)) ratio = dts < MESO_R(1.0) ? MESO_R(1.0) / dts : MESO_R(1.0);
  f.ratio = (float)ratio;
  f.sqrt_ratio = (float)meso_sqrt(ratio);
  const meso_real inv_w = acc[0] > MESO_R(0.0) ? MESO_R(1.0) / acc[0] : MESO_R(0.0);
  f.ux = (float)(acc[5] * inv_w); /* the W-weighted mean wall velocity (0 at rest) */
  f.uy = (float)(acc[6] * inv_w);
  f.uz = (float)(acc[7] * inv_w);
  return f;
}

/* After the drift of mobile particle i from x_old to x: reflect it when its predicted phi passes
 * phi_c. Never loses a particle (returns 0). */
MESO_HD int wall_boundary_after_drift(const wall_boundary_params_t *w, int i, double x[3],
                                      double v[3], const double x_old[3]) {
  const wall_field_t f = w->field[i];
  if (f.phi <= 0.0f) return 0; /* no wall within r_phi of x_old: none within reach of one drift */
  const double phi = (double)f.phi + (double)f.gx * (x[0] - x_old[0]) +
                     (double)f.gy * (x[1] - x_old[1]) + (double)f.gz * (x[2] - x_old[2]);
  if (!(phi > w->phi_c)) return 0;
  const double g2 = (double)f.gx * f.gx + (double)f.gy * f.gy + (double)f.gz * f.gz;
  if (!(g2 > 0.0)) return 0; /* no direction (a symmetric spot): leave it to the next step */
  const double inv_g = 1.0 / sqrt(g2);
  const double n[3] = {-f.gx * inv_g, -f.gy * inv_g, -f.gz * inv_g}; /* into the fluid */
  /* relative to the wall's velocity u (moving walls; u = 0 at rest): v - u reflected, u added */
  const double u[3] = {(double)f.ux, (double)f.uy, (double)f.uz};
  const double vr[3] = {v[0] - u[0], v[1] - u[1], v[2] - u[2]};
  const double vn = vr[0] * n[0] + vr[1] * n[1] + vr[2] * n[2];
  const double k = 2.0 * (vn > 0.0 ? vn : 0.0);
  for (int d = 0; d < 3; d++) {
    v[d] = u[d] - vr[d] + k * n[d];
    x[d] = x_old[d] + w->dt * v[d];
  }
  return 0;
}

#endif
