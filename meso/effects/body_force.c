/* body_force: a constant force g per particle of a species (a pressure gradient -dp/dx = n m g,
 * physics.md section 4). Option reverse_along: k makes the force +g below the box centre along k
 * and -g above it: reverse Poiseuille flow for the viscosity (Backer et al. 2005). The per-particle
 * math both backends run is body_force_particle_force in meso/physics/body_force.h. */
#include "effects/effect.h"

#include <string.h>

_Static_assert(sizeof(body_force_params_t) <= SCENE_EFFECT_OPTION_BYTES, "options too large");

/* The scene keeps the parameters themselves as the options (the plan adds the centre). */
static body_force_params_t *options(scene_t *s) {
  return SCENE_EFFECT_OPTIONS(s, EFFECT_BODY_FORCE, body_force_params_t);
}
static const body_force_params_t *options_of(const scene_t *s) {
  return SCENE_EFFECT_OPTIONS(s, EFFECT_BODY_FORCE, const body_force_params_t);
}

static void defaults(scene_t *s) {
  memset(options(s), 0, sizeof(body_force_params_t));
  options(s)->reverse_axis = -1;
}

/* body_force: {SPECIES: [gx, gy, gz], ..., reverse_along: x|y|z} */
static int parse(ytree_t *t, yaml_node_t *opt, const char *path, scene_t *s) {
  static const char *const axis_words[] = {"x", "y", "z", NULL};
  static const char *const named[] = {"reverse_along", NULL}; /* + species names */
  yt_record_keys(path, named, 1);
  if (yt_check_keys(t, opt, path, NULL)) return -1; /* a map; each key once, as text */
  const int n = yt_map_size(opt);
  for (int j = 0; j < n; j++) {
    yaml_node_t *kn;
    const char *key = yt_map_key(t, opt, j, &kn);
    char sub[192];
    snprintf(sub, sizeof sub, "%s.%s", path, key ? key : "?");
    yaml_node_t *v = yt_map_value(t, opt, j);
    if (key && !strcmp(key, "reverse_along")) {
      const int axis = yt_enum(t, v, sub, axis_words);
      if (axis < 0) return -1;
      options(s)->reverse_axis = axis;
      continue;
    }
    const int species = key ? scene_species_index(s, key) : -1;
    if (species < 0)
      return yt_error(t, kn, sub, "expected a species name or 'reverse_along' (got '%s')",
                      key ? key : "?");
    if (yt_vec3(t, v, sub, options(s)->g[species])) return -1;
  }
  return 0;
}

static int check(const scene_t *s, scene_report_t *r) {
  const int axis = options_of(s)->reverse_axis;
  if (axis >= 0 && !s->periodic[axis])
    return r->error(
        r, "effects.body_force.reverse_along",
        "expected a periodic axis for reverse Poiseuille flow (got a non-periodic one)");
  return 0;
}

static int configure(const scene_t *s, plan_t *plan, char *err, size_t errlen) {
  (void)err, (void)errlen;
  body_force_params_t *b = &plan->particle.body_force;
  *b = *options_of(s);
  b->centre =
      b->reverse_axis >= 0 ? 0.5 * (s->box_lo[b->reverse_axis] + s->box_hi[b->reverse_axis]) : 0.0;
  return 0;
}

static void describe(const scene_t *s, FILE *out) {
  const body_force_params_t *b = options_of(s);
  fprintf(out, "body_force: constant force per particle:");
  for (int a = 0; a < s->n_species; a++) {
    const double *g = b->g[a];
    fprintf(out, " %s (%g, %g, %g)%s", s->species[a].name, g[0], g[1], g[2],
            a + 1 < s->n_species ? "," : "");
  }
  if (b->reverse_axis >= 0)
    fprintf(out, "; sign flips in the upper half along %c (reverse Poiseuille)",
            "xyz"[b->reverse_axis]);
}

const effect_t effect_body_force = {
    .scene = {.name = "body_force", .defaults = defaults, .parse = parse, .check = check},
    .id = EFFECT_BODY_FORCE,
    .needs = NEED_PARTICLE,
    .configure = configure,
    .describe = describe,
};
