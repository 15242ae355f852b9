/* mdpd_attraction: the long-range conservative term A w_c(r) e, w_c = 1 - r/rc, A < 0 attracts
 * (Warren 2003; paper eq. 1; physics.md section 1). Cutoff rc. The pair math is
 * pair_conservative_inv in meso/physics/pair_forces.h. */
#include "effects/effect.h"

#include <stddef.h>

static int check(const scene_t *s, scene_report_t *r) {
  if (s->effect[EFFECT_DPD_CONSERVATIVE])
    return r->error(r, "effects.dpd_conservative",
                    "expected either mdpd_attraction or dpd_conservative (got both; both use the "
                    "pair's A)");
  return 0;
}

static double cutoff(const scene_t *s, int a, int b) {
  return s->pair[a][b].rc;
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
    .scene = {.name = "mdpd_attraction", .pair_params = SCENE_PAIR_A, .check = check},
    .id = EFFECT_MDPD_ATTRACTION,
    .needs = NEED_PAIR,
    .pair_term = PAIR_TERM_CONSERVATIVE,
    .cutoff = cutoff,
    .pair_coef = pair_coef,
    .describe = describe,
};
