/* Device density pass of many-body DPD (Warren 2003): rho_i = sum_{j != i, r < rd} w_rho(r), the
 * Warren or Lucy kernel of meso/physics/density_kernels.h, self term excluded (physics.md 1). One
 * thread per particle; with one rank there are no ghosts, so no rho sync is needed.
 * The same bin scan writes each particle's neighbour list (partners within the largest cutoff, in
 * traversal order) for the force pass: the force kernel then runs only over partners in range, so a
 * warp does not pay the pair body for the ~85% of bin candidates that are out of range. With a
 * Verlet skin (one GPU) the lists hold the partners within the cutoff plus the skin and serve
 * several steps: between builds the densities come from the lists (k_density_list).
 * Density cache (plan.density_cache, one rank): a static frozen particle's density is its
 * static-static part, summed once (in fixed point, so independent of the traversal order) and kept
 * by particle id, plus its mobile and moving partners' part; its list holds only those partners (no
 * pass reads a frozen particle's list otherwise), and when none of the bins around it holds a mobile
 * or moving particle it does no scan at all. The static tail (one rank, cuda_cells.cu) does the
 * same without the cache's table and per-candidate test: a tail particle's part from the tail is
 * summed once per placement of the tail (k_tail_static, by slot), and its thread of the density
 * pass scans only the slots before the tail. */
#include "cuda_neighbours.cuh"
#include "physics/density_kernels.h"

#include <stdio.h>

/* The term of a partner at squared distance r2 in rho_i: the kernel's weight when r2 is within the
 * pair's rd2, else 0, without a branch. r = r2 rsqrt(r2) (no sqrt slow path; r2 = 0 gives r = 0):
 * within a few float ulps of sqrt; the bin scan, the list pass and the static part all use it. */
template <int KERNEL>
__device__ __forceinline__ meso_real dev_w_rho(const struct dev_coef &c, meso_real r2) {
  const meso_real r = r2 * dev_rsqrt_normal(fmax(r2, MESO_R(1e-30)));
  const meso_real w = KERNEL == MESO_KERNEL_LUCY ? w_rho_lucy_inv(r, c.inv_rd, c.wnorm)
                                                 : w_rho_warren_inv(r, c.inv_rd, c.wnorm);
  return r2 < c.rd2 ? w : MESO_R(0.0);
}

/* The density cache's arguments of the passes (NULL table: off). */
struct density_cache_args {
  meso_real *table; /* [len] static part by id, NaN until computed */
  long long len;
  const int64_t *id;       /* [n] ids of the owned slots */
  const int *cell_dynamic; /* [ncell] 1: the bin holds a mobile or moving particle */
};

/* The static part in fixed point: units of 2^-32 (each term rounded once; the order of the terms
 * does not change the sum, so a restart rebuilds the value bitwise). */
#define STATIC_FIXED_SCALE 4294967296.0

/* Mode of slot i under the cache: 0 not cached, 1 cached (value in *cached), 2 not computed yet
 * (never seen by the passes: k_static_part fills the table before the first build). */
__device__ __forceinline__ int cache_mode(const struct dev_params &q,
                                          const struct density_cache_args &dc, int species, int i,
                                          meso_real *cached, long long *id) {
  if (!dc.table || !q.static_frozen[species]) return 0;
  *id = dc.id[i];
  if (*id < 0 || *id >= dc.len) return 0;
  *cached = dc.table[*id];
  return isnan(*cached) ? 2 : 1;
}

/* Whether any (fine) bin around bin ci holds a mobile or moving particle (one rank: no ghosts). */
__device__ __forceinline__ int any_dynamic_near(const struct dev_params &q,
                                                const int *__restrict__ cell_dynamic, uint32_t ci) {
  const int h[3] = {(int)ci % q.nf[0], ((int)ci / q.nf[0]) % q.nf[1],
                    (int)ci / (q.nf[0] * q.nf[1])};
  const int b[3] = {h[0] / q.sub[0], h[1] / q.sub[1], h[2] / q.sub[2]};
  const int r[3] = {h[0] - b[0] * q.sub[0], h[1] - b[1] * q.sub[1], h[2] - b[2] * q.sub[2]};
  int co;
  for (int oz = dev_fine_lo(q, 2); oz <= dev_fine_hi(q, 2); oz++) {
    const int fz = dev_fine_bin(q, 2, b[2], r[2], oz, &co);
    if (fz < 0) continue;
    for (int oy = dev_fine_lo(q, 1); oy <= dev_fine_hi(q, 1); oy++) {
      const int fy = dev_fine_bin(q, 1, b[1], r[1], oy, &co);
      if (fy < 0) continue;
      for (int ox = dev_fine_lo(q, 0); ox <= dev_fine_hi(q, 0); ox++) {
        const int fx = dev_fine_bin(q, 0, b[0], r[0], ox, &co);
        if (fx >= 0 && cell_dynamic[fx + q.nf[0] * (fy + q.nf[1] * fz)]) return 1;
      }
    }
  }
  return 0;
}

__global__ void k_cell_dynamic(const struct dev_params q, int n, const struct dev_pos *pos,
                               const uint32_t *__restrict__ key, int *cell_dynamic) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < n && !q.static_frozen[pos[t].species]) cell_dynamic[key[t]] = 1;
}

__global__ void k_max_id(int n, const int64_t *__restrict__ id, unsigned long long *out) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n && id[i] >= 0) atomicMax(out, (unsigned long long)id[i]);
}

/* Once, before the first build: the static part of every owned static frozen particle (its static
 * partners within rd, fixed point) into the table. */
template <int KERNEL>
__global__ void __launch_bounds__(CUDA_BLOCK)
    k_static_part(const struct dev_params q, int n, const int *__restrict__ start,
                  const struct dev_pos *__restrict__ pos, const uint32_t *__restrict__ key,
                  const struct density_cache_args dc) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const struct dev_pos pi = pos[i];
  if (!q.static_frozen[pi.species]) return;
  const long long id_i = dc.id[i];
  if (id_i < 0 || id_i >= dc.len) return;
  const struct dev_coef *row = q.coef[pi.species];
  long long fixed = 0;
  dev_for_each_neighbour(
      q, start, NULL, n, pos, pi, key[i],
      [&](int t, int code, const struct dev_pos &pj, meso_real dx, meso_real dy, meso_real dz) {
        (void)code;
        if (t == i || !q.static_frozen[pj.species]) return;
        const meso_real r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= row[pj.species].rd2) return;
        fixed += llrint((double)dev_w_rho<KERNEL>(row[pj.species], r2) * STATIC_FIXED_SCALE);
      },
      q.scan_rd2);
  dc.table[id_i] = (meso_real)((double)fixed / STATIC_FIXED_SCALE);
}

/* The static tail's own density part: for each tail slot i (from tail_from), the sum over its tail
 * partners within rd, in the scan's order (once per placement of the tail; no mobile or moving
 * particle is among them, so it stays valid while the tail stays). */
template <int KERNEL>
__global__ void __launch_bounds__(CUDA_BLOCK)
    k_tail_static(const struct dev_params q, int tail_from, int n, const int *__restrict__ start,
                  const struct dev_pos *__restrict__ pos, const uint32_t *__restrict__ key,
                  meso_real *__restrict__ tail_rho) {
  const int i = tail_from + blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const struct dev_pos pi = pos[i];
  const struct dev_coef *row = q.coef[pi.species];
  meso_real sum = MESO_R(0.0);
  dev_for_each_neighbour(
      q, start, NULL, n, pos, pi, key[i],
      [&](int t, int code, const struct dev_pos &pj, meso_real dx, meso_real dy, meso_real dz) {
        (void)code;
        const meso_real r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= q.rd2_max || t == i) return;
        sum += dev_w_rho<KERNEL>(row[pj.species], r2);
      },
      q.scan_rd2, 2);
  tail_rho[i - tail_from] = sum;
}

/* Threads per block of the scan with lists: 64 (porous 72 2300/2302 -> 2333/2335, bulk 118 1421 ->
 * 1440, the scan on porous 33 611 -> 595 us; 256: 2253/2255; bench/RESULTS.md, 2026-11-27
 * 94ed3e8). The compact mode's scan keeps CUDA_BLOCK (64 everywhere made it 4% slower there). */
#ifndef CUDA_SCAN_BLOCK
#define CUDA_SCAN_BLOCK 64
#endif
#define DENSITY_BLOCK(LISTS) ((LISTS) ? CUDA_SCAN_BLOCK : CUDA_BLOCK)

/* LISTS 0: the compact memory mode (no lists; the force pass scans the bins again). */
template <int KERNEL, int DENSITY, int CACHE, int LISTS>
__global__ void __launch_bounds__(DENSITY_BLOCK(LISTS))
    k_density(const struct dev_params q, int n, int cap, int stride, const int *__restrict__ start,
              const int *__restrict__ gstart, const struct dev_pos *__restrict__ pos,
              const uint32_t *__restrict__ key, meso_real *__restrict__ rho,
              uint32_t *__restrict__ nbr, int *__restrict__ count, int *most,
              const uint32_t *__restrict__ part, uint32_t part_flag, struct dev_vel *vel,
              const struct density_cache_args dc, const int *__restrict__ slots, int n_slots,
              const meso_real *__restrict__ tail_rho, int tail_from) {
  /* Each thread gathers NBR_CHUNK entries in its own shared-memory slots (padded: no bank
   * conflicts), then stores them as one chunk (no barrier: no thread reads another's slots). */
  __shared__ uint32_t chunk_buf[DENSITY_BLOCK(LISTS) * (NBR_CHUNK + 1)];
  uint32_t *mine = chunk_buf + threadIdx.x * (NBR_CHUNK + 1);
  /* slots (the boundary part of several ranks, or one rank's mobile-then-frozen partition): thread
   * t_id computes slot slots[t_id] */
  const int t_id = blockIdx.x * blockDim.x + threadIdx.x;
  if (t_id >= (slots ? n_slots : n)) return;
  const int i = slots ? slots[t_id] : t_id;
  if (part && part[i] != part_flag) return;
  const auto flush = [&](int c) {
    uint4 *dst = (uint4 *)(nbr + nbr_index(i, c * NBR_CHUNK, cap));
    dst[0] = make_uint4(mine[0], mine[1], mine[2], mine[3]);
    dst[1] = make_uint4(mine[4], mine[5], mine[6], mine[7]);
  };
  const struct dev_pos pi = pos[i];
  const struct dev_coef *row = q.coef[pi.species];
  meso_real sum = MESO_R(0.0), cached = MESO_R(0.0);
  long long id_i = 0;
  /* the table is complete before any build (k_static_part): mode 0 or 1 here */
  const int mode = CACHE ? cache_mode(q, dc, pi.species, i, &cached, &id_i) : 0;
  if (CACHE && mode == 1 && !any_dynamic_near(q, dc.cell_dynamic, key[i])) {
    rho[i] = cached; /* a wall particle with no mobile neighbour: nothing to scan */
    if (vel) vel[i].pad = cached;
    if (LISTS) count[i] = 0;
    return;
  }
  /* A frozen particle's list is read by no pass when lists are rebuilt every step (the force and
   * wall-field passes run over the mobile particles' lists): it keeps none, and its scan (as every
   * scan of the compact mode) reaches only the density cutoff. */
  const int list_me = LISTS && (q.mobile[pi.species] || q.skin > 0.0);
  if (!list_me && !DENSITY) {
    if (LISTS) count[i] = 0;
    return;
  }
  const meso_real keep2 = list_me ? q.list_cut2 : q.rd2_max;
  const meso_real trim2 = list_me ? q.scan_cut2 : q.scan_rd2;
  /* a static tail particle (tail_rho: one rank, the static tail): its tail partners' part was
   * summed once (k_tail_static); only the other slots are scanned */
  const int tail_me = DENSITY && tail_rho && i >= tail_from && !list_me;
  if (tail_me) sum = tail_rho[i - tail_from];
  int m = 0;
  dev_for_each_neighbour(
      q, start, gstart, n, pos, pi, key[i],
      [&](int t, int code, const struct dev_pos &pj, meso_real dx, meso_real dy, meso_real dz) {
        const meso_real r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= keep2 || t == i) return;                             /* most candidates */
        if (CACHE && mode == 1 && q.static_frozen[pj.species]) return; /* in the cached part */
        if (list_me && m < stride) {
          /* (m >= 0: a mask and a shift, not the signed % and /) */
          mine[m & (NBR_CHUNK - 1)] = (uint32_t)t | ((uint32_t)code << NBR_SLOT_BITS);
          if ((m & (NBR_CHUNK - 1)) == NBR_CHUNK - 1) flush(m >> 3);
        }
        m++;
        if (!DENSITY || r2 >= q.rd2_max) return;
        sum += dev_w_rho<KERNEL>(row[pj.species], r2);
      },
      trim2, tail_me ? 1 : 3);
  if (CACHE && mode == 1) sum = cached + sum;
  if (DENSITY) rho[i] = sum;
  if (DENSITY && vel) vel[i].pad = sum; /* one rank: the force pass reads it there */
  if (!LISTS) return;
  if (!list_me) {
    count[i] = 0;
    return;
  }
  const int kept = m < stride ? m : stride;
  if (kept % NBR_CHUNK) flush(kept / NBR_CHUNK); /* the last, partial chunk */
  count[i] = m;
  if (m > stride) atomicMax(most, m);
}

/* With the thermostat the density passes also store rho in vel.pad, where the force pass reads
 * a partner's density (several ranks: the owned slots here, the ghosts' once their densities
 * have arrived, cuda_rho_to_vel). */
static struct dev_vel *rho_vel(struct cuda_sim *g) {
  return !(g->prm.terms & PAIR_TERM_THERMOSTAT) ? NULL : g->vel;
}

/* The cache's arguments, table off (NULL) when the cache is not in use. */
static struct density_cache_args cache_args(const struct cuda_sim *g) {
  struct density_cache_args dc = {NULL, 0, NULL, NULL};
  if (g->rho_static && g->prm.density_cache) {
    dc.table = g->rho_static;
    dc.len = g->rho_static_len;
    dc.id = g->a.id;
    dc.cell_dynamic = g->cell_dynamic;
  }
  return dc;
}

/* Before a build: the table (first use: NaN for every id up to the largest; off when ids are much
 * sparser than the particles, or with several ranks) and this build's bin flags. 0 or -1. */
static int cache_prepare(struct cuda_sim *g) {
  if (!g->prm.density_cache || !g->prm.density || g->prm.multi || g->n == 0) return 0;
  const int blocks = (g->n + CUDA_BLOCK - 1) / CUDA_BLOCK;
  if (!g->rho_static) {
    unsigned long long *d_max = NULL, max_id = 0;
    if (cuda_alloc(g, (void **)&d_max, sizeof *d_max) ||
        cuda_check(cudaMemset(d_max, 0, sizeof *d_max), "density cache"))
      return -1;
    k_max_id<<<blocks, CUDA_BLOCK>>>(g->n, g->a.id, d_max);
    const int rc = cuda_check(cudaMemcpy(&max_id, d_max, sizeof max_id, cudaMemcpyDeviceToHost),
                              "density cache");
    cuda_free_ptr(g, (void **)&d_max);
    if (rc) return -1;
    const long long len = (long long)max_id + 1;
    if (len > 8LL * g->n + (1LL << 20)) { /* sparse ids: a table by id would waste memory */
      g->prm.density_cache = 0;
      return 0;
    }
    if (cuda_alloc(g, (void **)&g->rho_static, (size_t)len * sizeof(meso_real)) ||
        cuda_alloc(g, (void **)&g->cell_dynamic, (size_t)g->prm.ncell * sizeof(int)) ||
        cuda_check(cudaMemset(g->rho_static, 0xff, (size_t)len * sizeof(meso_real)), /* NaN */
                   "density cache"))
      return -1;
    g->rho_static_len = len;
    struct density_cache_args dc = cache_args(g);
    if (g->prm.kernel == MESO_KERNEL_LUCY)
      k_static_part<MESO_KERNEL_LUCY>
          <<<blocks, CUDA_BLOCK>>>(g->prm, g->n, g->cell_start, g->pos, g->key_sorted, dc);
    else
      k_static_part<MESO_KERNEL_WARREN>
          <<<blocks, CUDA_BLOCK>>>(g->prm, g->n, g->cell_start, g->pos, g->key_sorted, dc);
  }
  if (cuda_check(cudaMemsetAsync(g->cell_dynamic, 0, (size_t)g->prm.ncell * sizeof(int)),
                 "density cache"))
    return -1;
  k_cell_dynamic<<<blocks, CUDA_BLOCK>>>(g->prm, g->n, g->pos, g->key_sorted, g->cell_dynamic);
  return 0;
}

/* One rank with lists and frozen particles: the whole pass over the partition of the slots, the
 * mobile ones first (cuda_mobile_partition, which the force pass uses again), so that a warp holds
 * either fluid particles (lists to the largest cutoff) or wall particles (densities to rd, often
 * from the cache alone), not both. */
static const int *partitioned_slots(struct cuda_sim *g, int part) {
  if (part >= 0 || g->compact || g->prm.multi || !g->mobile_slots_on || g->n == 0) return NULL;
  return cuda_mobile_partition(g) ? NULL : g->mobile_slot;
}

/* The static tail's own density part, once per placement (k_tail_static); the tail's threads of
 * the density pass start from it. NULL: no tail (or no room: the whole scan, as without it). */
template <int KERNEL> static const meso_real *tail_static(struct cuda_sim *g) {
  if (!g->prm.tail || !g->tail_rho_on) return NULL; /* (the compact mode has no tail) */
  const int n_tail = g->n - g->n_dyn;
  if (n_tail <= 0) return NULL;
  if (!g->tail_rho_ready) {
    if (cuda_dev_room(g, (char **)&g->tail_rho, &g->tail_rho_bytes,
                      (size_t)n_tail * sizeof(meso_real)))
      return NULL;
    k_tail_static<KERNEL><<<(n_tail + CUDA_BLOCK - 1) / CUDA_BLOCK, CUDA_BLOCK>>>(
        g->prm, g->n_dyn, g->n, g->cell_start, g->pos, g->key_sorted, g->tail_rho);
    g->tail_rho_ready = 1;
  }
  return g->tail_rho;
}

template <int KERNEL, int DENSITY, int CACHE> static void launch(struct cuda_sim *g, int part) {
  /* the boundary part over its slot list when the ghost selection made one (cuda_halo_device.cu),
   * else over every slot, the others leaving at once */
  const int *slots = part == 0 ? g->boundary_slots : partitioned_slots(g, part);
  const meso_real *tail_rho = DENSITY && part < 0 ? tail_static<KERNEL>(g) : NULL;
  const int threads = part == 0 && slots ? g->n_bslots : g->n;
  if (slots && threads == 0) return;
  if (g->compact) {
    const int blocks = (threads + DENSITY_BLOCK(0) - 1) / DENSITY_BLOCK(0);
    k_density<KERNEL, DENSITY, CACHE, 0><<<blocks, DENSITY_BLOCK(0)>>>(
        g->prm, g->n, g->cap, 0, g->cell_start, g->prm.multi && part != 1 ? g->gcell_start : NULL,
        g->pos, g->key_sorted, g->rho, NULL, NULL, NULL, part >= 0 ? g->key : NULL,
        (uint32_t)(part > 0 ? 1 : 0), rho_vel(g), cache_args(g), slots, threads, NULL, g->n);
    return;
  }
  const int blocks = (threads + DENSITY_BLOCK(1) - 1) / DENSITY_BLOCK(1);
  k_density<KERNEL, DENSITY, CACHE, 1><<<blocks, DENSITY_BLOCK(1)>>>(
      g->prm, g->n, g->cap, g->nbr_stride, g->cell_start,
      g->prm.multi && part != 1 ? g->gcell_start : NULL, /* the interior part meets no ghost */
      g->pos, g->key_sorted, g->rho, g->nbr, g->nbr_count, g->nbr_most, part >= 0 ? g->key : NULL,
      (uint32_t)(part > 0 ? 1 : 0), rho_vel(g), cache_args(g), slots, threads, tail_rho,
      tail_rho ? g->n_dyn : g->n);
}

static void launch_part(struct cuda_sim *g, int part) {
  const int cache = cache_args(g).table != NULL;
  if (!g->prm.density)
    launch<MESO_KERNEL_WARREN, 0, 0>(g, part);
  else if (g->prm.kernel == MESO_KERNEL_LUCY)
    cache ? launch<MESO_KERNEL_LUCY, 1, 1>(g, part) : launch<MESO_KERNEL_LUCY, 1, 0>(g, part);
  else
    cache ? launch<MESO_KERNEL_WARREN, 1, 1>(g, part) : launch<MESO_KERNEL_WARREN, 1, 0>(g, part);
}

/* Clear the overflow record and launch one part (-1: all) of the scan; lists start with room for
 * 48 entries. */
static int start_scan(struct cuda_sim *g, int part) {
  if (!g->compact && g->nbr_stride == 0) {
    if (cuda_nbr_reserve(g, 48)) return -1;
    if (g->compact) cuda_pack(g); /* switched (no room for the lists): arrays re-made */
  }
  if (cache_prepare(g)) return -1;
  if (!g->compact && cuda_check(cudaMemsetAsync(g->nbr_most, 0, sizeof(int)), "density pass"))
    return -1;
  launch_part(g, part);
  return 0;
}

/* The longest list that did not fit since start_scan (0: all fitted; waits for the scan), or -1. */
static int overflow(struct cuda_sim *g) {
  int most = 0;
  if (g->compact) return 0; /* no lists */
  if (cuda_check(cudaMemcpy(&most, g->nbr_most, sizeof(int), cudaMemcpyDeviceToHost),
                 "density pass"))
    return -1;
  return most;
}

/* Several ranks, overlap (cuda_halo.cu): the interior particles (boundary flag 1 in key) need no
 * ghost, so their densities and lists are computed while the host builds the ghosts. No list
 * overflow check here: cuda_density_pass_rest checks both parts. */
int cuda_density_pass_interior(struct cuda_sim *g) {
  if (!g->prm.terms || g->n == 0) return 0;
  return start_scan(g, 1);
}

/* The boundary part after the ghosts arrived; on a list overflow in either part, room grows and
 * the whole pass runs again. */
int cuda_density_pass_rest(struct cuda_sim *g) {
  if (!g->prm.terms || g->n == 0) return 0;
  launch_part(g, 0);
  const int most = overflow(g);
  if (most < 0) return -1;
  if (most == 0) {
    g->n_builds++;
    return 0;
  }
  return cuda_nbr_reserve(g, most + most / 8 + 8) || cuda_density_pass(g) ? -1 : 0;
}

/* Densities over the lists of the last build: the same kernel sums as the bin scan, partners in
 * list order (= the traversal order of the build). */
template <int KERNEL>
__global__ void __launch_bounds__(CUDA_BLOCK)
    k_density_list(const struct dev_params q, int n, int cap,
                   const struct dev_pos *__restrict__ pos, const uint32_t *__restrict__ nbr,
                   const int *__restrict__ count, meso_real *__restrict__ rho, struct dev_vel *vel,
                   const struct density_cache_args dc) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const struct dev_pos pi = pos[i];
  const struct dev_coef *row = q.coef[pi.species];
  meso_real sum = MESO_R(0.0), cached = MESO_R(0.0);
  long long id_i = 0;
  /* cached: the static part from the table, the list's static partners (a list built while the
   * table was filled holds them) left out */
  const int cached_i = cache_mode(q, dc, pi.species, i, &cached, &id_i) == 1;
  const int m = count[i];
  nbr_for_each(nbr, i, m, cap, [&](uint32_t e) {
    const struct dev_pos pj = pos[e & ((1u << NBR_SLOT_BITS) - 1)];
    if (cached_i && q.static_frozen[pj.species]) return;
    meso_real dx, dy, dz;
    dev_offset_sep(q, pi, pj, e >> NBR_SLOT_BITS, &dx, &dy, &dz);
    const meso_real r2 = dx * dx + dy * dy + dz * dz;
    if (r2 >= q.rd2_max) return;
    sum += dev_w_rho<KERNEL>(row[pj.species], r2);
  });
  if (cached_i) sum = cached + sum;
  rho[i] = sum;
  if (vel) vel[i].pad = sum;
}

void cuda_density_from_lists(struct cuda_sim *g) {
  if (!g->prm.density || g->n == 0) return;
  const int blocks = (g->n + CUDA_BLOCK - 1) / CUDA_BLOCK;
  if (g->prm.kernel == MESO_KERNEL_LUCY)
    k_density_list<MESO_KERNEL_LUCY><<<blocks, CUDA_BLOCK>>>(
        g->prm, g->n, g->cap, g->pos, g->nbr, g->nbr_count, g->rho, rho_vel(g), cache_args(g));
  else
    k_density_list<MESO_KERNEL_WARREN><<<blocks, CUDA_BLOCK>>>(
        g->prm, g->n, g->cap, g->pos, g->nbr, g->nbr_count, g->rho, rho_vel(g), cache_args(g));
}

__global__ void k_rho_to_vel(int i0, int n, const meso_real *__restrict__ rho,
                             struct dev_vel *vel) {
  const int i = i0 + blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) vel[i].pad = rho[i];
}

void cuda_rho_to_vel(struct cuda_sim *g, int i0, int i1, cudaStream_t stream) {
  if (!g->prm.density || !g->vel || i1 <= i0) return;
  k_rho_to_vel<<<(i1 - i0 + CUDA_BLOCK - 1) / CUDA_BLOCK, CUDA_BLOCK, 0, stream>>>(i0, i1, g->rho,
                                                                                   g->vel);
}

/* Densities and lists; a list longer than the room it had grows the room and runs the pass again
 * (one small device-to-host copy per step tells). */
int cuda_density_pass(struct cuda_sim *g) {
  if (!g->prm.terms || g->n == 0) return 0;
  for (;;) {
    if (start_scan(g, -1)) return -1;
    const int most = overflow(g);
    if (most < 0) return -1;
    if (most == 0) break;
    if (cuda_nbr_reserve(g, most + most / 8 + 8)) return -1;
    if (g->compact) cuda_pack(g); /* switched (no room for the lists): arrays re-made */
  }
  g->n_builds++;
  if (g->prm.skin <= 0.0 || g->prm.multi || g->compact) return 0;
  /* Positions at this build: the pack kernel measures the displacement from them. */
  if (!g->pos0 && cuda_alloc(g, (void **)&g->pos0, (size_t)g->cap * sizeof(struct dev_pos)))
    return -1;
  g->lists_valid = 1;
  return cuda_check(cudaMemcpyAsync(g->pos0, g->pos, (size_t)g->n * sizeof(struct dev_pos),
                                    cudaMemcpyDeviceToDevice),
                    "density pass");
}
