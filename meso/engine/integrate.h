/* Groot-Warren velocity Verlet (Groot & Warren 1997, eq. 16; lambda = 1/2 is plain velocity
 * Verlet): v(t + dt/2) = v(t) + dt/2 f(t)/m;  x(t + dt) = x(t) + dt v(t + dt/2) v~(t + dt)  = v(t)
 * + lambda dt f(t)/m = v(t + dt/2) + (lambda - 1/2) dt f(t)/m   (for the thermostat) f(t + dt)   =
 * F(x(t + dt), v~(t + dt));  v(t + dt) = v(t + dt/2) + dt/2 f(t + dt)/m Frozen species are never
 * moved (their v stays 0). */
#ifndef MESO_ENGINE_INTEGRATE_H
#define MESO_ENGINE_INTEGRATE_H

#include "particles.h"
#include "plan.h"
#include "step_check.h"

/* First half kick + drift of owned mobile particles; notes non-finite x/v and displacements above
 * plan->max_disp in pr. */
void integrate_kick_drift(const plan_t *plan, particles_t *p, double dt, step_problem_t *pr);
/* v~ = v + (lambda - 1/2) dt f/m into p->vpred (only when allocated). */
void integrate_predict(const plan_t *plan, particles_t *p, double dt, double lambda);
/* Second half kick; notes non-finite f/v in pr. */
void integrate_kick(const plan_t *plan, particles_t *p, double dt, step_problem_t *pr);

#endif
