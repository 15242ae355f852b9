/* box_walls: specular reflection on the non-periodic faces of the box. A particle that crossed face
 * x = lo during the drift is mirrored, x <- 2 lo - x, and its normal velocity reversed, v_n <- -v_n
 * (the tangential velocity is kept: a slip wall). Periodic axes are left alone. */
#include "effect.h"

#include <math.h>

static long after_drift(const scene_t *s, const plan_t *plan, particles_t *p,
                        effect_violation_t *bad) {
  (void)plan;
  long n_bad = 0;
  for (int d = 0; d < 3; d++) {
    if (s->periodic[d]) continue;
    const double lo = s->box_lo[d], hi = s->box_hi[d];
    double *x = p->x[d], *v = p->v[d];
    for (int i = 0; i < p->n_local; i++) {
      if (x[i] < lo) {
        x[i] = 2.0 * lo - x[i];
        v[i] = -v[i];
      } else if (x[i] >= hi) {
        x[i] = 2.0 * hi - x[i];
        v[i] = -v[i];
        if (x[i] >= hi) x[i] = nextafter(hi, lo); /* x == hi exactly: stay inside [lo, hi) */
      }
      if (!(x[i] >= lo && x[i] < hi)) { /* moved more than a box length, or NaN */
        if (n_bad++ == 0) {
          bad->id = p->id[i];
          for (int k = 0; k < 3; k++) bad->x[k] = p->x[k][i];
        }
      }
    }
  }
  return n_bad;
}

static void describe(const scene_t *s, FILE *out) {
  fprintf(out, "box_walls: reflect on faces");
  int any = 0;
  for (int d = 0; d < 3; d++)
    if (!s->periodic[d]) {
      fprintf(out, " %c = %g and %c = %g;", "xyz"[d], s -> box_lo[d], "xyz"[d], s -> box_hi[d]);
      any = 1;
    }
  fprintf(out, any ? " position mirrored, normal velocity reversed" : " (none: all axes periodic)");
}

const effect_t effect_box_walls = {
    .id = EFFECT_BOX_WALLS,
    .name = "box_walls",
    .needs = NEED_AFTER_DRIFT,
    .after_drift = after_drift,
    .describe = describe,
};
