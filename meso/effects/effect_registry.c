/* The table of effects by scene id, and small helpers the effects share for their messages. */
#include "effect.h"

#include <stddef.h>

static const effect_t *const effect_table[EFFECT_COUNT] = {
    [EFFECT_MDPD_ATTRACTION] = &effect_mdpd_attraction,
    [EFFECT_MDPD_REPULSION] = &effect_mdpd_repulsion,
    [EFFECT_DPD_CONSERVATIVE] = &effect_dpd_conservative,
    [EFFECT_DPD_THERMOSTAT] = &effect_dpd_thermostat,
    [EFFECT_BODY_FORCE] = &effect_body_force,
    [EFFECT_BOX_WALLS] = &effect_box_walls,
};

const effect_t *effect_get(int id) {
  return id >= 0 && id < EFFECT_COUNT ? effect_table[id] : NULL;
}

static double pair_field(const scene_t *s, int a, int b, size_t field) {
  return *(const double *)((const char *)&s->pair[a][b] + field);
}

int effect_pair_param_common(const scene_t *s, size_t field) {
  for (int a = 0; a < s->n_species; a++)
    for (int b = 0; b < s->n_species; b++)
      if (pair_field(s, a, b, field) != pair_field(s, 0, 0, field)) return 0;
  return 1;
}

void effect_print_pair_param(const scene_t *s, FILE *out, size_t field) {
  if (effect_pair_param_common(s, field)) {
    fprintf(out, "%g", pair_field(s, 0, 0, field));
    return;
  }
  const char *sep = "";
  for (int a = 0; a < s->n_species; a++)
    for (int b = a; b < s->n_species; b++) {
      fprintf(out, "%s%s-%s %g", sep, s->species[a].name, s->species[b].name,
              pair_field(s, a, b, field));
      sep = ", ";
    }
}
