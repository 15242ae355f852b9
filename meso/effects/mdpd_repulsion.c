/* mdpd_repulsion: the many-body repulsion B (rho_i + rho_j) w_d(r) e, w_d = 1 - r/rd (Warren 2003;
 * paper eq. 1). Needs the local densities rho_i = sum_{j != i, r < rd} w_rho(r) (self term
 * excluded, physics.md section 1) of owned particles and of ghosts: a density pass and a ghost sync
 * of rho. Cutoff rd. The pair math is pair_manybody_inv in meso/physics/pair_forces.h. */
#include "effects/effect.h"

#include <stddef.h>
#include <string.h>

static int check(const scene_t *s, scene_report_t *r) {
  for (int a = 0; a < s->n_species; a++)
    for (int b = a; b < s->n_species; b++) {
      const scene_pair_t *p = &s->pair[a][b];
      char key[160];
      if (!(p->rd > 0) || p->rd > p->rc) {
        snprintf(key, sizeof key, "pairs.%s-%s.rd", s->species[a].name, s->species[b].name);
        return r->error(r, key, "expected 0 < rd <= rc = %g (got %g)", p->rc, p->rd);
      }
      if (!(p->B >= 0)) {
        snprintf(key, sizeof key, "pairs.%s-%s.B", s->species[a].name, s->species[b].name);
        return r->error(r, key, "expected B >= 0: the many-body term repels (got %g)", p->B);
      }
    }
  /* Warren, PRE 87, 045303 (2013): species-dependent B or rd make the force non-conservative
   * (no potential exists). The reference is the first mobile species' own pair; every pair that
   * differs from it is named in one warning. Immiscibility and wetting come from A alone. */
  int ref_sp = 0;
  while (ref_sp < s->n_species - 1 && s->species[ref_sp].frozen) ref_sp++;
  const scene_pair_t *ref = &s->pair[ref_sp][ref_sp];
  char list[640] = "", key[160] = "";
  int n = 0;
  for (int a = 0; a < s->n_species; a++)
    for (int b = a; b < s->n_species; b++) {
      const scene_pair_t *p = &s->pair[a][b];
      if (p->B == ref->B && p->rd == ref->rd) continue;
      const size_t len = strlen(list);
      if (!n) /* the warning points at the first pair that differs */
        snprintf(key, sizeof key, "pairs.%s-%s", s->species[a].name, s->species[b].name);
      if (n++ < 8)
        snprintf(list + len, sizeof list - len, "%s%s-%s (B %g, rd %g)", len ? ", " : "",
                 s->species[a].name, s->species[b].name, p->B, p->rd);
    }
  if (n)
    r->warn(r, key,
            "B or rd differs between species pairs: %s%s differ from %s-%s (B %g, rd %g): the "
            "many-body force is then not conservative (Warren, PRE 87, 045303, 2013); keep B and "
            "rd common to every pair, set immiscibility and wetting via A",
            list, n > 8 ? " and more" : "", s->species[ref_sp].name, s->species[ref_sp].name,
            ref->B, ref->rd);
  return 0;
}

static double cutoff(const scene_t *s, int a, int b) {
  return s->pair[a][b].rd;
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
    .scene = {.name = "mdpd_repulsion",
              .pair_params = SCENE_PAIR_B | SCENE_PAIR_RD,
              .check = check},
    .id = EFFECT_MDPD_REPULSION,
    .needs = NEED_PAIR | NEED_DENSITY_PASS,
    .pair_term = PAIR_TERM_MANYBODY,
    .cutoff = cutoff,
    .pair_coef = pair_coef,
    .describe = describe,
};
