/* dpd_thermostat: dissipative + random pair forces (Espanol & Warren 1995; paper eq. 1):
 *   -gamma w_R^2 (e . v_ij) e + sigma w_R xi_ij / sqrt(dt) e,  w_R = (1 - r/rc)^s,
 *   sigma^2 = 2 gamma kT.
 * xi_ij = xi_ji comes from the counter-based generator of meso/physics/pair_random.h. v_ij uses the
 * Groot-Warren predicted velocities, so ghosts must carry velocities. Options: exponent s (1), the
 * s of every pair that does not set its own pairs.X.s (a pair's s < 1 raises its viscosity: Fan et
 * al., Phys. Fluids 18, 063102, 2006; docs/twophase.md section 4);
 * rng, the generator of xi: philox (Philox4x32-10, the default), philox2x32 (Philox2x32-10) or fast
 * (Philox2x32-7 with a hashed key; pair_random.h says why it is sound). */
#include "effects/dpd_thermostat.h"
#include "effects/effect.h"
#include "physics/pair_random.h"

#include <math.h>
#include <stddef.h>

_Static_assert(sizeof(dpd_thermostat_options_t) <= SCENE_EFFECT_OPTION_BYTES, "options too large");

static dpd_thermostat_options_t *options(scene_t *s) {
  return SCENE_EFFECT_OPTIONS(s, EFFECT_DPD_THERMOSTAT, dpd_thermostat_options_t);
}
static const dpd_thermostat_options_t *options_of(const scene_t *s) {
  return SCENE_EFFECT_OPTIONS(s, EFFECT_DPD_THERMOSTAT, const dpd_thermostat_options_t);
}

static void defaults(scene_t *s) {
  options(s)->exponent = 1.0;
  options(s)->rng = PAIR_RNG_PHILOX;
}

static int parse(ytree_t *t, yaml_node_t *opt, const char *path, scene_t *s) {
  static const char *const keys[] = {"exponent", "rng", NULL};
  /* in enum pair_rng order */
  static const char *const rng_words[] = {"philox", "philox2x32", "fast", NULL};
  _Static_assert(PAIR_RNG_PHILOX == 0 && PAIR_RNG_PHILOX2X32 == 1 && PAIR_RNG_FAST == 2 &&
                     PAIR_RNG_COUNT == 3,
                 "rng_words follows enum pair_rng");
  if (yt_check_keys(t, opt, path, keys)) return -1;
  char sub[192];
  yaml_node_t *v = yt_get(t, opt, "rng");
  if (v) {
    snprintf(sub, sizeof sub, "%s.rng", path);
    const int rng = yt_enum(t, v, sub, rng_words);
    if (rng < 0) return -1;
    options(s)->rng = rng;
  }
  v = yt_get(t, opt, "exponent");
  if (!v) return 0;
  snprintf(sub, sizeof sub, "%s.exponent", path);
  if (yt_double(t, v, sub, &options(s)->exponent)) return -1;
  if (!(options(s)->exponent > 0))
    return yt_error(t, v, sub, "expected an exponent s > 0 of w_R = (1 - r/rc)^s (got %g)",
                    options(s)->exponent);
  return 0;
}

/* The exponent s of w_R for pair (a, b): its own pairs.X.s, else the effect's exponent. */
static double pair_exponent(const scene_t *s, int a, int b) {
  const double own = s->pair[a][b].s, e = options_of(s)->exponent;
  return own > 0 ? own : e > 0 ? e : 1.0;
}

static int check(const scene_t *s, scene_report_t *r) {
  const int rng = options_of(s)->rng;
  if (rng < 0 || rng >= PAIR_RNG_COUNT) /* scenes built in code */
    return r->error(r, "effects.dpd_thermostat.rng",
                    "expected philox, philox2x32 or fast (got generator number %d)", rng);
  if (!(s->kT >= 0))
    return r->error(r, "kT", "expected kT >= 0 for dpd_thermostat (got %g)", s->kT);
  for (int a = 0; a < s->n_species; a++)
    for (int b = a; b < s->n_species; b++)
      if (!(s->pair[a][b].gamma >= 0)) {
        char key[160];
        snprintf(key, sizeof key, "pairs.%s-%s.gamma", s->species[a].name, s->species[b].name);
        return r->error(r, key, "expected gamma >= 0 (got %g)", s->pair[a][b].gamma);
      }
  for (int a = 0; a < s->n_species; a++) /* scenes built in code; the parser checks the file's */
    for (int b = a; b < s->n_species; b++)
      if (!(s->pair[a][b].s >= 0 && s->pair[a][b].s <= SCENE_PAIR_S_MAX)) {
        char key[160];
        snprintf(key, sizeof key, "pairs.%s-%s.s", s->species[a].name, s->species[b].name);
        return r->error(r, key,
                        "expected an exponent 0 < s <= %g of w_R = (1 - r/rc)^s, or 0 for the "
                        "thermostat's exponent (got %g)",
                        SCENE_PAIR_S_MAX, s->pair[a][b].s);
      }
  return 0;
}

static double cutoff(const scene_t *s, int a, int b) {
  return s->pair[a][b].rc;
}

static void pair_coef(const scene_t *s, int a, int b, pair_coef_t *c) {
  c->gamma = s->pair[a][b].gamma;
  c->sigma = sqrt(2.0 * c->gamma * s->kT); /* fluctuation-dissipation */
  c->s_exp = pair_exponent(s, a, b);
  c->s_one = c->s_exp == 1.0; /* the standard weight: no pow, bitwise as without the key */
}

static int configure(const scene_t *s, plan_t *plan, char *err, size_t errlen) {
  (void)err, (void)errlen;
  const double e = options_of(s)->exponent;
  plan->weight_exp = e > 0 ? e : 1.0;
  plan->pair_rng = options_of(s)->rng;
  return 0;
}

static void describe(const scene_t *s, FILE *out) {
  int common = 1;
  for (int a = 0; a < s->n_species; a++)
    for (int b = a; b < s->n_species; b++)
      common &= pair_exponent(s, a, b) == pair_exponent(s, 0, 0);
  fprintf(out,
          "dpd_thermostat: -gamma w_R^2 (e.v~) e + sigma w_R xi/sqrt(dt) e, w_R = (1 - r/rc)^");
  if (common) {
    fprintf(out, "%g", s->n_species > 0 ? pair_exponent(s, 0, 0) : 1.0);
  } else { /* per pair, as the other pair parameters are printed */
    fprintf(out, "s, s = ");
    for (int a = 0; a < s->n_species; a++)
      for (int b = a; b < s->n_species; b++)
        fprintf(out, "%s%s-%s %g", a || b ? ", " : "", s->species[a].name, s->species[b].name,
                pair_exponent(s, a, b));
  }
  fprintf(out, "; gamma = ");
  effect_print_pair_param(s, out, offsetof(scene_pair_t, gamma));
  const int rng = options_of(s)->rng;
  fprintf(out, "; kT = %g; xi from %s (rng %s; seed %llu, step, ids)", s->kT,
          pair_rng_construction(rng), pair_rng_word(rng), (unsigned long long)s->seed);
}

const effect_t effect_dpd_thermostat = {
    .scene = {.name = "dpd_thermostat",
              .pair_params = SCENE_PAIR_GAMMA,
              .defaults = defaults,
              .parse = parse,
              .check = check},
    .id = EFFECT_DPD_THERMOSTAT,
    .needs = NEED_PAIR | NEED_GHOST_V,
    .pair_term = PAIR_TERM_THERMOSTAT,
    .cutoff = cutoff,
    .pair_coef = pair_coef,
    .configure = configure,
    .describe = describe,
};
