/* Temperature runaway guard (temperature_guard.h). */
#include "analysis/temperature_guard.h"
#include "effects/effect_list.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int temperature_guard_init(temperature_guard_t *g, sim_t *sim) {
  memset(g, 0, sizeof *g);
  g->above_since = g->last_step = -1;
  const scene_t *s = sim_scene(sim);
  if (!s->effect[EFFECT_DPD_THERMOSTAT] || !(s->guard.temperature_tolerance > 0)) return 0;
  const particles_t *p = sim_particles(sim);
  double m = 0;
  for (int i = 0; i < p->n_local; i++) {
    const scene_species_t *sp = &s->species[p->species[i]];
    if (!sp->frozen) m += sp->mass;
  }
  MPI_Allreduce(MPI_IN_PLACE, &m, 1, MPI_DOUBLE, MPI_SUM, sim_comm(sim));
  g->mobile_mass = m;
  g->kT = s->kT;
  g->dt = s->dt;
  g->tolerance = s->guard.temperature_tolerance;
  g->window = s->guard.temperature_window;
  g->on = m > 0;
  return 0;
}

int temperature_guard_sample(temperature_guard_t *g, const thermo_t *th, char *msg, size_t len) {
  if (!g->on || th->n_mobile < 2 || th->step == g->last_step) return 0;
  g->last_step = th->step;
  const double *P = th->momentum;
  const double p2 = P[0] * P[0] + P[1] * P[1] + P[2] * P[2];
  const double T = (2.0 * th->ke - p2 / g->mobile_mass) / (3.0 * (double)(th->n_mobile - 1));
  const double limit = (1.0 + g->tolerance) * g->kT;
  if (!(T > limit) && T == T) { /* back under the limit (NaN counts as above) */
    g->above_since = -1;
    g->above_n = 0;
    g->above_sum = 0;
    return 0;
  }
  if (g->above_since < 0) g->above_since = th->step;
  g->above_n++;
  g->above_sum += T;
  if (th->step - g->above_since < g->window || g->above_n < 3) return 0;
  snprintf(msg, len,
           "mdpore: step %ld: temperature runaway: the fluid temperature (mean flow removed) has "
           "stayed above %.4g = (1 + guard.temperature_tolerance %g) x kT %g at all %ld thermo "
           "samples since step %ld (guard.temperature_window %ld steps): mean %.4g, now %.4g. The "
           "thermostat does not hold it: try a smaller run.dt (dt %g now; try %.3g), a weaker "
           "body force, or a larger gamma",
           th->step, limit, g->tolerance, g->kT, g->above_n, g->above_since, g->window,
           g->above_sum / g->above_n, T, g->dt, 0.5 * g->dt);
  return 1;
}

void temperature_guard_free(temperature_guard_t *g) {
  memset(g, 0, sizeof *g);
}
