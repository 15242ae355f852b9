/* Small queries on a parsed scene: effect names, ghost-layer width, species lookup, physics hash.
 */
#include "io/scene.h"

#include <string.h>

const char *const scene_effect_names[EFFECT_COUNT] = {
    [EFFECT_MDPD_ATTRACTION] = "mdpd_attraction",
    [EFFECT_MDPD_REPULSION] = "mdpd_repulsion",
    [EFFECT_DPD_CONSERVATIVE] = "dpd_conservative",
    [EFFECT_DPD_THERMOSTAT] = "dpd_thermostat",
    [EFFECT_BODY_FORCE] = "body_force",
    [EFFECT_BOX_WALLS] = "box_walls",
};

double scene_max_cutoff(const scene_t *s) {
  const int uses_rc = s->effect[EFFECT_MDPD_ATTRACTION] || s->effect[EFFECT_DPD_CONSERVATIVE] ||
                      s->effect[EFFECT_DPD_THERMOSTAT];
  const int uses_rd = s->effect[EFFECT_MDPD_REPULSION];
  double cut = 0;
  for (int a = 0; a < s->n_species; a++)
    for (int b = 0; b < s->n_species; b++) {
      if (uses_rc && s->pair[a][b].rc > cut) cut = s->pair[a][b].rc;
      if (uses_rd && s->pair[a][b].rd > cut) cut = s->pair[a][b].rd;
    }
  return cut;
}

int scene_species_index(const scene_t *s, const char *name) {
  for (int i = 0; i < s->n_species; i++)
    if (!strcmp(s->species[i].name, name)) return i;
  return -1;
}

/* FNV-1a over the bytes of the fields that shape the trajectory. */
static uint64_t fnv(uint64_t h, const void *p, size_t n) {
  const unsigned char *c = p;
  for (size_t i = 0; i < n; i++) h = (h ^ c[i]) * 1099511628211ull;
  return h;
}

uint64_t scene_physics_hash(const scene_t *s) {
  uint64_t h = 14695981039346656037ull;
  h = fnv(h, s->box_lo, sizeof s->box_lo);
  h = fnv(h, s->box_hi, sizeof s->box_hi);
  h = fnv(h, s->periodic, sizeof s->periodic);
  h = fnv(h, &s->n_species, sizeof s->n_species);
  for (int a = 0; a < s->n_species; a++) {
    h = fnv(h, s->species[a].name, strlen(s->species[a].name));
    h = fnv(h, &s->species[a].mass, sizeof(double));
    h = fnv(h, &s->species[a].frozen, sizeof(int));
    for (int b = 0; b < s->n_species; b++) h = fnv(h, &s->pair[a][b], sizeof(scene_pair_t));
    h = fnv(h, s->body_force[a], sizeof s->body_force[a]);
  }
  h = fnv(h, &s->density_kernel, sizeof s->density_kernel);
  h = fnv(h, &s->kT, sizeof s->kT);
  h = fnv(h, &s->weight_exp, sizeof s->weight_exp);
  h = fnv(h, &s->vv_lambda, sizeof s->vv_lambda);
  h = fnv(h, s->effect, sizeof s->effect);
  h = fnv(h, &s->body_force_reverse_axis, sizeof s->body_force_reverse_axis);
  h = fnv(h, &s->dt, sizeof s->dt);
  h = fnv(h, &s->seed, sizeof s->seed);
  return h;
}
