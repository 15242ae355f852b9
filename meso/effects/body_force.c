/* body_force: a constant force g per particle of a species (a pressure gradient -dp/dx = n m g,
 * physics.md section 4). With scene.body_force_reverse_axis = k the force is +g below the box
 * centre along k and -g above it: reverse Poiseuille flow for the viscosity (Backer et al. 2005).
 */
#include "effect.h"

static void particle_force(const scene_t *s, particles_t *p) {
  const int axis = s->body_force_reverse_axis;
  const double centre = axis >= 0 ? 0.5 * (s->box_lo[axis] + s->box_hi[axis]) : 0.0;
  for (int i = 0; i < p->n_local; i++) {
    const double *g = s->body_force[p->species[i]];
    const double sign = (axis >= 0 && p->x[axis][i] >= centre) ? -1.0 : 1.0;
    for (int d = 0; d < 3; d++) p->f[d][i] += sign * g[d];
  }
}

static void describe(const scene_t *s, FILE *out) {
  fprintf(out, "body_force: constant force per particle:");
  for (int a = 0; a < s->n_species; a++) {
    const double *g = s->body_force[a];
    fprintf(out, " %s (%g, %g, %g)%s", s->species[a].name, g[0], g[1], g[2],
            a + 1 < s->n_species ? "," : "");
  }
  if (s->body_force_reverse_axis >= 0)
    fprintf(out, "; sign flips in the upper half along %c (reverse Poiseuille)",
            "xyz"[s->body_force_reverse_axis]);
}

const effect_t effect_body_force = {
    .id = EFFECT_BODY_FORCE,
    .name = "body_force",
    .needs = NEED_PARTICLE,
    .particle_force = particle_force,
    .describe = describe,
};
