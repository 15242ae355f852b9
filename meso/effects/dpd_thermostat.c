/* dpd_thermostat: dissipative + random pair forces (Espanol & Warren 1995; paper eq. 1):
 *   -gamma w_R^2 (e . v_ij) e + sigma w_R xi_ij / sqrt(dt) e,  w_R = (1 - r/rc)^s,  sigma^2 = 2
 * gamma kT. xi_ij = xi_ji comes from the counter-based generator of meso/physics/pair_random.h.
 * v_ij uses the Groot-Warren predicted velocities, so ghosts must carry velocities. */
#include "effect.h"

#include <math.h>
#include <stddef.h>

static int check(const scene_t *s, char *err, size_t errlen) {
  if (!(s->kT >= 0)) {
    snprintf(err, errlen, "%s: kT = %g: expected kT >= 0 for dpd_thermostat", s->file, s->kT);
    return -1;
  }
  for (int a = 0; a < s->n_species; a++)
    for (int b = 0; b < s->n_species; b++)
      if (!(s->pair[a][b].gamma >= 0)) {
        snprintf(err, errlen, "%s: pair %s-%s: gamma = %g: expected gamma >= 0", s->file,
                 s->species[a].name, s->species[b].name, s->pair[a][b].gamma);
        return -1;
      }
  return 0;
}

static void pair_coef(const scene_t *s, int a, int b, pair_coef_t *c) {
  c->gamma = s->pair[a][b].gamma;
  c->sigma = sqrt(2.0 * c->gamma * s->kT); /* fluctuation-dissipation */
}

static void describe(const scene_t *s, FILE *out) {
  fprintf(out,
          "dpd_thermostat: -gamma w_R^2 (e.v~) e + sigma w_R xi/sqrt(dt) e, w_R = (1 - r/rc)^%g; "
          "gamma = ",
          s->weight_exp);
  effect_print_pair_param(s, out, offsetof(scene_pair_t, gamma));
  fprintf(out, "; kT = %g; xi from Philox(seed %llu, step, ids)", s->kT,
          (unsigned long long)s->seed);
}

const effect_t effect_dpd_thermostat = {
    .id = EFFECT_DPD_THERMOSTAT,
    .name = "dpd_thermostat",
    .needs = NEED_PAIR | NEED_GHOST_V,
    .pair_term = PAIR_TERM_THERMOSTAT,
    .check = check,
    .pair_coef = pair_coef,
    .describe = describe,
};
