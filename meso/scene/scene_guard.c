/* The `guard:` block (scene_guard.h). */
#include "scene/scene_guard.h"
#include "common/size_check.h"

#include <math.h>

/* the density guard's arrays per bin: pore volume, count and reference (analysis/density_guard.c) */
#define GUARD_BYTES_PER_BIN 24.0

#define TRY(x)                                                                                     \
  do {                                                                                             \
    if ((x) != 0) return -1;                                                                       \
  } while (0)

void scene_guard_defaults(scene_t *s) {
  s->guard.temperature_tolerance = 0.5;
  s->guard.temperature_window = 1000;
  s->guard.density_every = 0;
  s->guard.density_bin = 3.0;
  s->guard.density_fraction = 0.3;
}

int scene_parse_guard(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"temperature_tolerance", "temperature_window", "density_every",
                                     "density_bin",           "density_fraction",   NULL};
  TRY(yt_check_keys(t, n, "guard", keys));
  scene_guard_t *g = &s->guard;
  yaml_node_t *v;
  if ((v = yt_get(t, n, "temperature_tolerance"))) {
    TRY(yt_double(t, v, "guard.temperature_tolerance", &g->temperature_tolerance));
    if (!(g->temperature_tolerance >= 0))
      return yt_error(t, v, "guard.temperature_tolerance",
                      "expected a relative tolerance >= 0 (0: off; e.g. 0.5 stops at T > 1.5 kT) "
                      "(got %g)",
                      g->temperature_tolerance);
  }
  if ((v = yt_get(t, n, "temperature_window"))) {
    TRY(yt_long(t, v, "guard.temperature_window", &g->temperature_window));
    if (g->temperature_window < 1)
      return yt_error(t, v, "guard.temperature_window", "expected steps >= 1 (got %ld)",
                      g->temperature_window);
  }
  if ((v = yt_get(t, n, "density_every"))) {
    TRY(yt_long(t, v, "guard.density_every", &g->density_every));
    if (g->density_every < 0)
      return yt_error(t, v, "guard.density_every", "expected steps >= 0 (0: off) (got %ld)",
                      g->density_every);
  }
  if ((v = yt_get(t, n, "density_bin"))) {
    TRY(yt_double(t, v, "guard.density_bin", &g->density_bin));
    if (!(g->density_bin > 0 && isfinite(g->density_bin)))
      return yt_error(t, v, "guard.density_bin", "expected a finite bin edge > 0 in rc (got %g)",
                      g->density_bin);
    /* the bins (at least one per axis) in double: a tiny edge must not overflow their count */
    double bins = 1.0;
    for (int d = 0; d < 3; d++) {
      const double per_axis = floor((s->box_hi[d] - s->box_lo[d]) / g->density_bin);
      bins *= per_axis < 1.0 ? 1.0 : per_axis;
    }
    char why[256];
    if (mdp_size_check(bins, 2147483646.0, GUARD_BYTES_PER_BIN, "bins of the density guard", why,
                       sizeof why))
      return yt_error(t, v, "guard.density_bin",
                      "expected a bin edge whose bins over the box fit (%s) (got %g rc)", why,
                      g->density_bin);
  }
  if ((v = yt_get(t, n, "density_fraction"))) {
    TRY(yt_double(t, v, "guard.density_fraction", &g->density_fraction));
    if (!(g->density_fraction > 0 && g->density_fraction < 1))
      return yt_error(t, v, "guard.density_fraction",
                      "expected a fraction of the mean fluid density, 0 < f < 1 (got %g)",
                      g->density_fraction);
  }
  return 0;
}
