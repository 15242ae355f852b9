/* wall_boundary: the boundary of walls of any shape made of frozen particles (Li, Bian, Tang,
 * Karniadakis, J. Comput. Phys. 355 (2018) 534; physics.md section 3). Each step the backends
 * compute, for every mobile particle, the wall volume fraction phi and its gradient from the frozen
 * particles within r_phi (a wall-field pass over the neighbour lists); after the drift a particle
 * predicted past phi_c is reflected onto a path from its old position; with no_slip the
 * dissipative and random forces of its pairs with wall particles are scaled by Li's ratio(phi).
 * The math is in meso/physics/wall_boundary.h, shared by both backends.
 * Options: r_phi (1.0), phi_c (0.5), rho_wall (the geometry's wall_density, else 8), no_slip
 * (true). */
#include "effects/effect.h"

#include <math.h>
#include <string.h>

typedef struct {
  double r_phi, phi_c, rho_wall; /* rho_wall <= 0: the geometry's wall density (or 8) */
  int no_slip;
} wall_boundary_options_t;
_Static_assert(sizeof(wall_boundary_options_t) <= SCENE_EFFECT_OPTION_BYTES, "options too large");

static wall_boundary_options_t *options(scene_t *s) {
  return SCENE_EFFECT_OPTIONS(s, EFFECT_WALL_BOUNDARY, wall_boundary_options_t);
}
static const wall_boundary_options_t *options_of(const scene_t *s) {
  return SCENE_EFFECT_OPTIONS(s, EFFECT_WALL_BOUNDARY, const wall_boundary_options_t);
}

static void defaults(scene_t *s) {
  wall_boundary_options_t *o = options(s);
  o->r_phi = 1.0;
  o->phi_c = 0.5;
  o->rho_wall = 0.0;
  o->no_slip = 1;
}

static double rho_wall_of(const scene_t *s) {
  const double r = options_of(s)->rho_wall;
  if (r > 0) return r;
  return s->geometry.on && s->geometry.wall_density > 0 ? s->geometry.wall_density : 8.0;
}

static int parse_positive(ytree_t *t, yaml_node_t *opt, const char *path, const char *key,
                          double *out) {
  yaml_node_t *v = yt_get(t, opt, key);
  if (!v) return 0;
  char sub[192];
  snprintf(sub, sizeof sub, "%s.%s", path, key);
  if (yt_double(t, v, sub, out)) return -1;
  if (!(*out > 0) || !isfinite(*out))
    return yt_error(t, v, sub, "expected a finite number > 0 (got %g)", *out);
  return 0;
}

static int parse(ytree_t *t, yaml_node_t *opt, const char *path, scene_t *s) {
  static const char *const keys[] = {"r_phi", "phi_c", "rho_wall", "no_slip", NULL};
  if (yt_check_keys(t, opt, path, keys)) return -1;
  wall_boundary_options_t *o = options(s);
  if (parse_positive(t, opt, path, "r_phi", &o->r_phi) ||
      parse_positive(t, opt, path, "phi_c", &o->phi_c) ||
      parse_positive(t, opt, path, "rho_wall", &o->rho_wall))
    return -1;
  yaml_node_t *v = yt_get(t, opt, "phi_c");
  if (v && !(o->phi_c < 1.0)) {
    char sub[192];
    snprintf(sub, sizeof sub, "%s.phi_c", path);
    return yt_error(t, v, sub, "expected 0 < phi_c < 1 (got %g; 0.5 is a flat wall's surface)",
                    o->phi_c);
  }
  v = yt_get(t, opt, "no_slip");
  if (v) {
    char sub[192];
    snprintf(sub, sizeof sub, "%s.no_slip", path);
    if (yt_bool(t, v, sub, &o->no_slip)) return -1;
  }
  return 0;
}

static int check(const scene_t *s, scene_report_t *r) {
  const wall_boundary_options_t *o = options_of(s);
  int frozen = 0, mobile = 0;
  for (int a = 0; a < s->n_species; a++) {
    frozen += s->species[a].frozen != 0;
    mobile += s->species[a].frozen == 0;
  }
  if (!frozen || !mobile)
    return r->error(r, "effects.wall_boundary",
                    "expected frozen wall species and mobile fluid species (got %d frozen, %d "
                    "mobile): the boundary is made of frozen particles",
                    frozen, mobile);
  if (!(o->r_phi > 0) || !(o->phi_c > 0 && o->phi_c < 1))
    return r->error(r, "effects.wall_boundary", "expected r_phi > 0 and 0 < phi_c < 1");
  if (o->no_slip && !s->effect[EFFECT_DPD_THERMOSTAT])
    return r->error(r, "effects.wall_boundary.no_slip",
                    "no slip scales the thermostat's wall pairs: name dpd_thermostat too, or set "
                    "no_slip: false");
  if (s->geometry.on && !s->effect[EFFECT_BOUNCE_BACK])
    r->warn(r, "effects.wall_boundary",
            "the phi_c surface of a frozen wall at density 8 is not the voxel faces: the wall has "
            "holes where phi < phi_c, and fluid particles find them (measured on an image slit: "
            "fluid inside solid voxels in every sample). Name bounce_back as well to keep every "
            "fluid particle out of the solid voxels (docs/walls.md)");
  return 0;
}

/* The wall field needs the frozen partners within r_phi in the lists and the ghost layer. */
static double cutoff(const scene_t *s, int a, int b) {
  return (!s->species[a].frozen && s->species[b].frozen) ? options_of(s)->r_phi : 0.0;
}

static void pair_coef(const scene_t *s, int a, int b, pair_coef_t *c) {
  if (s->species[a].frozen || !s->species[b].frozen) return;
  const double r2 = options_of(s)->r_phi * options_of(s)->r_phi;
  c->wall_phi2 = r2;
  if (r2 > c->cut2) c->cut2 = r2;
}

static int configure(const scene_t *s, plan_t *plan, char *err, size_t errlen) {
  (void)err, (void)errlen;
  const wall_boundary_options_t *o = options_of(s);
  wall_boundary_params_t *w = &plan->particle.wall_boundary;
  const double h = o->r_phi, rho_w = rho_wall_of(s);
  const double norm = 105.0 / (16.0 * MESO_PI * h * h * h); /* Lucy kernel, physics.md 3 */
  memset(w, 0, sizeof *w);
  w->r_phi2 = h * h;
  w->inv_h = 1.0 / h;
  w->w_norm = norm / rho_w;
  w->g_norm = 12.0 * norm / (h * h * rho_w);
  w->phi_c = o->phi_c;
  w->dt = s->dt;
  for (int a = 0; a < s->n_species; a++) /* moving walls: the reflection is relative to them */
    if (s->species[a].moving) {
      w->moving = 1;
      for (int d = 0; d < 3; d++) w->wall_u[a][d] = s->species[a].velocity[d];
    }
  plan->wall_field = 1;
  if (o->no_slip) plan->pair_terms |= PAIR_TERM_WALL_NO_SLIP;
  return 0;
}

static void describe(const scene_t *s, FILE *out) {
  const wall_boundary_options_t *o = options_of(s);
  fprintf(out,
          "wall_boundary: wall fraction phi (Lucy kernel, r_phi %g, rho_wall %g) from the frozen "
          "particles; a drift predicted past phi_c %g is reflected from the old position",
          o->r_phi, rho_wall_of(s), o->phi_c);
  if (o->no_slip)
    fprintf(out, "; no slip: wall pairs' gamma x ratio(phi), sigma x sqrt(ratio) (Li et al. 2018)");
}

const effect_t effect_wall_boundary = {
    .scene = {.name = "wall_boundary",
              .confines = 0,
              .defaults = defaults,
              .parse = parse,
              .check = check},
    .id = EFFECT_WALL_BOUNDARY,
    .needs = NEED_AFTER_DRIFT | NEED_WALL_FIELD,
    .cutoff = cutoff,
    .pair_coef = pair_coef,
    .configure = configure,
    .describe = describe,
};
