/* bounce_back: the solid voxels of the scene's geometry image as a boundary for the mobile
 * particles (physics.md section 3, the simpler of the two boundaries; Mirheo uses the same idea
 * with a signed distance field). A particle whose drift ends inside a solid voxel is put back at
 * its position before the drift with its velocity reversed (relative to the velocity of the voxel's
 * wall species: v' = 2 u - v, u = species[].velocity, 0 at rest), so no mobile particle is ever inside
 * the solid at the end of a step. The per-particle math both backends run is
 * bounce_back_after_drift in meso/physics/bounce_back.h; the solid map is read from the image once,
 * at plan time, and handed to the backends as a plan array. */
#include "effects/effect.h"
#include "scene/scene_geometry.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

static int check(const scene_t *s, scene_report_t *r) {
  if (!s->geometry.on)
    return r->error(r, "effects.bounce_back",
                    "expected a 'geometry' image whose solid voxels the particles bounce off (got "
                    "none)");
  return 0;
}

static int configure(const scene_t *s, plan_t *plan, char *err, size_t errlen) {
  mdp_image_t img;
  if (scene_geometry_read_image(s, &img, err, errlen)) return -1;
  const size_t n = mdp_image_count(&img);
  uint8_t *solid = malloc(n ? n : 1);
  if (!solid) {
    snprintf(err, errlen, "%s: bounce_back: out of memory for the solid map of %zu voxels", s->file,
             n);
    mdp_image_free(&img);
    return -1;
  }
  /* each solid voxel keeps its wall species (organic / inorganic), whose velocity the bounce is
   * relative to (species[].velocity: a moving wall) */
  const scene_geometry_t *g = &s->geometry;
  for (size_t i = 0; i < n; i++) {
    const int phase = mdp_image_phase(&img, i);
    const int species = phase == MDP_PHASE_ORGANIC     ? g->organic_species
                        : phase == MDP_PHASE_INORGANIC ? g->inorganic_species
                                                       : -1;
    solid[i] = phase == MDP_PHASE_PORE ? 0
               : species >= 0          ? (uint8_t)(1 + species)
                                       : BOUNCE_BACK_SOLID_AT_REST;
  }
  bounce_back_params_t *b = &plan->particle.bounce_back;
  for (int a = 0; a < s->n_species; a++)
    for (int d = 0; d < 3; d++)
      b->wall_u[a][d] = s->species[a].moving ? s->species[a].velocity[d] : 0;
  b->solid = solid;
  scene_geometry_grid(s, &img, &b->grid);
  mdp_image_free(&img);
  if (plan_add_array(plan, offsetof(particle_effects_t, bounce_back.solid), n)) {
    free(solid);
    b->solid = NULL;
    snprintf(err, errlen, "%s: bounce_back: too many effect arrays", s->file);
    return -1;
  }
  return 0;
}

static void describe(const scene_t *s, FILE *out) {
  fprintf(out,
          "bounce_back: a mobile particle whose drift ends in a solid voxel of %s (voxel %g rc) "
          "goes back to where it was, velocity reversed (relative to the voxel's wall species' "
          "velocity)",
          s->geometry.image, s->geometry.rc_per_voxel);
}

const effect_t effect_bounce_back = {
    .scene = {.name = "bounce_back", .check = check},
    .id = EFFECT_BOUNCE_BACK,
    .needs = NEED_AFTER_DRIFT,
    .configure = configure,
    .describe = describe,
};
