/* The `units:` block (scene_units.h). */
#include "scene/scene_units.h"

#include <math.h>
#include <stdio.h>

/* The scene's fluid density for the water mapping: geometry.fluid_density, else
 * output.flux.density, else the first fill of a mobile species. */
static void scene_density(const scene_t *s, units_context_t *c) {
  if (s->geometry.on) {
    c->density = s->geometry.fluid_density;
    snprintf(c->density_source, sizeof c->density_source, "geometry.fluid_density");
  } else if (s->flux.density > 0) {
    c->density = s->flux.density;
    snprintf(c->density_source, sizeof c->density_source, "output.flux.density");
  } else if (s->init.kind == INIT_FILL) {
    for (int k = 0; k < s->init.n_fill; k++)
      if (!s->species[s->init.fill[k].species].frozen) {
        c->density = s->init.fill[k].density;
        snprintf(c->density_source, sizeof c->density_source, "initial.fill[%d].density", k);
        break;
      }
  }
}

int scene_parse_units(ytree_t *t, yaml_node_t *n, scene_t *s) {
  units_context_t c;
  units_context_init(&c);
  c.kT = s->kT;
  if (s->geometry.on) c.rc_per_voxel = s->geometry.rc_per_voxel;
  scene_density(s, &c);
  return units_block_read(t, n, "units", &c, &s->units);
}
