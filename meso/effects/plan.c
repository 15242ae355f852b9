/* Build the step plan from the effects a scene names: checks, constants, phase lists (plan.h). */
#include "effects/plan.h"
#include "effects/effect.h"
#include "physics/density_kernels.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const step_phase_names[PHASE_COUNT] = {
    [PHASE_KICK_DRIFT] = "kick_drift",
    [PHASE_AFTER_DRIFT] = "after_drift",
    [PHASE_CHECK_DRIFT] = "check_drift",
    [PHASE_MIGRATE] = "migrate",
    [PHASE_SORT] = "sort",
    [PHASE_PREDICT] = "predict",
    [PHASE_GHOSTS] = "ghosts",
    [PHASE_NEIGHBOURS] = "neighbours",
    [PHASE_DENSITY] = "density",
    [PHASE_RHO_SYNC] = "rho_sync",
    [PHASE_WALL_FIELD] = "wall_field",
    [PHASE_PAIR_FORCES] = "pair_forces",
    [PHASE_PARTICLE_FORCES] = "particle_forces",
    [PHASE_KICK] = "kick",
    [PHASE_CHECK] = "check",
};

/* An effect's check on a scene built in code: the first error becomes the plan's message. */
typedef struct {
  const scene_t *scene;
  char *err;
  size_t errlen;
} report_buf_t;

static int buf_error(scene_report_t *r, const char *key, const char *fmt, ...) {
  report_buf_t *b = r->ctx;
  char msg[768];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  snprintf(b->err, b->errlen, "%s: key '%s': %s", b->scene->file, key, msg);
  return -1;
}

static void buf_warn(scene_report_t *r, const char *key, const char *fmt, ...) {
  (void)r, (void)key, (void)fmt; /* the scene parser already printed it */
}

static void add_phase(unsigned char *list, int *n, int phase) {
  list[(*n)++] = (unsigned char)phase;
}

/* The ordered phase lists of the set-up and of a step (enum step_phase). */
static void build_phases(plan_t *plan) {
  const int pairs = plan->pair_terms != 0 || plan->wall_field;
  plan->n_setup = plan->n_step = 0;
  add_phase(plan->step, &plan->n_step, PHASE_KICK_DRIFT);
  if (plan->walls) add_phase(plan->step, &plan->n_step, PHASE_AFTER_DRIFT);
  add_phase(plan->step, &plan->n_step, PHASE_CHECK_DRIFT);
  add_phase(plan->step, &plan->n_step, PHASE_MIGRATE);
  /* set-up and step share the force phases */
  for (int setup = 1; setup >= 0; setup--) {
    unsigned char *list = setup ? plan->setup : plan->step;
    int *n = setup ? &plan->n_setup : &plan->n_step;
    add_phase(list, n, PHASE_SORT);
    if (plan->use_vpred) add_phase(list, n, PHASE_PREDICT);
    if (pairs) {
      add_phase(list, n, PHASE_GHOSTS);
      add_phase(list, n, PHASE_NEIGHBOURS);
    }
    if (plan->density) {
      add_phase(list, n, PHASE_DENSITY);
      add_phase(list, n, PHASE_RHO_SYNC);
    }
    if (plan->wall_field) add_phase(list, n, PHASE_WALL_FIELD);
    add_phase(list, n, PHASE_PAIR_FORCES);
    if (plan->particle_forces) add_phase(list, n, PHASE_PARTICLE_FORCES);
    if (!setup) add_phase(list, n, PHASE_KICK);
    add_phase(list, n, PHASE_CHECK);
  }
}

int plan_add_array(plan_t *plan, size_t offset, size_t bytes) {
  if (plan->n_arrays >= PLAN_MAX_ARRAYS) return -1;
  plan->arrays[plan->n_arrays].offset = offset;
  plan->arrays[plan->n_arrays].bytes = bytes;
  plan->n_arrays++;
  return 0;
}

void *plan_array(const plan_t *plan, int k) {
  return *(void *const *)((const char *)&plan->particle + plan->arrays[k].offset);
}

void plan_release(plan_t *plan) {
  for (int k = 0; k < plan->n_arrays; k++) {
    free(plan_array(plan, k));
    *(void **)((char *)&plan->particle + plan->arrays[k].offset) = NULL;
  }
  plan->n_arrays = 0;
}

int plan_has_phase(const plan_t *plan, int setup, int phase) {
  const unsigned char *list = setup ? plan->setup : plan->step;
  const int n = setup ? plan->n_setup : plan->n_step;
  for (int k = 0; k < n; k++)
    if (list[k] == phase) return 1;
  return 0;
}

static const char axis_name[3] = {'x', 'y', 'z'};

static int check_scene_basics(const scene_t *s, char *err, size_t errlen) {
  if (s->n_species < 1 || s->n_species > SCENE_MAX_SPECIES) {
    snprintf(err, errlen, "%s: %d species: expected 1 to %d", s->file, s->n_species,
             SCENE_MAX_SPECIES);
    return -1;
  }
  for (int d = 0; d < 3; d++)
    if (!(s->box_hi[d] > s->box_lo[d])) {
      snprintf(err, errlen, "%s: box along %c is [%g, %g]: expected lo < hi", s->file, axis_name[d],
               s->box_lo[d], s->box_hi[d]);
      return -1;
    }
  for (int a = 0; a < s->n_species; a++)
    if (!(s->species[a].mass > 0)) {
      snprintf(err, errlen, "%s: species '%s': mass = %g: expected > 0", s->file,
               s->species[a].name, s->species[a].mass);
      return -1;
    }
  if (!(s->dt > 0)) {
    snprintf(err, errlen, "%s: dt = %g: expected dt > 0", s->file, s->dt);
    return -1;
  }
  /* Without an effect that keeps particles in, one reaching a non-periodic face would leave. */
  int confined = 0;
  for (int e = 0; e < EFFECT_COUNT; e++) confined |= s->effect[e] && effect_get(e)->scene.confines;
  for (int d = 0; d < 3; d++)
    if (!s->periodic[d] && !confined) {
      snprintf(err, errlen,
               "%s: axis %c is not periodic but no effect keeps particles in (name box_walls or "
               "make the axis periodic)",
               s->file, axis_name[d]);
      return -1;
    }
  return 0;
}

static int build(plan_t *plan, const scene_t *s, char *err, size_t errlen) {
  if (check_scene_basics(s, err, errlen)) return -1;
  report_buf_t buf = {s, err, errlen};
  scene_report_t report = {.error = buf_error, .warn = buf_warn, .ctx = &buf};
  unsigned needs = 0;
  plan->weight_exp = 1.0; /* the thermostat's configure sets its exponent */
  for (int e = 0; e < EFFECT_COUNT; e++) {
    plan->named[e] = s->effect[e] != 0;
    plan->particle.on[e] = plan->named[e];
    if (!plan->named[e]) continue;
    const effect_t *eff = effect_get(e);
    if (eff->scene.check && eff->scene.check(s, &report)) return -1;
    needs |= eff->needs;
    if (eff->needs & NEED_PAIR) plan->pair_terms |= (int)eff->pair_term;
    if (eff->configure && eff->configure(s, plan, err, errlen)) return -1;
    for (int a = 0; a < s->n_species; a++)
      for (int b = 0; b < s->n_species; b++)
        if (eff->cutoff && eff->cutoff(s, a, b) > plan->rcut) plan->rcut = eff->cutoff(s, a, b);
  }
  plan->density = (needs & NEED_DENSITY_PASS) != 0;
  plan->density_kernel = s->density_kernel;
  plan->ghost_v = (needs & NEED_GHOST_V) != 0;
  plan->use_vpred = plan->ghost_v && s->vv_lambda != 0.5;
  plan->particle_forces = (needs & NEED_PARTICLE) != 0;
  plan->walls = (needs & NEED_AFTER_DRIFT) != 0;
  plan->wall_field = (needs & NEED_WALL_FIELD) != 0;
  plan->weight_exp_is_one = plan->weight_exp == 1.0;
  plan->max_disp = 0.5 * (plan->rcut > 0 ? plan->rcut : 1.0);
  plan->dt = s->dt;
  plan->half_dt = 0.5 * s->dt;
  plan->inv_sqrt_dt = 1.0 / sqrt(s->dt);
  plan->vv_lambda = s->vv_lambda;
  plan->predict_c = (s->vv_lambda - 0.5) * s->dt;
  plan->seed = s->seed;
  plan->n_species = s->n_species;
  for (int a = 0; a < s->n_species; a++) {
    plan->mass[a] = s->species[a].mass;
    plan->inv_mass[a] = 1.0 / s->species[a].mass;
    plan->mobile[a] = !s->species[a].frozen;
    plan->moving[a] = s->species[a].frozen && s->species[a].moving;
    for (int d = 0; d < 3; d++)
      plan->wall_u[a][d] = plan->moving[a] ? s->species[a].velocity[d] : 0;
    plan->any_moving |= plan->moving[a];
    plan->static_frozen[a] = s->species[a].frozen && !plan->moving[a];
    if (plan->density && plan->static_frozen[a]) plan->density_cache = 1;
  }
  const char *cache_env = getenv("MDPORE_DENSITY_CACHE");
  if (cache_env && !strcmp(cache_env, "0")) plan->density_cache = 0;
  if (plan->pair_terms && !(plan->rcut > 0)) {
    snprintf(err, errlen, "%s: pair effects are named but every pair cutoff is 0", s->file);
    return -1;
  }
  if (plan->density && s->density_kernel != MESO_KERNEL_WARREN &&
      s->density_kernel != MESO_KERNEL_LUCY) {
    snprintf(err, errlen, "%s: density kernel %d: expected warren or lucy", s->file,
             s->density_kernel);
    return -1;
  }
  for (int a = 0; a < s->n_species; a++)
    for (int b = 0; b < s->n_species; b++) {
      const scene_pair_t *sp = &s->pair[a][b];
      pair_coef_t *c = &plan->coef[a][b];
      const int uses_rc = plan->pair_terms & (PAIR_TERM_CONSERVATIVE | PAIR_TERM_THERMOSTAT);
      if (uses_rc && !(sp->rc > 0)) {
        snprintf(err, errlen, "%s: pair %s-%s: rc = %g: expected rc > 0", s->file,
                 s->species[a].name, s->species[b].name, sp->rc);
        return -1;
      }
      c->rc = sp->rc;
      c->inv_rc = sp->rc > 0 ? 1.0 / sp->rc : 0.0;
      c->rc2 = uses_rc ? sp->rc * sp->rc : 0.0;
      c->rd = sp->rd;
      c->inv_rd = sp->rd > 0 ? 1.0 / sp->rd : 0.0;
      c->rd2 = plan->density ? sp->rd * sp->rd : 0.0;
      c->wnorm = sp->rd > 0 ? w_rho_norm(s->density_kernel, sp->rd) : 0.0;
      c->cut2 = c->rc2 > c->rd2 ? c->rc2 : c->rd2;
      c->s_exp = 1.0; /* the thermostat's pair_coef sets the pair's exponent */
      c->s_one = 1;
      for (int e = 0; e < EFFECT_COUNT; e++) {
        const effect_t *eff = effect_get(e);
        if (plan->named[e] && eff->pair_coef) eff->pair_coef(s, a, b, c);
      }
    }
  build_phases(plan);
  return 0;
}

int plan_build(plan_t *plan, const scene_t *s, char *err, size_t errlen) {
  memset(plan, 0, sizeof *plan);
  if (build(plan, s, err, errlen) == 0) return 0;
  plan_release(plan); /* the arrays of the effects configured so far */
  return -1;
}
