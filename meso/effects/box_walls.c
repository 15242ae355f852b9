/* box_walls: specular reflection on the non-periodic faces of the box (position mirrored, normal
 * velocity reversed: a slip wall). Periodic axes are left alone. The per-particle math both
 * backends run after the drift is box_walls_after_drift in meso/physics/box_walls.h. */
#include "effects/effect.h"

static int check(const scene_t *s, scene_report_t *r) {
  if (s->periodic[0] && s->periodic[1] && s->periodic[2])
    r->warn(r, "effects.box_walls", "every box axis is periodic: box_walls has nothing to do");
  return 0;
}

static int configure(const scene_t *s, plan_t *plan, char *err, size_t errlen) {
  (void)err, (void)errlen;
  box_walls_params_t *w = &plan->particle.box_walls;
  for (int d = 0; d < 3; d++) {
    w->lo[d] = s->box_lo[d];
    w->hi[d] = s->box_hi[d];
    w->reflect[d] = !s->periodic[d];
  }
  return 0;
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
    .scene = {.name = "box_walls", .confines = 1, .check = check},
    .id = EFFECT_BOX_WALLS,
    .needs = NEED_AFTER_DRIFT,
    .configure = configure,
    .describe = describe,
};
