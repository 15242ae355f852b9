/* dpd_conservative: standard DPD soft repulsion a w_c(r) e, w_c = 1 - r/rc, a > 0 (Groot & Warren
 * 1997). Uses the pair's A value as a. Same pair term as mdpd_attraction, without any density. */
#include "effect.h"

#include <stddef.h>

static int check(const scene_t *s, char *err, size_t errlen) {
  for (int a = 0; a < s->n_species; a++)
    for (int b = 0; b < s->n_species; b++)
      if (s->pair[a][b].A < 0)
        fprintf(stderr,
                "%s: warning: dpd_conservative with A = %g < 0 for pair %s-%s: standard DPD has "
                "a > 0; without mdpd_repulsion an attractive fluid collapses\n",
                s->file, s->pair[a][b].A, s->species[a].name, s->species[b].name);
  (void)err;
  (void)errlen;
  return 0;
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
    .id = EFFECT_DPD_CONSERVATIVE,
    .name = "dpd_conservative",
    .needs = NEED_PAIR,
    .pair_term = PAIR_TERM_CONSERVATIVE,
    .check = check,
    .pair_coef = pair_coef,
    .describe = describe,
};
