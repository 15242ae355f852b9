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
#include "populate/image_walls.h"

#include <Random123/philox.h>
#include <math.h>
#include <stdint.h>
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

static int by_voxel(const void *p, const void *q) {
  const int64_t a = *(const int64_t *)p, b = *(const int64_t *)q;
  return (a > b) - (a < b);
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
        const int64_t v = image_walls_voxel(g, w);
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

/* The class byte of global voxel v (its window entry). */
static uint8_t cls_of(const image_walls_t *g, int64_t v) {
  const int q[3] = {(int)(v % g->n[0]), (int)(v / g->n[0] % g->n[1]),
                    (int)(v / ((int64_t)g->n[0] * g->n[1]))};
  return g->cls[image_walls_win(g, q)];
}

int image_fluid_voxel(const image_walls_t *g, int64_t v, double *x, long *dropped, long *redrawn) {
  int ijk[3], full[3];
  double a[3], b[3];
  const int target =
      voxel_ijk_base(g, v, ijk, a, b, full) + ((cls_of(g, v) & IMAGE_VOXEL_EXTRA) ? 1 : 0);
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

/* The smallest k of the (key, voxel) pairs of all ranks (voxels distinct): a pair is among them iff
 * key < *cut, or key == *cut and voxel <= *tie_last. The cut is found by bisection over the 64-bit
 * keys (one MPI_Allreduce of a count per step, at most 64), the ties at it in voxel order from the
 * short list of tied voxels gathered everywhere: the same choice as sorting all pairs, without
 * holding them. Collective. 0, or -1 (memory, on every rank). */
static int select_smallest(const uint64_t *key, const int64_t *vox, long n, long long k,
                           MPI_Comm comm, uint64_t *cut, int64_t *tie_last) {
  long long total = n;
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_LONG_LONG, MPI_SUM, comm);
  if (k <= 0) {
    *cut = 0, *tie_last = -1;
    return 0;
  }
  if (k >= total) {
    *cut = UINT64_MAX, *tie_last = INT64_MAX;
    return 0;
  }
  uint64_t lo = 0, hi = UINT64_MAX; /* the smallest c with count(key <= c) >= k */
  while (lo < hi) {
    const uint64_t mid = lo + (hi - lo) / 2;
    long long c = 0;
    for (long i = 0; i < n; i++) c += key[i] <= mid;
    MPI_Allreduce(MPI_IN_PLACE, &c, 1, MPI_LONG_LONG, MPI_SUM, comm);
    if (c >= k)
      hi = mid;
    else
      lo = mid + 1;
  }
  long long below = 0;
  int ties = 0;
  for (long i = 0; i < n; i++) below += key[i] < lo, ties += key[i] == lo;
  MPI_Allreduce(MPI_IN_PLACE, &below, 1, MPI_LONG_LONG, MPI_SUM, comm);
  int size;
  MPI_Comm_size(comm, &size);
  int *counts = malloc((size_t)size * sizeof *counts),
      *displ = malloc((size_t)size * sizeof *displ);
  int64_t *mine = malloc(((size_t)ties + 1) * sizeof *mine);
  int fail = !counts || !displ || !mine;
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  if (fail) {
    free(counts), free(displ), free(mine);
    return -1;
  }
  MPI_Allgather(&ties, 1, MPI_INT, counts, 1, MPI_INT, comm);
  long long all = 0;
  for (int r = 0; r < size; r++) displ[r] = (int)all, all += counts[r];
  int64_t *tied = malloc(((size_t)all + 1) * sizeof *tied);
  fail = !tied;
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, comm);
  if (!fail) {
    ties = 0;
    for (long i = 0; i < n; i++)
      if (key[i] == lo) mine[ties++] = vox[i];
    MPI_Allgatherv(mine, ties, MPI_INT64_T, tied, counts, displ, MPI_INT64_T, comm);
    qsort(tied, (size_t)all, sizeof *tied, by_voxel);
    *cut = lo;
    *tie_last = tied[k - below - 1];
  }
  free(counts), free(displ), free(mine), free(tied);
  return fail ? -1 : 0;
}

/* Orders as the doubles it comes from (keys >= 0, -0 made +0). */
static uint64_t key_bits(double key) {
  key += 0.0;
  uint64_t b;
  memcpy(&b, &key, sizeof b);
  return b;
}

/* The key of a fluid voxel of gen in the selection of the extra particles, 0 when it takes no
 * part (a region voxel whose mean is a whole number). */
static int extra_key(const image_walls_t *g, int64_t v, uint64_t *key) {
  const scene_geometry_t *geo = &g->scene->geometry;
  if (!geo->fluid_region) {
    *key = remainder_key(g->scene->seed, v);
    return 1;
  }
  int ijk[3], full[3];
  double a[3], b[3];
  const double mean = geo->fluid_density * g->h * g->h * g->h;
  const int base = voxel_ijk_base(g, v, ijk, a, b, full);
  const double frac = mean * region_part(g, ijk, a, b, full) - base;
  if (!(frac > 0)) return 0;
  const double u =
      ((double)(remainder_key(g->scene->seed, v) >> 11) + 1) * (1.0 / 9007199254740992.0);
  *key = key_bits(-log(u) / frac);
  return 1;
}

/* Calls f on every gen voxel of class FLUID: its global index, gen index and whether it is own. */
#define FOR_GEN_FLUID(g, ...)                                                                      \
  for (int c2_ = 0; c2_ < (g)->gen_n[2]; c2_++)                                                    \
    for (int c1_ = 0; c1_ < (g)->gen_n[1]; c1_++)                                                  \
      for (int c0_ = 0; c0_ < (g)->gen_n[0]; c0_++) {                                              \
        const int lc_[3] = {c0_, c1_, c2_};                                                        \
        int q_[3];                                                                                 \
        image_walls_global((g), (g)->gen_lo, lc_, q_);                                             \
        const long long w_ = image_walls_win((g), q_);                                             \
        if (((g)->cls[w_] & IMAGE_VOXEL_CLASS) != IMAGE_VOXEL_FLUID) continue;                     \
        const int64_t v = image_walls_voxel((g), q_);                                              \
        const long long gi =                                                                       \
            c0_ + (long long)(g)->gen_n[0] * (c1_ + (long long)(g)->gen_n[1] * c2_);               \
        const int own = image_walls_in_range((g), (g)->own_lo, (g)->own_n, q_);                    \
        uint8_t *cls = &(g)->cls[w_];                                                              \
        (void)v, (void)gi, (void)own, (void)cls;                                                   \
        __VA_ARGS__                                                                                \
      }

/* geometry.fluid_region: the filled pore voxels wholly outside it become empty; the fluid target,
 * the volume and the region counts, summed over the ranks' own voxels. The volume's partial voxels
 * are summed in fixed point (2^-32 of a voxel) so that the sum, and the target rounded from it, do
 * not depend on the order of the ranks. 0 or -1 + message (the same on every rank). *extra: the
 * voxels that take one more; *candidates: the own voxels with a fractional mean. */
static int region_counts(image_walls_t *g, long long *extra, char *err, size_t errlen) {
  const scene_t *s = g->scene;
  const scene_geometry_t *geo = &s->geometry;
  image_walls_counts_t *ct = &g->count;
  const double mean = geo->fluid_density * g->h * g->h * g->h;
  const long long before = ct->fluid_voxels;
  long long sum[6] = {0, 0, 0,
                      0, 0, 0}; /* full, partial (2^-32), base, n_frac, outside, partial n */
  FOR_GEN_FLUID(g, {
    int ijk[3], full[3];
    double a[3], b[3];
    const int base = voxel_ijk_base(g, v, ijk, a, b, full);
    const double w = region_part(g, ijk, a, b, full);
    if (w <= 0) {
      *cls = IMAGE_VOXEL_EMPTY;
      sum[4] += own;
      continue;
    }
    if (!own) continue;
    if (w >= 1)
      sum[0]++;
    else
      sum[1] += llround(w * 4294967296.0), sum[5]++;
    sum[2] += base;
    sum[3] += mean * w - base > 0;
  })
  MPI_Allreduce(MPI_IN_PLACE, sum, 6, MPI_LONG_LONG, MPI_SUM, g->work);
  ct->region_outside = sum[4], ct->region_partial = sum[5];
  ct->fluid_voxels -= sum[4];
  const double volume = ((double)sum[0] + (double)sum[1] / 4294967296.0) * g->h * g->h * g->h;
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
  long long e = ct->fluid_target - sum[2];
  *extra = e < 0 ? 0 : e > sum[3] ? sum[3] : e;
  return 0;
}

int image_fluid_count(image_walls_t *g, uint16_t **kept_out, char *err, size_t errlen) {
  const scene_t *s = g->scene;
  const scene_geometry_t *geo = &s->geometry;
  image_walls_counts_t *ct = &g->count;
  const double mean = geo->fluid_density * g->h * g->h * g->h;
  *kept_out = NULL;
  g->fluid_base = (int)floor(mean);
  if (g->fluid_base + 1 > UINT16_MAX) {
    snprintf(err, errlen,
             "%s: key 'geometry.fluid_density': expected at most %d fluid particles per voxel "
             "(got a mean of %g)",
             s->file, UINT16_MAX - 1, mean);
    return -1;
  }
  long long extra;
  if (geo->fluid_region) {
    if (region_counts(g, &extra, err, errlen)) return -1;
  } else {
    const long long nf = ct->fluid_voxels;
    ct->fluid_target = lround(mean * (double)nf);
    ct->fluid_volume = (double)nf * g->h * g->h * g->h;
    extra = ct->fluid_target - (long long)g->fluid_base * nf;
    extra = extra < 0 ? 0 : extra > nf ? nf : extra;
  }
  /* the keys of the own candidates, the global selection, then the bit on every gen voxel */
  long n_own = 0;
  FOR_GEN_FLUID(g, { n_own += own; })
  uint64_t *key = malloc(((size_t)n_own + 1) * sizeof *key);
  int64_t *vox = malloc(((size_t)n_own + 1) * sizeof *vox);
  const long long G = (long long)g->gen_n[0] * g->gen_n[1] * g->gen_n[2];
  uint16_t *kept = calloc(G ? (size_t)G : 1, sizeof *kept);
  g->cache = malloc(sizeof *g->cache + 3 * ((size_t)g->fluid_base + 1) * sizeof(double));
  int fail = !key || !vox || !kept || !g->cache;
  MPI_Allreduce(MPI_IN_PLACE, &fail, 1, MPI_INT, MPI_MAX, g->work);
  uint64_t cut = 0;
  int64_t tie_last = -1;
  if (!fail) {
    image_walls_mem(g, (long long)n_own * 16 + G * 2);
    long m = 0;
    FOR_GEN_FLUID(g, {
      if (own && extra_key(g, v, &key[m])) vox[m++] = v;
    })
    fail = select_smallest(key, vox, m, extra, g->work, &cut, &tie_last);
    image_walls_mem(g, -(long long)n_own * 16);
  }
  free(key), free(vox);
  if (fail) {
    free(kept);
    snprintf(err, errlen, "%s: geometry: out of memory for %lld fluid voxels", s->file,
             ct->fluid_voxels);
    return -1;
  }
  FOR_GEN_FLUID(g, {
    uint64_t k;
    if (extra_key(g, v, &k) && (k < cut || (k == cut && v <= tie_last))) *cls |= IMAGE_VOXEL_EXTRA;
  })
  /* every gen voxel once, to know how many of its particles keep their distance from the walls */
  g->cache->voxel = -1;
  long long sums[3] = {0, 0, 0}; /* kept, dropped, redrawn of the own voxels */
  FOR_GEN_FLUID(g, {
    long dropped, redrawn;
    const int k = image_fluid_voxel(g, v, g->cache->x, &dropped, &redrawn);
    kept[gi] = (uint16_t)k;
    if (own) sums[0] += k, sums[1] += dropped, sums[2] += redrawn;
    if (own && g->label_sp && g->label_sp[w_]) g->label_particles[g->label_sp[w_] - 1] += k;
  })
  MPI_Allreduce(MPI_IN_PLACE, sums, 3, MPI_LONG_LONG, MPI_SUM, g->work);
  const int n_labels = s->geometry.n_species_labels;
  if (n_labels > 0) /* geometry.fluid_species_labels: the kept particles of each label's voxels */
    MPI_Allreduce(MPI_IN_PLACE, g->label_particles, n_labels, MPI_LONG_LONG, MPI_SUM, g->work);
  g->n_fluid = (long)sums[0];
  ct->fluid_particles = g->n_fluid;
  ct->fluid_dropped = (long)sums[1], ct->fluid_redrawn = (long)sums[2];
  *kept_out = kept;
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
