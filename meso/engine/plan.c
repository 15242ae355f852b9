/* Build the step plan from the effects a scene names (see plan.h). */
#include "plan.h"
#include "effects/effect.h"
#include "physics/density_kernels.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

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
  /* Without reflecting walls a particle reaching a non-periodic face would leave the box. */
  for (int d = 0; d < 3; d++)
    if (!s->periodic[d] && !s->effect[EFFECT_BOX_WALLS]) {
      snprintf(err, errlen,
               "%s: axis %c is not periodic but the effect 'box_walls' is not named: particles "
               "would leave the box (name box_walls or make the axis periodic)",
               s->file, axis_name[d]);
      return -1;
    }
  return 0;
}

int plan_build(plan_t *plan, const scene_t *s, char *err, size_t errlen) {
  memset(plan, 0, sizeof *plan);
  if (check_scene_basics(s, err, errlen)) return -1;
  unsigned needs = 0;
  for (int e = 0; e < EFFECT_COUNT; e++) {
    plan->named[e] = s->effect[e] != 0;
    if (!plan->named[e]) continue;
    const effect_t *eff = effect_get(e);
    if (eff->check && eff->check(s, err, errlen)) return -1;
    needs |= eff->needs;
    if (eff->needs & NEED_PAIR) plan->pair_terms |= (int)eff->pair_term;
  }
  plan->density = (needs & NEED_DENSITY_PASS) != 0;
  plan->density_kernel = s->density_kernel;
  plan->ghost_v = (needs & NEED_GHOST_V) != 0;
  plan->use_vpred = plan->ghost_v && s->vv_lambda != 0.5;
  plan->particle_forces = (needs & NEED_PARTICLE) != 0;
  plan->walls = (needs & NEED_AFTER_DRIFT) != 0;
  plan->weight_exp = s->weight_exp > 0 ? s->weight_exp : 1.0;
  plan->weight_exp_is_one = plan->weight_exp == 1.0;
  plan->rcut = scene_max_cutoff(s); /* meso/io/scene_util.c */
  plan->max_disp = 0.5 * (plan->rcut > 0 ? plan->rcut : 1.0);
  plan->n_species = s->n_species;
  for (int a = 0; a < s->n_species; a++) {
    plan->mass[a] = s->species[a].mass;
    plan->inv_mass[a] = 1.0 / s->species[a].mass;
    plan->mobile[a] = !s->species[a].frozen;
  }
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
      for (int e = 0; e < EFFECT_COUNT; e++) {
        const effect_t *eff = effect_get(e);
        if (plan->named[e] && eff->pair_coef) eff->pair_coef(s, a, b, c);
      }
    }
  return 0;
}
