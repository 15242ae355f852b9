/* The table of effects, generated from the registry list (effect_list.h), the catalog the scene
 * parser reads, and small helpers the effects share for their messages. */
#include "effects/effect.h"

#include <stddef.h>

#define DECLARE_(name, ID, kind) extern const effect_t effect_##name;
MESO_EFFECT_LIST(DECLARE_)

#define ENTRY_(name, ID, kind) [EFFECT_##ID] = &effect_##name,
static const effect_t *const effect_table[EFFECT_COUNT] = {MESO_EFFECT_LIST(ENTRY_)};

#define SCENE_ENTRY_(name, ID, kind) [EFFECT_##ID] = &effect_##name.scene,
static const scene_effect_entry_t *const scene_entries[EFFECT_COUNT] = {
    MESO_EFFECT_LIST(SCENE_ENTRY_)};
static const scene_catalog_t catalog = {EFFECT_COUNT, scene_entries};

_Static_assert(EFFECT_COUNT <= SCENE_MAX_EFFECTS, "raise SCENE_MAX_EFFECTS (scene/scene.h)");

const effect_t *effect_get(int id) {
  return id >= 0 && id < EFFECT_COUNT ? effect_table[id] : NULL;
}

const char *effect_name(int id) {
  return id >= 0 && id < EFFECT_COUNT ? effect_table[id]->scene.name : "?";
}

const scene_catalog_t *effect_catalog(void) {
  return &catalog;
}

void effect_name_in_scene(scene_t *s, int id) {
  const effect_t *e = effect_get(id);
  if (!e) return;
  s->effect[id] = 1;
  if (e->scene.defaults) e->scene.defaults(s);
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
