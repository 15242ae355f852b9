/* mdpd_repulsion: the many-body repulsion B (rho_i + rho_j) w_d(r) e, w_d = 1 - r/rd (Warren 2003;
 * paper eq. 1). Needs the local densities rho_i = sum_{j != i, r < rd} w_rho(r) (self term
 * excluded, physics.md section 1) of owned particles and of ghosts: a density pass and a ghost sync
 * of rho. */
#include "effect.h"

#include <stddef.h>

static int check(const scene_t *s, char *err, size_t errlen) {
  for (int a = 0; a < s->n_species; a++)
    for (int b = 0; b < s->n_species; b++) {
      const scene_pair_t *p = &s->pair[a][b];
      if (!(p->rd > 0) || p->rd > p->rc) {
        snprintf(err, errlen, "%s: pair %s-%s: rd = %g: expected 0 < rd <= rc (rc = %g)", s->file,
                 s->species[a].name, s->species[b].name, p->rd, p->rc);
        return -1;
      }
    }
  /* Warren, PRE 87, 045303 (2013): species-dependent B or rd make the force non-conservative. */
  if (!effect_pair_param_common(s, offsetof(scene_pair_t, B)) ||
      !effect_pair_param_common(s, offsetof(scene_pair_t, rd)))
    fprintf(stderr,
            "%s: warning: mdpd_repulsion with species-dependent B or rd is not conservative "
            "(Warren 2013 no-go theorem); set wetting through A instead\n",
            s->file);
  return 0;
}

static void pair_coef(const scene_t *s, int a, int b, pair_coef_t *c) {
  c->B = s->pair[a][b].B; /* enters pair_manybody_inv(B, rho_i + rho_j, r, 1/rd) */
}

static void describe(const scene_t *s, FILE *out) {
  fprintf(out, "mdpd_repulsion: B (rho_i + rho_j) (1 - r/rd) e for r < rd; B = ");
  effect_print_pair_param(s, out, offsetof(scene_pair_t, B));
  fprintf(out, "; rd = ");
  effect_print_pair_param(s, out, offsetof(scene_pair_t, rd));
}

const effect_t effect_mdpd_repulsion = {
    .id = EFFECT_MDPD_REPULSION,
    .name = "mdpd_repulsion",
    .needs = NEED_PAIR | NEED_DENSITY_PASS,
    .pair_term = PAIR_TERM_MANYBODY,
    .check = check,
    .pair_coef = pair_coef,
    .describe = describe,
};
