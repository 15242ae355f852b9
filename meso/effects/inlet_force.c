/* inlet_force: a constant force g per particle of a species, applied only inside a slab [lo, hi)
 * along one periodic axis: pressure-driven flow through a sample, the force acting in an inlet
 * region of the reservoir (docs/permeability.md "Pressure-driven runs"). With
 * `sample: [lo, hi]` the run also measures the pressure drop between probe slabs just outside the
 * sample's faces (analysis/pressure_drop.c). The per-particle math both backends run is
 * inlet_force_particle_force in meso/physics/inlet_force.h. */
#include "effects/inlet_force.h"
#include "effects/effect.h"

#include <math.h>
#include <string.h>

_Static_assert(sizeof(inlet_force_options_t) <= SCENE_EFFECT_OPTION_BYTES, "options too large");

static inlet_force_options_t *options(scene_t *s) {
  return SCENE_EFFECT_OPTIONS(s, EFFECT_INLET_FORCE, inlet_force_options_t);
}
static const inlet_force_options_t *options_of(const scene_t *s) {
  return SCENE_EFFECT_OPTIONS(s, EFFECT_INLET_FORCE, const inlet_force_options_t);
}

static void defaults(scene_t *s) {
  inlet_force_options_t *o = options(s);
  memset(o, 0, sizeof *o);
  o->force.axis = -1;
  o->force.lo = o->force.hi = NAN;
  o->probe_gap = 0.5;
  o->probe_width = 0.5;
}

/* [a, b] with a < b. */
static int interval(ytree_t *t, yaml_node_t *v, const char *path, double *lo, double *hi) {
  if (yt_expect_seq(t, v, path)) return -1;
  if (yt_seq_size(v) != 2)
    return yt_error(t, v, path, "expected a list of two numbers [lo, hi] (got %d items)",
                    yt_seq_size(v));
  if (yt_double(t, yt_seq_item(t, v, 0), path, lo) || yt_double(t, yt_seq_item(t, v, 1), path, hi))
    return -1;
  if (!(*hi > *lo)) return yt_error(t, v, path, "expected hi > lo (got [%g, %g])", *lo, *hi);
  return 0;
}

/* inlet_force: {SPECIES: [gx, gy, gz], ..., along: x|y|z, slab: [lo, hi], sample: [lo, hi],
 *               probe_gap: G, probe_width: W} */
static int parse(ytree_t *t, yaml_node_t *opt, const char *path, scene_t *s) {
  static const char *const axis_words[] = {"x", "y", "z", NULL};
  inlet_force_options_t *o = options(s);
  static const char *const named[] = {"along",     "slab",        "sample",
                                      "probe_gap", "probe_width", NULL}; /* + species names */
  yt_record_keys(path, named, 1);
  if (yt_check_keys(t, opt, path, NULL)) return -1; /* a map; each key once, as text */
  const int n = yt_map_size(opt);
  int have_slab = 0;
  for (int j = 0; j < n; j++) {
    yaml_node_t *kn;
    const char *key = yt_map_key(t, opt, j, &kn);
    char sub[192];
    snprintf(sub, sizeof sub, "%s.%s", path, key ? key : "?");
    yaml_node_t *v = yt_map_value(t, opt, j);
    if (key && !strcmp(key, "along")) {
      if ((o->force.axis = yt_enum(t, v, sub, axis_words)) < 0) return -1;
    } else if (key && !strcmp(key, "slab")) {
      if (interval(t, v, sub, &o->force.lo, &o->force.hi)) return -1;
      have_slab = 1;
    } else if (key && !strcmp(key, "sample")) {
      if (interval(t, v, sub, &o->sample_lo, &o->sample_hi)) return -1;
      o->has_sample = 1;
    } else if (key && (!strcmp(key, "probe_gap") || !strcmp(key, "probe_width"))) {
      const int gap = !strcmp(key, "probe_gap");
      double *w = gap ? &o->probe_gap : &o->probe_width;
      if (yt_double(t, v, sub, w)) return -1;
      if (gap ? !(*w >= 0) : !(*w > 0))
        return yt_error(t, v, sub, "expected a length %s (got %g)", gap ? ">= 0" : "> 0", *w);
    } else {
      const int species = key ? scene_species_index(s, key) : -1;
      if (species < 0)
        return yt_error(t, kn, sub,
                        "expected a species name, 'along', 'slab', 'sample', 'probe_gap' or "
                        "'probe_width' (got '%s')",
                        key ? key : "?");
      if (yt_vec3(t, v, sub, o->force.g[species])) return -1;
    }
  }
  if (o->force.axis < 0)
    return yt_error(t, opt, path, "expected key 'along: x|y|z' (the slab's normal; it is missing)");
  if (!have_slab)
    return yt_error(t, opt, path,
                    "expected key 'slab: [lo, hi]' (the forced region; it is missing)");
  return 0;
}

static int check(const scene_t *s, scene_report_t *r) {
  const inlet_force_options_t *o = options_of(s);
  const int a = o->force.axis;
  if (a < 0) return 0; /* parse said so */
  const double blo = s->box_lo[a], bhi = s->box_hi[a], L = bhi - blo;
  if (!s->periodic[a])
    return r->error(r, "effects.inlet_force.along",
                    "expected a periodic axis (the fluid leaves the sample into the reservoir "
                    "through the periodic face; got a non-periodic one)");
  if (!(o->force.lo >= blo && o->force.hi <= bhi))
    return r->error(r, "effects.inlet_force.slab",
                    "expected a slab inside the box along %c, [%g, %g] (got [%g, %g])", 'x' + a,
                    blo, bhi, o->force.lo, o->force.hi);
  if (!o->has_sample) return 0;
  if (s->flux.every <= 0 || s->flux.axis != a)
    return r->error(r, "effects.inlet_force.sample",
                    "expected output.flux along %c with it (the pressure drop is sampled with the "
                    "flux; got %s)",
                    'x' + a, s->flux.every <= 0 ? "no output.flux" : "another flux axis");
  if (!(o->sample_lo >= blo && o->sample_hi <= bhi))
    return r->error(r, "effects.inlet_force.sample",
                    "expected the sample inside the box along %c, [%g, %g] (got [%g, %g])", 'x' + a,
                    blo, bhi, o->sample_lo, o->sample_hi);
  if (scene_circle_overlap(o->force.lo, o->force.hi, o->sample_lo, o->sample_hi, L) > 0)
    return r->error(r, "effects.inlet_force.slab",
                    "expected the forced slab outside the sample [%g, %g] (got [%g, %g])",
                    o->sample_lo, o->sample_hi, o->force.lo, o->force.hi);
  const double gw = o->probe_gap + o->probe_width;
  const double in0 = o->sample_lo - gw, out0 = o->sample_hi + o->probe_gap;
  if (2 * gw + (o->sample_hi - o->sample_lo) > L ||
      scene_circle_overlap(in0, in0 + o->probe_width, o->force.lo, o->force.hi, L) > 1e-12 ||
      scene_circle_overlap(out0, out0 + o->probe_width, o->force.lo, o->force.hi, L) > 1e-12)
    return r->error(r, "effects.inlet_force.probe_width",
                    "expected the probe slabs (width %g, %g from the sample faces) to fit "
                    "between the sample and the forced slab (they overlap one of them)",
                    o->probe_width, o->probe_gap);
  return 0;
}

static int configure(const scene_t *s, plan_t *plan, char *err, size_t errlen) {
  (void)err, (void)errlen;
  inlet_force_params_t *b = &plan->particle.inlet_force;
  *b = options_of(s)->force;
  b->box_lo = s->box_lo[b->axis];
  b->box_len = s->box_hi[b->axis] - s->box_lo[b->axis];
  return 0;
}

static void describe(const scene_t *s, FILE *out) {
  const inlet_force_options_t *o = options_of(s);
  const char ax = (char)('x' + o->force.axis);
  fprintf(out, "inlet_force: constant force per particle inside %c in [%g, %g):", ax, o->force.lo,
          o->force.hi);
  for (int a = 0; a < s->n_species; a++) {
    const double *g = o->force.g[a];
    fprintf(out, " %s (%g, %g, %g)%s", s->species[a].name, g[0], g[1], g[2],
            a + 1 < s->n_species ? "," : "");
  }
  if (o->has_sample)
    fprintf(out,
            "; pressure drop measured across the sample %c in [%g, %g] (probe slabs %g wide, %g "
            "outside its faces)",
            ax, o->sample_lo, o->sample_hi, o->probe_width, o->probe_gap);
}

const effect_t effect_inlet_force = {
    .scene = {.name = "inlet_force", .defaults = defaults, .parse = parse, .check = check},
    .id = EFFECT_INLET_FORCE,
    .needs = NEED_PARTICLE,
    .configure = configure,
    .describe = describe,
};
