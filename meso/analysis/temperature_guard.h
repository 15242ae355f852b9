/* Temperature runaway guard: the fluid temperature with the mean flow removed,
 *   T_fluid = (2 KE - |P|^2 / M) / (3 (N_mobile - 1)),
 * (KE, P: kinetic energy and momentum of the mobile particles, M their mass), at every thermo
 * sample; the run stops when it has stayed above (1 + guard.temperature_tolerance) kT at every
 * sample over at least guard.temperature_window steps (and 3 samples): a start-up transient (a
 * random fill releasing its overlaps) cools back within the window, a runaway does not. Only the uniform flow is removed: a Poiseuille profile's
 * non-uniform part still counts as heat (small: (u - <u>)^2 / 3 per particle). Active when the
 * scene names dpd_thermostat (then kT is what T should stay at) and the tolerance is > 0. */
#ifndef MESO_ANALYSIS_TEMPERATURE_GUARD_H
#define MESO_ANALYSIS_TEMPERATURE_GUARD_H

#include "engine/sim.h"

#include <stddef.h>

typedef struct {
  int on;
  double kT, tolerance, dt;
  double mobile_mass; /* M: total mass of the mobile particles */
  long window;        /* steps */
  long above_since;   /* first step of the current run of samples above the limit (-1: none) */
  long above_n;       /* samples in it */
  double above_sum;   /* their T sum */
  long last_step;     /* the latest sample's step */
} temperature_guard_t;

/* Collective (sums the mobile mass). 0. */
int temperature_guard_init(temperature_guard_t *g, sim_t *sim);
/* At a thermo sample (identical on every rank, no communication): 1 to stop, with the message in
 * msg (cause, step, T, what to try); 0 to go on. */
int temperature_guard_sample(temperature_guard_t *g, const thermo_t *th, char *msg, size_t len);
void temperature_guard_free(temperature_guard_t *g);

#endif
