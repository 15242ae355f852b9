/* Cell sort of the device particles: bin index per particle, stable radix sort of (bin, index),
 * gather of every field into bin order, and the first slot of each bin (cell_start). The sort is
 * stable, so an already sorted set keeps its order and the traversal order is deterministic. */
#include "cuda_neighbours.cuh"

#include <cub/device/device_radix_sort.cuh>

/* (Fine) bin of each particle; with sentinel (several ranks, owned particles) a particle outside
 * this rank's subdomain gets bin ncell, so the stable sort puts the leavers last. With
 * tail_species (the first sort with the static tail) a static frozen particle's key is its bin +
 * tail_off: those particles go last, in bin order. */
__global__ void k_cell_keys(struct dev_params q, int n, const double *__restrict__ x,
                            const double *__restrict__ y, const double *__restrict__ z,
                            uint32_t *key, int *iota, int sentinel,
                            const int *__restrict__ tail_species) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  key[i] = dev_cell_key(q, x[i], y[i], z[i]);
  if (tail_species && q.static_frozen[tail_species[i]]) key[i] += (uint32_t)q.tail_off;
  if (sentinel && !(x[i] >= q.sub_lo[0] && x[i] < q.sub_hi[0] && y[i] >= q.sub_lo[1] &&
                    y[i] < q.sub_hi[1] && z[i] >= q.sub_lo[2] && z[i] < q.sub_hi[2]))
    key[i] = (uint32_t)q.ncell;
  iota[i] = i;
}

/* Position relative to the lower corner of the bin the particle was sorted into. With a skin the
 * particle may have left that bin, or crossed a periodic face, since the sort: along a wrapping
 * axis the nearest image of the offset is taken, so the packed value stays continuous. */
__device__ __forceinline__ meso_real rel_to_bin(const struct dev_params &q, int d, double x,
                                                int b) {
  double r = x - (q.lo[d] + b * (q.L[d] / q.nb[d]));
  if (q.periodic[d]) {
    if (r > 0.5 * q.L[d])
      r -= q.L[d];
    else if (r < -0.5 * q.L[d])
      r += q.L[d];
  }
  return (meso_real)r;
}

/* The packed position of a particle at (x, y, z) sorted into fine bin c (relative to the coarse
 * bin that holds it), with its species. */
__device__ __forceinline__ struct dev_pos dev_packed_pos(const struct dev_params &q, uint32_t key,
                                                         double x, double y, double z, int s) {
  const int c = (int)key;
  const int b[3] = {(c % q.nf[0]) / q.sub[0], ((c / q.nf[0]) % q.nf[1]) / q.sub[1],
                    c / (q.nf[0] * q.nf[1]) / q.sub[2]};
  struct dev_pos r;
  r.x = rel_to_bin(q, 0, x, b[0]);
  r.y = rel_to_bin(q, 1, y, b[1]);
  r.z = rel_to_bin(q, 2, z, b[2]);
  r.species = s;
  return r;
}

/* The thermostat's packed velocity (pad: the density, written by the density pass). */
__device__ __forceinline__ struct dev_vel dev_packed_vel(double vx, double vy, double vz) {
  struct dev_vel u;
  u.x = (meso_real)vx;
  u.y = (meso_real)vy;
  u.z = (meso_real)vz;
  u.pad = 0;
  return u;
}

/* dst[k] = src[perm[k]] for every field; with pos (one rank, a step's sort) the pack of the
 * gathered slot (k_pack without a skin check) while the fields are in registers, instead of a
 * second read; with start the bin starts of k_cell_start, in the same pass. */
__global__ void k_gather(const struct dev_params q, int n, const int *__restrict__ perm,
                         struct dev_fields src, struct dev_fields dst, int with_vpred, int with_f,
                         const uint32_t *__restrict__ key, struct dev_pos *pos, struct dev_vel *vel,
                         int *start, int top) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const int i = perm[k];
  const int s = src.species[i];
  dst.id[k] = src.id[i];
  dst.species[k] = s;
  double x[3], v[3], vp[3];
#pragma unroll
  for (int d = 0; d < 3; d++) {
    x[d] = src.x[d][i];
    v[d] = src.v[d][i];
    dst.x[d][k] = x[d];
    dst.v[d][k] = v[d];
    if (with_f) dst.f[d][k] = src.f[d][i];
    if (with_vpred) {
      vp[d] = src.vpred[d][i];
      dst.vpred[d][k] = vp[d];
    }
  }
  const uint32_t c = key[k];
  if (pos) {
    pos[k] = dev_packed_pos(q, c, x[0], x[1], x[2], s);
    if (vel)
      vel[k] = with_vpred ? dev_packed_vel(vp[0], vp[1], vp[2]) : dev_packed_vel(v[0], v[1], v[2]);
  }
  if (!start) return;
  const int prev = k > 0 ? (int)key[k - 1] : -1;
  for (int b = prev + 1; b <= (int)c; b++) start[b] = k;
  if (k == n - 1)
    for (int b = (int)c + 1; b <= top; b++) start[b] = n;
}

/* The static tail's sort keys made bins again, once its bin starts are written. */
__global__ void k_tail_keys(int n0, int n, uint32_t *key, uint32_t off) {
  const int k = n0 + blockIdx.x * blockDim.x + threadIdx.x;
  if (k < n) key[k] -= off;
}

/* cell_start[c] = first sorted slot with key >= c, for c in [0, ncell]. */
__global__ void k_cell_start(int n, int ncell, const uint32_t *__restrict__ key, int *start) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const int c = (int)key[k];
  const int prev = k > 0 ? (int)key[k - 1] : -1;
  for (int b = prev + 1; b <= c; b++) start[b] = k;
  if (k == n - 1)
    for (int b = c + 1; b <= ncell; b++) start[b] = n;
}

static struct dev_fields shifted(struct dev_fields f, int off) {
  f.id += off;
  f.species += off;
  for (int d = 0; d < 3; d++) {
    f.x[d] += off;
    f.v[d] += off;
    f.f[d] += off;
    if (f.vpred[d]) f.vpred[d] += off;
  }
  return f;
}

/* The same starts by a binary search per bin: for a sparse set (the ghosts: a few bins of every
 * row), where one thread per particle would fill the long runs of empty bins between two
 * particles (and the last thread every bin after the last particle) alone. */
__global__ void k_cell_start_search(int n, int ncell, const uint32_t *__restrict__ key,
                                    int *start) {
  const int c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c > ncell) return;
  int lo = 0, hi = n; /* first k with key[k] >= c */
  while (lo < hi) {
    const int mid = (lo + hi) >> 1;
    if ((int)key[mid] < c)
      lo = mid + 1;
    else
      hi = mid;
  }
  start[c] = lo;
}

/* Sort slots [off, off + n) of src by bin into dst, bin starts (relative to off) into start.
 * The owned particles of several ranks (sentinel) skip the predicted velocities: the prediction
 * follows the sort there and rewrites them. pack (one rank, no sentinel): the packed copies
 * written by the gather. tail: the first sort with the static tail (keys up to 2 ncell + 1, the
 * tail's bin starts from start + tail_off). */
static int sort_range(struct cuda_sim *g, int off, int n, int sentinel, struct dev_fields src,
                      struct dev_fields dst, int *start, int with_f, int pack, int tail = 0) {
  const struct dev_params *q = &g->prm;
  const int top = tail ? 2 * q->ncell + 1 : q->ncell; /* the last key */
  if (n == 0) return cuda_check(cudaMemset(start, 0, (top + 1) * sizeof(int)), "sort");
  const int blocks = (n + CUDA_BLOCK - 1) / CUDA_BLOCK;
  src = shifted(src, off);
  if (tail || !(g->keys_ready && off == 0 && !sentinel)) /* (else the kick-drift wrote them) */
    k_cell_keys<<<blocks, CUDA_BLOCK>>>(*q, n, src.x[0], src.x[1], src.x[2], g->key + off,
                                        g->iota + off, sentinel, tail ? src.species : NULL);
  g->keys_ready = 0;
  int end_bit = 1;
  while (end_bit < 32 && (1u << end_bit) <= (unsigned)top) end_bit++; /* keys 0..top */
  size_t tmp = g->sort_tmp_bytes;
  if (cuda_check(cub::DeviceRadixSort::SortPairs(g->sort_tmp, tmp, g->key + off,
                                                 g->key_sorted + off, g->iota + off, g->perm + off,
                                                 n, 0, end_bit),
                 "cell sort"))
    return -1;
  const int sparse = !tail && (long long)n * 4 < (long long)q->ncell;
  k_gather<<<blocks, CUDA_BLOCK>>>(*q, n, g->perm + off, src, shifted(dst, off),
                                   q->use_vpred && !sentinel, with_f, g->key_sorted + off,
                                   pack ? g->pos + off : NULL, pack && g->vel ? g->vel + off : NULL,
                                   sparse ? NULL : start, top);
  if (sparse)
    k_cell_start_search<<<(q->ncell + CUDA_BLOCK) / CUDA_BLOCK, CUDA_BLOCK>>>(
        n, q->ncell, g->key_sorted + off, start);
  return cuda_check(cudaGetLastError(), "cell sort kernels");
}

/* dst[k] = src[perm[k]] for one field of T. */
template <class T>
__global__ void k_gather_one(int n, const int *__restrict__ perm, const T *__restrict__ src,
                             T *__restrict__ dst) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < n) dst[k] = src[perm[k]];
}

/* Gather one field through the scratch array and swap the two (compact mode: every field array and
 * the scratch hold 8 bytes per slot). */
template <class T> static void gather_swap(struct cuda_sim *g, int blocks, T **field) {
  k_gather_one<T><<<blocks, CUDA_BLOCK>>>(g->n, g->perm, *field, (T *)g->sort_scratch);
  T *const was = *field;
  *field = (T *)g->sort_scratch;
  g->sort_scratch = (double *)was;
}

/* Compact mode, one rank: the same stable sort by bin with cub's double-buffer variant (no key and
 * value copies in its temporary storage), then each field gathered on its own through the 8-byte
 * scratch, so no second field set is held. The order is that of sort_range. */
static int sort_one_set(struct cuda_sim *g, int with_f) {
  const struct dev_params *q = &g->prm;
  const int n = g->n;
  if (n == 0) return cuda_check(cudaMemset(g->cell_start, 0, (q->ncell + 1) * sizeof(int)), "sort");
  const int blocks = (n + CUDA_BLOCK - 1) / CUDA_BLOCK;
  if (!g->keys_ready) /* (else the kick-drift wrote them) */
    k_cell_keys<<<blocks, CUDA_BLOCK>>>(*q, n, g->a.x[0], g->a.x[1], g->a.x[2], g->key, g->iota, 0,
                                        NULL);
  g->keys_ready = 0;
  int end_bit = 1;
  while (end_bit < 32 && (1u << end_bit) <= (unsigned)q->ncell) end_bit++;
  cub::DoubleBuffer<uint32_t> keys(g->key, g->key_sorted);
  cub::DoubleBuffer<int> values(g->iota, g->perm);
  size_t tmp = g->sort_tmp_bytes;
  if (cuda_check(cub::DeviceRadixSort::SortPairs(g->sort_tmp, tmp, keys, values, n, 0, end_bit),
                 "cell sort"))
    return -1;
  if (keys.Current() != g->key_sorted) { /* the result landed in the input buffers: swap names */
    uint32_t *tk = g->key;
    g->key = g->key_sorted;
    g->key_sorted = tk;
    int *tv = g->iota;
    g->iota = g->perm;
    g->perm = tv;
  }
  gather_swap<int64_t>(g, blocks, &g->a.id);
  gather_swap<int>(g, blocks, &g->a.species);
  for (int d = 0; d < 3; d++) {
    gather_swap<double>(g, blocks, &g->a.x[d]);
    gather_swap<double>(g, blocks, &g->a.v[d]);
    if (with_f) gather_swap<double>(g, blocks, &g->a.f[d]);
    if (q->use_vpred) gather_swap<double>(g, blocks, &g->a.vpred[d]);
  }
  k_cell_start<<<blocks, CUDA_BLOCK>>>(n, q->ncell, g->key_sorted, g->cell_start);
  return cuda_check(cudaGetLastError(), "cell sort kernels");
}

/* After the first sort with the static tail (now in a): n_dyn from the tail's first bin start,
 * the tail's keys made bins, and its fields copied into b too, so that the later sorts, which
 * swap a and b and cover only the slots before it, find it in either set. 0 or -1. */
static int tail_settle(struct cuda_sim *g) {
  const int n = g->n;
  if (cuda_check(cudaMemcpy(&g->n_dyn, g->cell_start + g->prm.tail_off, sizeof(int),
                            cudaMemcpyDeviceToHost),
                 "static tail"))
    return -1;
  const size_t k = (size_t)g->n_dyn, m = (size_t)(n - g->n_dyn);
  if (m > 0)
    k_tail_keys<<<(int)((m + CUDA_BLOCK - 1) / CUDA_BLOCK), CUDA_BLOCK>>>(
        g->n_dyn, n, g->key_sorted, (uint32_t)g->prm.tail_off);
  if (cuda_copy_fields(&g->b, &g->a, k, m, "static tail")) return -1;
  g->tail_rho_ready = 0;
  g->prm.tail = 1;
  return 0;
}

int cuda_sort_cells(struct cuda_sim *g, int with_f, int pack) {
  g->lists_valid = 0;
  g->mobile_slots_ready = 0;
  if (g->sort_scratch) {
    if (sort_one_set(g, with_f)) return -1;
    if (pack) cuda_pack(g);
    return 0;
  }
  const int fused = pack && !g->prm.multi; /* one rank: no ghosts to pack after */
  const int tail_sort = g->tail_on && !g->prm.tail;
  const int n_sort = g->prm.tail ? g->n_dyn : g->n; /* (the tail stays where it is) */
  if (sort_range(g, 0, n_sort, g->prm.multi, g->a, g->b, g->cell_start, with_f, fused && !tail_sort,
                 tail_sort))
    return -1;
  struct dev_fields t = g->a;
  g->a = g->b;
  g->b = t;
  if (tail_sort) {
    if (tail_settle(g)) return -1;
    if (pack) cuda_pack(g);
    return 0;
  }
  if (pack && !fused) cuda_pack(g);
  return 0;
}

/* Ghosts uploaded into b's slots [n, n + n_ghost) go into a's, in bin order (multi). */
int cuda_sort_ghosts(struct cuda_sim *g) {
  return sort_range(g, g->n, g->n_ghost, 0, g->b, g->a, g->gcell_start, 0, 0); /* ghosts: no f */
}

/* Packed positions and thermostat velocities; with pos0 (skin > 0) a particle that moved more than
 * skin / 2 since the lists were built raises *rebuild. */
__global__ void k_pack(const struct dev_params q, int k0, int n, struct dev_fields p,
                       const uint32_t *__restrict__ key, struct dev_pos *pos, struct dev_vel *vel,
                       int use_vpred, const struct dev_pos *__restrict__ pos0, int *rebuild) {
  const int k = k0 + blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const struct dev_pos r = dev_packed_pos(q, key[k], p.x[0][k], p.x[1][k], p.x[2][k], p.species[k]);
  pos[k] = r;
  if (pos0) {
    const struct dev_pos o = pos0[k];
    /* Along an axis of fewer than 3 bins the packed value may jump by the box length when the
     * particle crosses the periodic face (the traversal takes the nearest image there anyway). */
    const meso_real dx = dev_nearest(q, 0, r.x - o.x), dy = dev_nearest(q, 1, r.y - o.y),
                    dz = dev_nearest(q, 2, r.z - o.z);
    if (!(dx * dx + dy * dy + dz * dz <= q.half_skin2)) *rebuild = 1; /* NaN rebuilds too */
  }
  if (vel) {
    double *const *v = use_vpred ? p.vpred : p.v;
    vel[k] = dev_packed_vel(v[0][k], v[1][k], v[2][k]);
  }
}

static void pack(struct cuda_sim *g, int i0, int i1, const struct dev_pos *pos0) {
  if (i1 <= i0) return;
  k_pack<<<(i1 - i0 + CUDA_BLOCK - 1) / CUDA_BLOCK, CUDA_BLOCK>>>(
      g->prm, i0, i1, g->a, g->key_sorted, g->pos, g->vel, g->prm.use_vpred, pos0, g->rebuild);
}

void cuda_pack(struct cuda_sim *g) {
  pack(g, 0, g->n + g->n_ghost, NULL);
}

void cuda_pack_range(struct cuda_sim *g, int i0, int i1) {
  pack(g, i0, i1, NULL);
}

int cuda_pack_check(struct cuda_sim *g) {
  if (g->prm.skin <= 0.0 || !g->pos0 || !g->lists_valid) {
    pack(g, 0, g->n, NULL);
    return 1;
  }
  if (cuda_check(cudaMemsetAsync(g->rebuild, 0, sizeof(int)), "pack")) return -1;
  pack(g, 0, g->n, g->pos0);
  int h = 1;
  if (cuda_check(cudaMemcpy(&h, g->rebuild, sizeof(int), cudaMemcpyDeviceToHost), "pack"))
    return -1;
  return h != 0;
}
