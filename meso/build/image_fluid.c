/* Fluid in the pore voxels of a geometry image (image_walls.h, docs/walls.md). The number per voxel
 * is the floor of the mean (fluid_density x voxel volume) plus one for a subset of the voxels of
 * exactly the size that makes the total round(fluid_density x filled pore volume): the voxels with
 * the smallest Philox keys of (run seed, voxel), a uniformly random subset, no lattice pattern.
 * Positions are uniform in the voxel, from a Philox stream keyed on (run seed, voxel, particle,
 * try); a position closer than min_wall_distance to a wall particle is redrawn, at most
 * IMAGE_FLUID_TRIES times, then that particle is dropped (and counted). All of it is a function of
 * the voxel index alone, so independent of the decomposition.
 *
 * With geometry.fluid_region (a box in rc) only the part of each filled pore voxel inside the box
 * gets fluid: voxel v holds the fraction w_v of its volume there (1 inside, 0 outside: those become
 * empty pore voxels), its mean is m w_v (m = fluid_density x voxel volume), it gets floor(m w_v)
 * plus one more for exactly round(fluid_density x sum_v w_v voxel volume) - sum_v floor(m w_v)
 * voxels, drawn with probabilities proportional to frac(m w_v) (the smallest keys -ln(u_v) /
 * frac(m w_v), u_v the same Philox number as above: Efraimidis & Spirakis' weighted sampling
 * without replacement), and its positions are uniform in the voxel's part inside the box. */
#include "build/image_walls.h"

#include <Random123/philox.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the fourth Philox counter word of each stream (the fill and velocity streams use 0x6d64706f) */
enum { TAG_FLUID = 0x666c7569, TAG_REMAINDER = 0x72656d64 };

static philox4x32_ctr_t draw(uint64_t seed, int64_t voxel, uint32_t word, uint32_t tag) {
  const uint64_t v = (uint64_t)voxel;
  philox4x32_ctr_t ctr = {{(uint32_t)v, (uint32_t)(v >> 32), word, tag}};
  philox4x32_key_t key = {{(uint32_t)seed, (uint32_t)(seed >> 32)}};
  return philox4x32(ctr, key);
}

static uint64_t remainder_key(uint64_t seed, int64_t voxel) {
  const philox4x32_ctr_t r = draw(seed, voxel, 0, TAG_REMAINDER);
  return (uint64_t)r.v[0] | (uint64_t)r.v[1] << 32;
}

/* The k-th smallest (0-based) of a[0..n-1] (reorders a): Hoare quickselect, median of three. */
static uint64_t select_kth(uint64_t *a, long n, long k) {
  long lo = 0, hi = n - 1;
  while (lo < hi) {
    uint64_t x = a[lo], y = a[lo + (hi - lo) / 2], z = a[hi], t;
    if (x > y) t = x, x = y, y = t;
    if (y > z) y = z;
    const uint64_t pivot = x > y ? x : y; /* median of the three */
    long i = lo, j = hi;
    while (i <= j) {
      while (a[i] < pivot) i++;
      while (a[j] > pivot) j--;
      if (i <= j) {
        t = a[i], a[i] = a[j], a[j] = t;
        i++, j--;
      }
    }
    if (k <= j)
      hi = j;
    else if (k >= i)
      lo = i;
    else
      return a[k];
  }
  return a[k];
}

/* 1 when x is at least min_wall_distance from every wall particle (voxel (i, j, k) holds x; the
 * voxels within reach are scanned, periodic images along periodic axes). */
static int clear_of_walls(const image_walls_t *g, const int ijk[3], const double x[3]) {
  const double md = g->min_distance, md2 = md * md, h = g->h;
  if (md <= 0) return 1;
  const int r = (int)ceil(md / h);
  for (int dz = -r; dz <= r; dz++)
    for (int dy = -r; dy <= r; dy++)
      for (int dx = -r; dx <= r; dx++) {
        const int q[3] = {ijk[0] + dx, ijk[1] + dy, ijk[2] + dz};
        int w[3], inside = 1;
        double shift[3], gap2 = 0;
        for (int d = 0; d < 3 && inside; d++) {
          w[d] = q[d];
          if (q[d] < 0 || q[d] >= g->n[d]) {
            if (!g->periodic[d]) inside = 0;
            w[d] = ((q[d] % g->n[d]) + g->n[d]) % g->n[d];
          }
          shift[d] = (double)(q[d] - w[d]) * h;
          const double lo = g->lo[d] + q[d] * h, gap = x[d] < lo ? lo - x[d] : x[d] - (lo + h);
          if (gap > 0) gap2 += gap * gap;
        }
        if (!inside || gap2 >= md2) continue;
        const int64_t v =
            (int64_t)w[0] + (int64_t)g->n[0] * ((int64_t)w[1] + (int64_t)g->n[1] * w[2]);
        const long n = image_walls_voxel_count(g, v);
        for (long j = 0; j < n; j++) {
          double y[3], r2 = 0;
          image_walls_voxel_particle(g, v, j, y);
          for (int d = 0; d < 3; d++) r2 += (y[d] + shift[d] - x[d]) * (y[d] + shift[d] - x[d]);
          if (r2 < md2) return 0;
        }
      }
  return 1;
}

/* The part of voxel ijk inside geometry.fluid_region: [a[d], b[d]) per axis (full[d] = 1 where
 * the voxel lies wholly inside along d) and the fraction of the voxel's volume it holds (exactly 1
 * or 0 for voxels wholly inside or outside). Without a region: the whole voxel, 1. */
static double region_part(const image_walls_t *g, const int ijk[3], double a[3], double b[3],
                          int full[3]) {
  const scene_geometry_t *geo = &g->scene->geometry;
  double w = 1;
  for (int d = 0; d < 3; d++) {
    const double lo = g->lo[d] + ijk[d] * g->h, hi = g->lo[d] + (ijk[d] + 1) * g->h;
    full[d] = !geo->fluid_region || (geo->fluid_lo[d] <= lo && hi <= geo->fluid_hi[d]);
    a[d] = full[d] ? lo : fmax(lo, geo->fluid_lo[d]);
    b[d] = full[d] ? hi : fmin(hi, geo->fluid_hi[d]);
    if (!full[d]) w *= b[d] > a[d] ? (b[d] - a[d]) / g->h : 0;
  }
  return w;
}

static int voxel_ijk_base(const image_walls_t *g, int64_t v, int ijk[3], double a[3], double b[3],
                          int full[3]) {
  ijk[0] = (int)(v % g->n[0]);
  ijk[1] = (int)(v / g->n[0] % g->n[1]);
  ijk[2] = (int)(v / ((int64_t)g->n[0] * g->n[1]));
  const double w = region_part(g, ijk, a, b, full);
  if (w == 1) return g->fluid_base;
  const double mean = g->scene->geometry.fluid_density * g->h * g->h * g->h;
  return (int)floor(mean * w);
}

int image_fluid_voxel(const image_walls_t *g, int64_t v, double *x, long *dropped, long *redrawn) {
  int ijk[3], full[3];
  double a[3], b[3];
  const int target =
      voxel_ijk_base(g, v, ijk, a, b, full) + ((g->cls[v] & IMAGE_VOXEL_EXTRA) ? 1 : 0);
  const uint64_t seed = g->scene->seed;
  int n = 0;
  long tries = 0;
  *dropped = 0;
  for (int k = 0; k < target; k++) {
    int placed = 0;
    for (int t = 0; t < IMAGE_FLUID_TRIES && !placed; t++, tries++) {
      const philox4x32_ctr_t r =
          draw(seed, v, (uint32_t)k * IMAGE_FLUID_TRIES + (uint32_t)t, TAG_FLUID);
      double p[3];
      for (int d = 0; d < 3; d++) {
        const double u = ((double)r.v[d] + 0.5) * (1.0 / 4294967296.0);
        p[d] = full[d] ? g->lo[d] + (ijk[d] + u) * g->h : a[d] + u * (b[d] - a[d]);
      }
      if (!clear_of_walls(g, ijk, p)) continue;
      memcpy(x + 3 * n++, p, sizeof p);
      placed = 1;
    }
    *dropped += !placed;
  }
  if (redrawn) *redrawn = tries - target;
  return n;
}

struct image_walls_cache {
  long voxel; /* position in fluid_vox of the voxel held, -1 none */
  double x[]; /* [3 * (fluid_base + 1)] */
};

typedef struct {
  double key;
  long f;
} weighted_key_t;

static int by_key(const void *p, const void *q) {
  const weighted_key_t *a = p, *b = q;
  return a->key < b->key ? -1 : a->key > b->key ? 1 : (a->f > b->f) - (a->f < b->f);
}

/* geometry.fluid_region: the filled pore voxels wholly outside it become empty, the others get
 * floor(m w_v) particles and the IMAGE_VOXEL_EXTRA bit as described at the top; fills the fluid
 * target, the volume and the region counts. 0 or -1 + message. */
static int region_counts(image_walls_t *g, char *err, size_t errlen) {
  const scene_t *s = g->scene;
  const scene_geometry_t *geo = &s->geometry;
  image_walls_counts_t *ct = &g->count;
  const double mean = geo->fluid_density * g->h * g->h * g->h;
  const long long before = ct->fluid_voxels;
  double volume = 0;
  long base_sum = 0, n_frac = 0;
  ct->region_outside = ct->region_partial = 0;
  for (int64_t v = 0; v < (int64_t)ct->voxels; v++) {
    if ((g->cls[v] & IMAGE_VOXEL_CLASS) != IMAGE_VOXEL_FLUID) continue;
    int ijk[3], full[3];
    double a[3], b[3];
    const int base = voxel_ijk_base(g, v, ijk, a, b, full);
    const double w = region_part(g, ijk, a, b, full);
    if (w <= 0) {
      g->cls[v] = IMAGE_VOXEL_EMPTY;
      ct->fluid_voxels--, ct->region_outside++;
      continue;
    }
    ct->region_partial += w < 1;
    volume += w * g->h * g->h * g->h;
    base_sum += base;
    n_frac += mean * w - base > 0;
  }
  ct->fluid_volume = volume;
  if (ct->fluid_voxels == 0) {
    snprintf(err, errlen,
             "%s: key 'geometry.fluid_region': expected a region that holds some of the %lld "
             "filled pore voxels (got [%g, %g] x [%g, %g] x [%g, %g] rc, none of them)",
             s->file, before, geo->fluid_lo[0], geo->fluid_hi[0], geo->fluid_lo[1],
             geo->fluid_hi[1], geo->fluid_lo[2], geo->fluid_hi[2]);
    return -1;
  }
  ct->fluid_target = lround(geo->fluid_density * volume);
  long extra = ct->fluid_target - base_sum;
  extra = extra < 0 ? 0 : extra > n_frac ? n_frac : extra;
  weighted_key_t *key = n_frac ? malloc((size_t)n_frac * sizeof *key) : NULL;
  if (n_frac && !key) {
    snprintf(err, errlen, "%s: geometry: out of memory for %ld fluid voxels", s->file, n_frac);
    return -1;
  }
  long k = 0;
  for (int64_t v = 0; v < (int64_t)ct->voxels; v++) {
    if ((g->cls[v] & IMAGE_VOXEL_CLASS) != IMAGE_VOXEL_FLUID) continue;
    int ijk[3], full[3];
    double a[3], b[3];
    const int base = voxel_ijk_base(g, v, ijk, a, b, full);
    const double frac = mean * region_part(g, ijk, a, b, full) - base;
    if (!(frac > 0)) continue;
    const double u = ((double)(remainder_key(s->seed, v) >> 11) + 1) * (1.0 / 9007199254740992.0);
    key[k].key = -log(u) / frac;
    key[k++].f = (long)v;
  }
  qsort(key, (size_t)n_frac, sizeof *key, by_key);
  for (k = 0; k < extra; k++) g->cls[key[k].f] |= IMAGE_VOXEL_EXTRA;
  free(key);
  return 0;
}

int image_fluid_count(image_walls_t *g, char *err, size_t errlen) {
  const scene_t *s = g->scene;
  const scene_geometry_t *geo = &s->geometry;
  image_walls_counts_t *ct = &g->count;
  const double mean = geo->fluid_density * g->h * g->h * g->h;
  g->fluid_base = (int)floor(mean);
  if (geo->fluid_region && region_counts(g, err, errlen)) return -1;
  const long nf = (long)ct->fluid_voxels;
  if (!geo->fluid_region) {
    ct->fluid_target = lround(mean * (double)nf);
    ct->fluid_volume = (double)nf * g->h * g->h * g->h;
  }
  long extra = geo->fluid_region ? 0 : ct->fluid_target - (long)g->fluid_base * nf;
  extra = extra < 0 ? 0 : extra > nf ? nf : extra;
  g->n_fluid_vox = nf;
  g->fluid_vox = malloc(((size_t)nf + 1) * sizeof *g->fluid_vox);
  g->fluid_start = malloc(((size_t)nf + 1) * sizeof *g->fluid_start);
  g->cache = malloc(sizeof *g->cache + 3 * ((size_t)g->fluid_base + 1) * sizeof(double));
  uint64_t *key = extra > 0 && extra < nf ? malloc(2 * (size_t)nf * sizeof *key) : NULL;
  if (!g->fluid_vox || !g->fluid_start || !g->cache || (extra > 0 && extra < nf && !key)) {
    free(key);
    snprintf(err, errlen, "%s: geometry: out of memory for %ld fluid voxels", s->file, nf);
    return -1;
  }
  g->cache->voxel = -1;
  long f = 0;
  for (int64_t v = 0; v < (int64_t)ct->voxels; v++)
    if ((g->cls[v] & IMAGE_VOXEL_CLASS) == IMAGE_VOXEL_FLUID) g->fluid_vox[f++] = v;
  /* the `extra` voxels with the smallest keys take one particle more (ties: voxel order) */
  if (key) {
    for (f = 0; f < nf; f++) key[f] = key[nf + f] = remainder_key(s->seed, g->fluid_vox[f]);
    const uint64_t cut = select_kth(key + nf, nf, extra - 1);
    long below = 0;
    for (f = 0; f < nf; f++) below += key[f] < cut;
    long at = extra - below;
    for (f = 0; f < nf; f++)
      if (key[f] < cut || (key[f] == cut && at-- > 0)) g->cls[g->fluid_vox[f]] |= IMAGE_VOXEL_EXTRA;
    free(key);
  } else if (extra == nf) {
    for (f = 0; f < nf; f++) g->cls[g->fluid_vox[f]] |= IMAGE_VOXEL_EXTRA;
  }
  /* every voxel once, to know how many of its particles keep their distance from the walls */
  g->n_fluid = 0;
  ct->fluid_dropped = ct->fluid_redrawn = 0;
  for (f = 0; f < nf; f++) {
    long dropped, redrawn;
    g->fluid_start[f] = g->n_fluid;
    g->n_fluid += image_fluid_voxel(g, g->fluid_vox[f], g->cache->x, &dropped, &redrawn);
    ct->fluid_dropped += dropped;
    ct->fluid_redrawn += redrawn;
  }
  g->fluid_start[nf] = g->n_fluid;
  ct->fluid_particles = g->n_fluid;
  return 0;
}

void image_fluid_particle(const image_walls_t *g, long i, double x[3]) {
  image_walls_cache_t *c = g->cache;
  long f = c->voxel;
  if (f < 0 || i < g->fluid_start[f] || i >= g->fluid_start[f + 1]) {
    f = image_walls_find(g->fluid_start, g->n_fluid_vox, i);
    long dropped;
    image_fluid_voxel(g, g->fluid_vox[f], c->x, &dropped, NULL);
    c->voxel = f;
  }
  memcpy(x, c->x + 3 * (i - g->fluid_start[f]), 3 * sizeof(double));
}
