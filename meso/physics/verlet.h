/* Groot-Warren velocity Verlet of one particle (Groot & Warren 1997, eq. 16; lambda = 1/2 is plain
 * velocity Verlet), the arithmetic both backends run:
 *   v(t + dt/2) = v(t) + dt/2 f(t)/m;   x(t + dt) = x(t) + dt v(t + dt/2)
 *   v~(t + dt)  = v(t + dt/2) + (lambda - 1/2) dt f(t)/m      (the velocity the thermostat sees)
 *   f(t + dt)   = F(x(t + dt), v~(t + dt));   v(t + dt) = v(t + dt/2) + dt/2 f(t + dt)/m
 * Frozen species are never integrated: the callers skip them (a moving frozen species translates
 * at its fixed velocity: verlet_moving_wall_drift). Everything in double. */
#ifndef MESO_PHYSICS_VERLET_H
#define MESO_PHYSICS_VERLET_H

#include "hd.h"

#include <math.h>

/* First half kick and drift; returns the squared displacement |dt v(t + dt/2)|^2 for the
 * displacement check. half_dt = dt / 2 (plan.half_dt). */
MESO_HD double verlet_kick_drift(double x[3], double v[3], const double f[3], double dt,
                                 double half_dt, double inv_mass) {
  const double h = half_dt * inv_mass;
  double d2 = 0.0;
  for (int d = 0; d < 3; d++) {
    v[d] = v[d] + h * f[d];
    x[d] += dt * v[d];
    d2 += (dt * v[d]) * (dt * v[d]);
  }
  return d2;
}

/* A frozen particle of a moving species (a wall translating at the fixed velocity u, plane
 * Couette): x += dt u, v = u. Never integrated from forces; v = u is the wall velocity the
 * thermostat's pairs see. */
MESO_HD void verlet_moving_wall_drift(double x[3], double v[3], const double u[3], double dt) {
  for (int d = 0; d < 3; d++) {
    x[d] += dt * u[d];
    v[d] = u[d];
  }
}

/* v~ = v + k f with k = (lambda - 1/2) dt / m (plan.predict_c / m), or k = 0 at set-up. */
MESO_HD void verlet_predict(double vpred[3], const double v[3], const double f[3], double k) {
  for (int d = 0; d < 3; d++) vpred[d] = v[d] + k * f[d];
}

/* Second half kick v += dt/2 f / m. */
MESO_HD void verlet_kick(double v[3], const double f[3], double half_dt, double inv_mass) {
  const double h = half_dt * inv_mass;
  for (int d = 0; d < 3; d++) v[d] += h * f[d];
}

/* Periodic wrap of one coordinate into [lo, hi) (len = hi - lo); a non-finite x is left alone for
 * the checks to report. */
MESO_HD double box_wrap(double x, double lo, double hi, double len) {
  if (isfinite(x) && (x < lo || x >= hi)) {
    x = lo + fmod(x - lo, len);
    if (x < lo) x += len;
    if (x >= hi) x = nextafter(hi, lo);
  }
  return x;
}

#endif
