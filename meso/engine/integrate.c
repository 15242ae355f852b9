/* Velocity-Verlet pieces of the step (see integrate.h for the scheme). */
#include "integrate.h"

#include <math.h>

static void position_of(const particles_t *p, int i, double x[3]) {
  for (int d = 0; d < 3; d++) x[d] = p->x[d][i];
}

void integrate_kick_drift(const plan_t *plan, particles_t *p, double dt, step_problem_t *pr) {
  const double max2 = plan->max_disp * plan->max_disp;
  for (int i = 0; i < p->n_local; i++) {
    const int s = p->species[i];
    if (!plan->mobile[s]) continue;
    const double h = 0.5 * dt * plan->inv_mass[s];
    double d2 = 0.0;
    for (int d = 0; d < 3; d++) {
      const double v = p->v[d][i] + h * p->f[d][i];
      p->v[d][i] = v;
      p->x[d][i] += dt * v;
      d2 += (dt * v) * (dt * v);
    }
    if (!(d2 < max2)) { /* also catches NaN */
      double x[3];
      position_of(p, i, x);
      if (isfinite(d2)) {
        step_problem_note(pr, STEP_TOO_FAST, p->id[i], x, sqrt(d2));
        pr->limit = plan->max_disp;
      } else {
        step_problem_note(pr, STEP_NONFINITE, p->id[i], x, 0);
        pr->field = "velocity or position";
      }
    }
  }
}

void integrate_predict(const plan_t *plan, particles_t *p, double dt, double lambda) {
  if (!p->vpred[0]) return;
  const double c = (lambda - 0.5) * dt;
  for (int i = 0; i < p->n_local; i++) {
    const int s = p->species[i];
    const double k = plan->mobile[s] ? c * plan->inv_mass[s] : 0.0;
    for (int d = 0; d < 3; d++) p->vpred[d][i] = p->v[d][i] + k * p->f[d][i];
  }
}

void integrate_kick(const plan_t *plan, particles_t *p, double dt, step_problem_t *pr) {
  for (int i = 0; i < p->n_local; i++) {
    const int s = p->species[i];
    const double fsum = p->f[0][i] + p->f[1][i] + p->f[2][i];
    if (!isfinite(fsum)) {
      double x[3];
      position_of(p, i, x);
      step_problem_note(pr, STEP_NONFINITE, p->id[i], x, 0);
      pr->field = "force";
    }
    if (!plan->mobile[s]) continue;
    const double h = 0.5 * dt * plan->inv_mass[s];
    for (int d = 0; d < 3; d++) p->v[d][i] += h * p->f[d][i];
  }
}
