/* Fill regions of the box with one species at a number density, on a cubic lattice or at random.
 * Global ids run 1, 2, ... over the regions in scene order; random positions come from a Philox
 * stream keyed on (seed, region, index), so every rank generates the same particles. */
#include "populate/init_config.h"
#include "populate/init_random.h"

#include <math.h>

/* Lattice: n_d = max(1, round(L_d rho^(1/3))) sites per axis at the centres of equal cells, so the
 * region is filled edge to edge without overlap with a neighbouring region; the realised density is
 * prod(n_d) / V (within a few % of the request for regions a few spacings wide). */
static void lattice_dims(const scene_fill_t *f, long n[3]) {
  const double a = cbrt(f->density);
  for (int d = 0; d < 3; d++) {
    n[d] = lround((f->hi[d] - f->lo[d]) * a);
    if (n[d] < 1) n[d] = 1;
  }
}

long init_fill_count(const scene_t *s, int k) {
  if (s->init.fill[k].shape != FILL_SHAPE_NONE) return init_fill_kept(s, k, NULL);
  return init_fill_candidates(s, k);
}

long init_fill_candidates(const scene_t *s, int k) {
  const scene_fill_t *f = &s->init.fill[k];
  if (f->mode == FILL_LATTICE) {
    long n[3];
    lattice_dims(f, n);
    return n[0] * n[1] * n[2];
  }
  const double vol = (f->hi[0] - f->lo[0]) * (f->hi[1] - f->lo[1]) * (f->hi[2] - f->lo[2]);
  return llround(f->density * vol);
}

void init_fill_position(const scene_t *s, int k, long i, double x[3]) {
  const scene_fill_t *f = &s->init.fill[k];
  if (f->mode == FILL_LATTICE) {
    long n[3];
    lattice_dims(f, n);
    const long c[3] = {i % n[0], (i / n[0]) % n[1], i / (n[0] * n[1])};
    for (int d = 0; d < 3; d++) x[d] = f->lo[d] + (c[d] + 0.5) * (f->hi[d] - f->lo[d]) / n[d];
    return;
  }
  double u[4];
  init_uniform4(s->seed, INIT_STREAM_POSITION + 16u * (uint32_t)k, (uint64_t)i, u);
  for (int d = 0; d < 3; d++) x[d] = f->lo[d] + u[d] * (f->hi[d] - f->lo[d]);
}

void init_mb_velocity(const scene_t *s, int64_t id, int species, double kT, double v[3]) {
  if (s->species[species].frozen || kT <= 0) {
    v[0] = v[1] = v[2] = 0;
    return;
  }
  double g[3];
  init_normal3(s->seed, INIT_STREAM_VELOCITY, (uint64_t)id, g);
  const double sd = sqrt(kT / s->species[species].mass);
  for (int d = 0; d < 3; d++) v[d] = sd * g[d];
}
