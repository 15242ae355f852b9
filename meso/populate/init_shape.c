/* Shaped fill regions (docs/twophase.md): a fill region with a `cylinder` or a `sphere` keeps only
 * the candidate sites of its axis-aligned region (lattice sites or random draws, exactly those of
 * the unshaped fill) that lie inside the shape, or outside it with `outside: true`. Two fills of
 * the same region, one inside and one outside, make a drop or a thread of one liquid in another.
 * The distance is the plain one in the box frame (no periodic image): keep the shape inside the
 * region. The same test assigns a species to the geometry builder's fluid particles
 * (geometry.fluid_species_regions, image_walls.c). */
#include "populate/init_config.h"

#include <stdlib.h>

int init_shape_keeps(const scene_fill_t *f, const double x[3]) {
  if (f->shape == FILL_SHAPE_NONE) return 1;
  double r2 = 0;
  for (int d = 0; d < 3; d++) {
    if (f->shape == FILL_SHAPE_CYLINDER && d == f->shape_axis) continue;
    r2 += (x[d] - f->centre[d]) * (x[d] - f->centre[d]);
  }
  const int inside = r2 < f->radius * f->radius;
  return f->outside ? !inside : inside;
}

long init_fill_kept(const scene_t *s, int k, long *kept) {
  const long n = init_fill_candidates(s, k);
  long m = 0;
  for (long i = 0; i < n; i++) {
    double x[3];
    init_fill_position(s, k, i, x);
    if (!init_shape_keeps(&s->init.fill[k], x)) continue;
    if (kept) kept[m] = i;
    m++;
  }
  return m;
}

long *init_fill_kept_list(const scene_t *s, int k) {
  const long m = init_fill_kept(s, k, NULL);
  long *kept = malloc((size_t)(m > 0 ? m : 1) * sizeof *kept);
  if (kept) init_fill_kept(s, k, kept);
  return kept;
}
