/* dpd_conservative: standard DPD soft repulsion a w_c(r) e, w_c = 1 - r/rc, a > 0 (Groot & Warren
 * 1997). Uses the pair's A value as a. Same pair term as mdpd_attraction, without any density. */
#include "effects/effect.h"

#include <stddef.h>

static int check(const scene_t *s, scene_report_t *r) {
  for (int a = 0; a < s->n_species; a++)
    for (int b = a; b < s->n_species; b++)
      if (s->pair[a][b].A < 0) {
        char key[160];
        snprintf(key, sizeof key, "pairs.%s-%s.A", s->species[a].name, s->species[b].name);
        r->warn(r, key,
                "dpd_conservative with A = %g < 0: standard DPD has a > 0; without "
                "mdpd_repulsion an attractive fluid collapses",
                s->pair[a][b].A);
      }
  return 0;
}

static double cutoff(const scene_t *s, int a, int b) {
  return s->pair[a][b].rc;
}

static void pair_coef(const scene_t *s, int a, int b, pair_coef_t *c) {
  c->A = s->pair[a][b].A;
}

static void describe(const scene_t *s, FILE *out) {
  fprintf(out, "dpd_conservative: a (1 - r/rc) e for r < rc; a = ");
  effect_print_pair_param(s, out, offsetof(scene_pair_t, A));
  fprintf(out, "; rc = ");
  effect_print_pair_param(s, out, offsetof(scene_pair_t, rc));
}

const effect_t effect_dpd_conservative = {
    .scene = {.name = "dpd_conservative", .pair_params = SCENE_PAIR_A, .check = check},
    .id = EFFECT_DPD_CONSERVATIVE,
    .needs = NEED_PAIR,
    .pair_term = PAIR_TERM_CONSERVATIVE,
    .cutoff = cutoff,
    .pair_coef = pair_coef,
    .describe = describe,
};
