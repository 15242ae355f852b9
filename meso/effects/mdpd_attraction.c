/* mdpd_attraction: the long-range conservative term A w_c(r) e, w_c = 1 - r/rc, A < 0 attracts
 * (Warren 2003; paper eq. 1; physics.md section 1). Cutoff rc. */
#include "effect.h"
#include "physics/pair_forces.h"

#include <stddef.h>

static int check(const scene_t *s, char *err, size_t errlen) {
  if (s->effect[EFFECT_DPD_CONSERVATIVE]) {
    snprintf(err, errlen,
             "%s: effects 'mdpd_attraction' and 'dpd_conservative' both use the pair amplitude A: "
             "name only one of them",
             s->file);
    return -1;
  }
  return 0;
}

static void pair_coef(const scene_t *s, int a, int b, pair_coef_t *c) {
  c->A = s->pair[a][b].A; /* enters pair_conservative_inv(A, r, 1/rc) */
}

static void describe(const scene_t *s, FILE *out) {
  fprintf(out, "mdpd_attraction: A (1 - r/rc) e for r < rc; A = ");
  effect_print_pair_param(s, out, offsetof(scene_pair_t, A));
  fprintf(out, "; rc = ");
  effect_print_pair_param(s, out, offsetof(scene_pair_t, rc));
}

const effect_t effect_mdpd_attraction = {
    .id = EFFECT_MDPD_ATTRACTION,
    .name = "mdpd_attraction",
    .needs = NEED_PAIR,
    .pair_term = PAIR_TERM_CONSERVATIVE,
    .check = check,
    .pair_coef = pair_coef,
    .describe = describe,
};
