/* Ghosts packed on the device, for the usual cut: one axis split between ranks,
 * the other axes wrapping on the device. The host path (cuda_halo.cu + the CPU path's ghosts.c)
 * copies the boundary set into host particle arrays, selects and packs it again there, exchanges,
 * unpacks into host arrays and copies the ghosts up: ~9 ms per step for 173k boundary particles on
 * the 2 x H200 machine (bench/RESULTS.md). Here the device selects the two sets (within the cutoff
 * of the lower and of the upper face), writes their 64-byte records (ghosts.c's layout, the
 * periodic shift added by the sender as ghosts.c does) in slot order, and one asynchronous copy
 * puts them in a pinned buffer that MPI sends as it is; the records that arrive go up in one copy
 * and are unpacked into ghost slots by a kernel. The ghost order (from above, then from below, each
 * in the sender's slot order) and the density halo's order are those of the host path, so the two
 * paths give the same ghosts in the same order. */
#include "cuda_select.cuh"
#include "domain/migrate.h"

#include <string.h>

struct __align__(8) ghost_record {
  long long id;
  int species, pad;
  double x[3], v[3];
};
static_assert(sizeof(struct ghost_record) == CUDA_GHOST_RECORD_BYTES, "ghosts.c's record");

static int blocks_for(int n) {
  return (n + CUDA_BLOCK - 1) / CUDA_BLOCK;
}

/* Boundary flags of the overlap split (key 0: within the cutoff of a face between ranks, as
 * k_boundary_keys) and the two send sets' flags (ghosts.c's tests: x < lo + rcut, x >= hi - rcut,
 * each only towards an existing neighbour). */
__global__ void k_ghost_flags(const struct dev_params q, int n, const double *__restrict__ x,
                              int axis, int send_lo, int send_hi, uint32_t *key, int *flag_lo,
                              int *flag_hi) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const double lo = q.sub_lo[axis] + q.rcut, hi = q.sub_hi[axis] - q.rcut;
  const int below = x[i] < lo, above = x[i] >= hi;
  key[i] = below || above ? 0u : 1u;
  flag_lo[i] = send_lo && below;
  flag_hi[i] = send_hi && above;
}

/* Records of the n_lo + n_hi selected slots (perm), the first n_lo shifted by shift_lo along the
 * axis, the others by shift_hi. */
__global__ void k_ghost_pack(int n_lo, int n_all, const int *__restrict__ perm, struct dev_fields p,
                             int use_vpred, int axis, double shift_lo, double shift_hi,
                             struct ghost_record *out) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n_all) return;
  const int i = perm[k];
  struct ghost_record r;
  r.id = (long long)p.id[i];
  r.species = p.species[i];
  r.pad = 0;
  for (int d = 0; d < 3; d++) {
    r.x[d] = p.x[d][i];
    r.v[d] = use_vpred ? p.vpred[d][i] : p.v[d][i];
  }
  r.x[axis] += k < n_lo ? shift_lo : shift_hi;
  out[k] = r;
}

/* Arrived records into ghost slots [n0, n0 + ng) of the field set (then sorted by bin). */
__global__ void k_ghost_unpack(int n0, int ng, const struct ghost_record *__restrict__ in,
                               struct dev_fields p, int use_vpred) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= ng) return;
  const struct ghost_record r = in[k];
  const int j = n0 + k;
  p.id[j] = (int64_t)r.id;
  p.species[j] = r.species;
  double *const *v = use_vpred ? p.vpred : p.v;
  for (int d = 0; d < 3; d++) {
    p.x[d][j] = r.x[d];
    v[d][j] = r.v[d];
  }
}

/* Whether slot i is in the boundary part (key 0: k_ghost_flags). */
struct is_boundary {
  const uint32_t *key;
  __device__ __forceinline__ bool operator()(int i) const { return key[i] == 0u; }
};

/* The boundary slots (slot order) into g->bslots, their count into count_dev. */
static int select_boundary(struct cuda_sim *g, int *count_dev) {
  const int n = g->n;
  const struct is_boundary pred = {g->key};
  if (cuda_dev_room(g, (char **)&g->bslots, &g->bslots_cap, (size_t)n * sizeof(int))) return -1;
  return cuda_select_slots_if(g, pred, g->bslots, count_dev, n, "boundary slots");
}

extern "C" int cuda_halo_select(cuda_sim_t *g, int axis, int send_lo, int send_hi, int n_send[2]) {
  const int n = g->n;
  n_send[0] = n_send[1] = 0;
  g->n_ghost = 0;
  g->n_boundary = 0;
  g->n_bslots = 0;
  g->boundary_slots = NULL;
  if (n == 0) return 0;
  if (!g->halo_count_dev && cuda_alloc(g, (void **)&g->halo_count_dev, 3 * sizeof(int))) return -1;
  /* iota and nbr_count are free here (the sort used iota; the density pass rewrites the counts) */
  int *flag_lo = g->iota, *flag_hi = g->nbr_count;
  k_ghost_flags<<<blocks_for(n), CUDA_BLOCK>>>(g->prm, n, g->a.x[axis], axis, send_lo, send_hi,
                                               g->key, flag_lo, flag_hi);
  /* the lower set into perm[0, n_lo), then the upper set after it (slot order in each) */
  int counts[3] = {0, 0, 0};
  /* Both sets sent and the subdomain at least two cutoffs wide (no slot in both): the sets are
   * exactly the boundary part (k_ghost_flags' tests), so no third selection is needed. */
  const int sets_cover =
      send_lo && send_hi && g->prm.sub_lo[axis] + g->prm.rcut <= g->prm.sub_hi[axis] - g->prm.rcut;
  if (sets_cover) {
    /* the upper set into bslots, both counts in one synchronising copy (then moved after the
     * lower set, below) */
    if (cuda_dev_room(g, (char **)&g->bslots, &g->bslots_cap, (size_t)n * sizeof(int)) ||
        cuda_select_slots(g, flag_lo, g->perm, g->halo_count_dev, n, "ghost selection") ||
        cuda_select_slots(g, flag_hi, g->bslots, g->halo_count_dev + 1, n, "ghost selection") ||
        cuda_counts_down(g, counts, g->halo_count_dev, 2, "ghost selection"))
      return -1;
  } else if (cuda_select_slots(g, flag_lo, g->perm, g->halo_count_dev, n, "ghost selection") ||
             cuda_counts_down(g, counts, g->halo_count_dev, 1, "ghost selection") ||
             cuda_select_slots(g, flag_hi, g->perm + counts[0], g->halo_count_dev + 1, n,
                               "ghost selection") ||
             select_boundary(g, g->halo_count_dev + 2) ||
             cuda_counts_down(g, counts + 1, g->halo_count_dev + 1, 2, "ghost selection"))
    return -1;
  if ((long long)counts[0] + counts[1] > (long long)g->cap) {
    fprintf(stderr, "mdpore: CUDA backend: %d + %d boundary particles exceed the %d slots\n",
            counts[0], counts[1], g->cap);
    return -1;
  }
  /* the upper set after the lower one in perm (queued: no wait) */
  if (sets_cover && counts[1] > 0 &&
      cuda_check(cudaMemcpyAsync(g->perm + counts[0], g->bslots, (size_t)counts[1] * sizeof(int),
                                 cudaMemcpyDeviceToDevice, 0),
                 "ghost selection"))
    return -1;
  /* the two sets are the boundary part when they cover it: both sent, disjoint */
  g->boundary_slots = sets_cover ? g->perm : g->bslots;
  g->n_bslots = sets_cover ? counts[0] + counts[1] : counts[2];
  g->halo_n[0] = n_send[0] = counts[0];
  g->halo_n[1] = n_send[1] = counts[1];
  g->n_boundary = counts[0] + counts[1]; /* perm[0, n_boundary): kept by cuda_grow */
  return 0;
}

/* The pinned buffer as [send | receive], each part 16-byte aligned; waits for every copy in flight
 * (both streams) when it must grow. */
static int pinned_parts(struct cuda_sim *g, size_t send_bytes, size_t recv_bytes, void **send,
                        void **recv) {
  const size_t s = (send_bytes + 15) & ~(size_t)15, total = s + recv_bytes + 16;
  if (total > g->pinned_bytes && cuda_check(cudaDeviceSynchronize(), "halo buffer")) return -1;
  char *buf = cuda_pinned(g, total);
  if (!buf) return -1;
  *send = buf;
  *recv = buf + s;
  g->pinned_send_bytes = s;
  return 0;
}

/* The copy stream and its events (made once). */
static int copy_stream(struct cuda_sim *g) {
  if (g->packed_made) return 0;
  if (cuda_check(cudaStreamCreateWithFlags(&g->copies, cudaStreamNonBlocking), "halo stream") ||
      cuda_check(cudaEventCreateWithFlags(&g->packed, cudaEventDisableTiming), "halo event") ||
      cuda_check(cudaEventCreateWithFlags(&g->ready, cudaEventDisableTiming), "halo event") ||
      cuda_check(cudaEventCreateWithFlags(&g->copied, cudaEventDisableTiming), "halo event"))
    return -1;
  g->packed_made = 1;
  return 0;
}

/* Device -> pinned on the copy stream once the default stream has written the data; `packed` marks
 * the end (cuda_halo_wait_packed). The default stream goes on meanwhile. */
static int copy_down(struct cuda_sim *g, void *host, const void *dev, size_t bytes,
                     const char *what) {
  if (copy_stream(g) || cuda_check(cudaEventRecord(g->ready, 0), what) ||
      cuda_check(cudaStreamWaitEvent(g->copies, g->ready, 0), what) ||
      (bytes &&
       cuda_check(cudaMemcpyAsync(host, dev, bytes, cudaMemcpyDeviceToHost, g->copies), what)))
    return -1;
  return cuda_check(cudaEventRecord(g->packed, g->copies), what);
}

/* Pinned -> device on the copy stream; the default stream waits for it before its next launch
 * (the kernel that reads the data), not the host. */
static int copy_up(struct cuda_sim *g, void *dev, const void *host, size_t bytes,
                   const char *what) {
  if (copy_stream(g) ||
      cuda_check(cudaMemcpyAsync(dev, host, bytes, cudaMemcpyHostToDevice, g->copies), what) ||
      cuda_check(cudaEventRecord(g->copied, g->copies), what))
    return -1;
  return cuda_check(cudaStreamWaitEvent(0, g->copied, 0), what);
}

extern "C" int cuda_halo_pack(cuda_sim_t *g, int axis, double shift_lo, double shift_hi,
                              int n_from_up, int n_from_down, void **send, void **recv) {
  const int n_all = g->halo_n[0] + g->halo_n[1];
  g->halo_n[2] = n_from_up;
  g->halo_n[3] = n_from_down;
  const size_t out_bytes = (size_t)n_all * sizeof(struct ghost_record);
  const size_t in_bytes = (size_t)(n_from_up + n_from_down) * sizeof(struct ghost_record);
  if (pinned_parts(g, out_bytes, in_bytes, send, recv) ||
      cuda_dev_room(g, &g->ghost_send_dev, &g->ghost_send_cap, out_bytes + 1))
    return -1;
  if (n_all > 0)
    k_ghost_pack<<<blocks_for(n_all), CUDA_BLOCK>>>(g->halo_n[0], n_all, g->perm, g->a,
                                                    g->prm.use_vpred, axis, shift_lo, shift_hi,
                                                    (struct ghost_record *)g->ghost_send_dev);
  return copy_down(g, *send, g->ghost_send_dev, out_bytes, "ghost records down");
}

extern "C" int cuda_halo_wait_packed(cuda_sim_t *g) {
  return g->packed_made ? cuda_check(cudaEventSynchronize(g->packed), "halo download") : 0;
}

extern "C" int cuda_halo_unpack(cuda_sim_t *g) {
  const int ng = g->halo_n[2] + g->halo_n[3], n0 = g->n;
  g->n_ghost = 0;
  if (n0 + ng > g->cap) {
    /* More ghosts than room: grow (after the interior pass in flight) and run this step's pair
     * passes in one part, since the interior lists went with the old arrays. */
    g->split_passes = 0;
    g->boundary_slots = NULL; /* (perm moves with the arrays) */
    if (cuda_grow(g, n0 + ng)) return -1;
  }
  const size_t bytes = (size_t)ng * sizeof(struct ghost_record);
  if (cuda_dev_room(g, &g->ghost_recv_dev, &g->ghost_recv_cap, bytes + 1)) return -1;
  if (ng > 0) {
    if (copy_up(g, g->ghost_recv_dev, g->pinned + g->pinned_send_bytes, bytes, "ghost records up"))
      return -1;
    k_ghost_unpack<<<blocks_for(ng), CUDA_BLOCK>>>(
        n0, ng, (const struct ghost_record *)g->ghost_recv_dev, g->b, g->prm.use_vpred);
  }
  g->n_ghost = ng;
  return cuda_sort_ghosts(g);
}

extern "C" int cuda_halo_rho_pack(cuda_sim_t *g, void **send, void **recv) {
  const int n_all = g->halo_n[0] + g->halo_n[1], ng = g->halo_n[2] + g->halo_n[3];
  const size_t w = sizeof(meso_real);
  /* the ghost records' upload of this step was queued on the copy stream before this download: the
   * receive part is free once `packed` is reached (pinned_parts waits for everything if it grows) */
  if (pinned_parts(g, (size_t)n_all * w, (size_t)ng * w, send, recv)) return -1;
  const int take = g->prm.density && n_all > 0;
  if (take) cuda_rho_gather(n_all, g->perm, g->rho, g->rho_stage, 0);
  return copy_down(g, *send, g->rho_stage, take ? (size_t)n_all * w : 0, "density halo down");
}

extern "C" int cuda_halo_rho_unpack(cuda_sim_t *g) {
  const int ng = g->n_ghost;
  if (!g->prm.density || ng == 0) return 0;
  /* Up and into the ghost slots on the copy stream, not waited for by the default stream (the
   * interior forces there read no ghost density): cuda_halo_forces puts the boundary forces after
   * them on the same stream and joins the two streams. */
  if (cuda_check(cudaMemcpyAsync(g->rho_stage, g->pinned + g->pinned_send_bytes,
                                 (size_t)ng * sizeof(meso_real), cudaMemcpyHostToDevice, g->copies),
                 "density halo up"))
    return -1;
  cuda_rho_scatter(g->n, ng, g->perm, g->rho_stage, g->rho, g->copies);
  g->rho_on_copies = 1;
  return cuda_check(cudaGetLastError(), "density halo");
}

extern "C" void cuda_halo_counts(const cuda_sim_t *g, int n[4]) {
  for (int k = 0; k < 4; k++) n[k] = g->halo_n[k];
}

/* Migration as records (one axis cut): the leavers' records from their slots perm[0, m), every
 * field with the forces (migrate.c's migrant_t, the CPU path's wire format). */
/* The leavers' records from their slots perm[0, min(*count, cap)) into out (pinned host memory,
 * mapped: written across the bus, read by the host after the synchronising copy of the count). */
__global__ void k_migrant_pack(const int *__restrict__ count, int cap, const int *__restrict__ perm,
                               struct dev_fields p, migrant_t *out) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= cap || k >= *count) return;
  const int i = perm[k];
  migrant_t r;
  r.id = p.id[i];
  r.species = p.species[i];
  r.pad = 0;
  for (int d = 0; d < 3; d++) {
    r.x[d] = p.x[d][i];
    r.v[d] = p.v[d][i];
    r.f[d] = p.f[d][i];
  }
  out[k] = r;
}

/* Records into the owned slots [n0, n0 + m). */
__global__ void k_migrant_unpack(int n0, int m, const migrant_t *__restrict__ in,
                                 struct dev_fields p) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= m) return;
  const migrant_t r = in[k];
  const int j = n0 + k;
  p.id[j] = r.id;
  p.species[j] = r.species;
  for (int d = 0; d < 3; d++) {
    p.x[d][j] = r.x[d];
    p.v[d][j] = r.v[d];
    p.f[d][j] = r.f[d];
  }
}

/* The migration's pinned buffer (mapped: the pack kernel writes into it), at least bytes (no copy
 * from it is in flight when it grows: the last upload from it was followed by synchronising
 * copies). */
static char *mig_pinned(struct cuda_sim *g, size_t bytes) {
  if (bytes <= g->mig_pinned_bytes) return g->mig_pinned;
  if (g->mig_pinned) cudaFreeHost(g->mig_pinned);
  g->mig_pinned = NULL;
  g->mig_pinned_dev = NULL;
  g->mig_pinned_bytes = 0;
  const size_t want = cuda_tight_room() ? bytes : bytes + bytes / 4 + 4096;
  if (cuda_check_alloc(cudaHostAlloc((void **)&g->mig_pinned, want, cudaHostAllocMapped),
                       "the migration buffer", want, "host (pinned)"))
    return NULL;
  g->mig_pinned_bytes = want;
  if (cuda_check(cudaHostGetDevicePointer((void **)&g->mig_pinned_dev, g->mig_pinned, 0),
                 "migration buffer"))
    return NULL;
  return g->mig_pinned;
}

/* Pack the first min(count, room) leavers into the mapped buffer. */
static int pack_leavers(struct cuda_sim *g, int room) {
  k_migrant_pack<<<blocks_for(room), CUDA_BLOCK>>>(g->counter, room, g->perm, g->a,
                                                   (migrant_t *)g->mig_pinned_dev);
  return cuda_check(cudaGetLastError(), "migration");
}

extern "C" int cuda_halo_take_leaving(cuda_sim_t *g, int *m, const void **out) {
  *m = 0;
  *out = NULL;
  g->n_leaving = 0;
  if (g->n == 0) return 0;
  /* first call: room for 4096 records (1 with MDPORE_CUDA_TIGHT_ROOM=1); it grows below */
  if (!g->mig_pinned && !mig_pinned(g, (cuda_tight_room() ? 1 : 4096) * sizeof(migrant_t)))
    return -1;
  int room = (int)(g->mig_pinned_bytes / sizeof(migrant_t));
  if (cuda_leavers_select(g) || pack_leavers(g, room) ||
      cuda_counts_down(g, m, g->counter, 1, "leaver selection"))
    return -1;
  if (*m > room) { /* more leavers than room: grow (nothing in flight), pack them all again */
    if (!mig_pinned(g, (size_t)*m * sizeof(migrant_t)) || pack_leavers(g, *m) ||
        cuda_check(cudaStreamSynchronize(0), "migration"))
      return -1;
  }
  g->n_leaving = *m;
  *out = g->mig_pinned;
  return 0;
}

extern "C" int cuda_halo_add_migrants(cuda_sim_t *g, const void *in, int m) {
  const int n0 = g->n;
  if (m <= 0) return 0;
  if (cuda_grow(g, n0 + m)) return -1;
  const size_t bytes = (size_t)m * sizeof(migrant_t);
  char *host = mig_pinned(g, bytes);
  if (!host || cuda_dev_room(g, &g->mig_dev, &g->mig_dev_cap, bytes)) return -1;
  memcpy(host, in, bytes);
  /* asynchronous: the next synchronising copy (the ghost selection's counts) comes before this
   * buffer is written again */
  if (cuda_check(cudaMemcpyAsync(g->mig_dev, host, bytes, cudaMemcpyHostToDevice, 0), "migration"))
    return -1;
  k_migrant_unpack<<<blocks_for(m), CUDA_BLOCK>>>(n0, m, (const migrant_t *)g->mig_dev, g->a);
  g->n = n0 + m;
  return cuda_check(cudaGetLastError(), "migration");
}
