/* Several ranks, one GPU each: the device side of migration, ghosts and the density halo. Only the
 * particles that cross or border a face travel through the host (through a pinned buffer, all
 * copies of a set queued before one wait); the host side reuses the CPU path's exchanges
 * (migrate_particles, ghosts_build, ghosts_sync_scalar) on those few particles, so the images, the
 * stages and the messages are the CPU path's. Owned particles come first in bin order, then the
 * ghosts in bin order (their own bin starts, gcell_start). */
#include "cuda_state.cuh"

#include <stdlib.h>
#include <string.h>

/* (hb must have room for all owned particles: the caller reserves it.) */
/* Owned particles within the ghost cutoff of a face between ranks: the only ones ghosts_build can
 * send, at any stage (axes not cut between ranks wrap on the device and send nothing). key 0 for
 * them, 1 for the others: the stable sort lists them first, in slot order. */
__global__ void k_boundary_keys(const struct dev_params q, int n, struct dev_fields p,
                                uint32_t *key, int *iota, int *count) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  int near = 0;
  for (int d = 0; d < 3; d++)
    near |= q.split[d] && (p.x[d][i] < q.sub_lo[d] + q.rcut || p.x[d][i] >= q.sub_hi[d] - q.rcut);
  key[i] = near ? 0u : 1u;
  iota[i] = i;
  if (near) atomicAdd(count, 1);
}

/* dst[k] = the boundary particle perm[k]: id, species, x, thermostat velocity (in dst.v). */
__global__ void k_boundary_gather(int n, const int *__restrict__ perm, struct dev_fields src,
                                  struct dev_fields dst, int use_vpred) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const int i = perm[k];
  dst.id[k] = src.id[i];
  dst.species[k] = src.species[i];
  for (int d = 0; d < 3; d++) {
    dst.x[d][k] = src.x[d][i];
    dst.v[d][k] = use_vpred ? src.vpred[d][i] : src.v[d][i];
  }
}

__global__ void k_rho_gather(int n, const int *__restrict__ perm, const meso_real *__restrict__ rho,
                             meso_real *out) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < n) out[k] = rho[perm[k]];
}

/* rho of ghost slot n0 + k from the host's ghost order (perm of the ghost sort). */
__global__ void k_rho_scatter(int n0, int ng, const int *__restrict__ perm,
                              const meso_real *__restrict__ in, meso_real *rho) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < ng) rho[n0 + k] = in[perm[n0 + k]];
}

static int blocks_of(int n) {
  return (n + CUDA_BLOCK - 1) / CUDA_BLOCK;
}

void cuda_rho_gather(int n, const int *perm, const meso_real *rho, meso_real *out,
                     cudaStream_t stream) {
  if (n > 0) k_rho_gather<<<blocks_of(n), CUDA_BLOCK, 0, stream>>>(n, perm, rho, out);
}

void cuda_rho_scatter(int n0, int ng, const int *perm, const meso_real *in, meso_real *rho,
                      cudaStream_t stream) {
  if (ng > 0) k_rho_scatter<<<blocks_of(ng), CUDA_BLOCK, 0, stream>>>(n0, ng, perm, in, rho);
}

static int down(void *dst, const void *src, size_t bytes) {
  return cuda_check(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToHost), "halo download");
}

/* The pinned host buffer every halo transfer goes through (DMA at full speed, several copies in
 * flight, one synchronisation per transfer set). Grows as needed. */
char *cuda_pinned(struct cuda_sim *g, size_t bytes) {
  if (bytes <= g->pinned_bytes) return g->pinned;
  if (g->pinned) cudaFreeHost(g->pinned);
  g->pinned = NULL;
  g->pinned_bytes = 0;
  const size_t want = bytes + bytes / 4 + 4096;
  if (cuda_check_alloc(cudaHostAlloc((void **)&g->pinned, want, cudaHostAllocDefault),
                       "the halo's pinned buffer", want, "host (pinned)"))
    return NULL;
  g->pinned_bytes = want;
  return g->pinned;
}

int cuda_counts_down(struct cuda_sim *g, int *out, const int *dev, int k, const char *what) {
  if (!g->counts_pinned &&
      cuda_check(cudaHostAlloc((void **)&g->counts_pinned, 4 * sizeof(int), cudaHostAllocDefault),
                 what))
    return -1;
  if (cuda_check(cudaMemcpyAsync(g->counts_pinned, dev, (size_t)k * sizeof(int),
                                 cudaMemcpyDeviceToHost, 0),
                 what) ||
      cuda_check(cudaStreamSynchronize(0), what))
    return -1;
  memcpy(out, g->counts_pinned, (size_t)k * sizeof(int));
  return 0;
}

/* A set of device <-> host copies staged through the pinned buffer (16-byte aligned pieces). */
struct stage {
  int k;
  void *host[16];
  void *dev[16];
  size_t bytes[16];
};

static void stage_add(struct stage *st, void *host, void *dev, size_t bytes) {
  st->host[st->k] = host;
  st->dev[st->k] = dev;
  st->bytes[st->k] = bytes;
  st->k++;
}

static size_t padded(size_t b) {
  return (b + 15) & ~(size_t)15;
}

/* Device -> pinned (all copies queued, one wait) -> the host arrays. */
static int stage_down(struct cuda_sim *g, const struct stage *st) {
  size_t total = 0;
  for (int i = 0; i < st->k; i++) total += padded(st->bytes[i]);
  char *buf = cuda_pinned(g, total);
  if (!buf) return -1;
  int rc = 0;
  for (int i = 0, off = 0; i < st->k; off += (int)padded(st->bytes[i]), i++)
    rc |= cuda_check(cudaMemcpyAsync(buf + off, st->dev[i], st->bytes[i], cudaMemcpyDeviceToHost),
                     "halo download");
  rc |= cuda_check(cudaStreamSynchronize(0), "halo download");
  for (int i = 0, off = 0; i < st->k && !rc; off += (int)padded(st->bytes[i]), i++)
    memcpy(st->host[i], buf + off, st->bytes[i]);
  return rc ? -1 : 0;
}

/* The host arrays -> pinned -> device (all copies queued, one wait before the buffer is reused). */
static int stage_up(struct cuda_sim *g, const struct stage *st) {
  size_t total = 0;
  for (int i = 0; i < st->k; i++) total += padded(st->bytes[i]);
  char *buf = cuda_pinned(g, total);
  if (!buf) return -1;
  int rc = cuda_check(cudaStreamSynchronize(0), "halo upload"); /* earlier copies are done */
  for (int i = 0, off = 0; i < st->k; off += (int)padded(st->bytes[i]), i++) {
    memcpy(buf + off, st->host[i], st->bytes[i]);
    rc |= cuda_check(cudaMemcpyAsync(st->dev[i], buf + off, st->bytes[i], cudaMemcpyHostToDevice),
                     "halo upload");
  }
  rc |= cuda_check(cudaStreamSynchronize(0), "halo upload");
  return rc ? -1 : 0;
}

/* Copy slots [off, off + n) of f into p's slots [p0, p0 + n) (id, species, x, v, f). */
static int fields_down(struct cuda_sim *g, const struct dev_fields *f, int off, int n,
                       particles_t *p, int p0, int with_f) {
  struct stage st = {0, {0}, {0}, {0}};
  stage_add(&st, p->id + p0, f->id + off, (size_t)n * 8);
  stage_add(&st, p->species + p0, f->species + off, (size_t)n * 4);
  for (int d = 0; d < 3; d++) {
    stage_add(&st, p->x[d] + p0, f->x[d] + off, (size_t)n * 8);
    stage_add(&st, p->v[d] + p0, f->v[d] + off, (size_t)n * 8);
    if (with_f) stage_add(&st, p->f[d] + p0, f->f[d] + off, (size_t)n * 8);
  }
  return stage_down(g, &st);
}

/* Leavers: owned particles outside this rank's subdomain (k_cell_keys' sentinel test, so the sort
 * phase puts exactly these last). */
__global__ void k_leaver_flags(const struct dev_params q, int n, const double *__restrict__ x,
                               const double *__restrict__ y, const double *__restrict__ z,
                               int *flag) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  flag[i] = !(x[i] >= q.sub_lo[0] && x[i] < q.sub_hi[0] && y[i] >= q.sub_lo[1] &&
              y[i] < q.sub_hi[1] && z[i] >= q.sub_lo[2] && z[i] < q.sub_hi[2]);
}

/* dst[k] = the particle perm[k], every field with the forces (the leavers' staging). */
__global__ void k_leaver_gather(int m, const int *__restrict__ perm, struct dev_fields src,
                                struct dev_fields dst) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= m) return;
  const int i = perm[k];
  dst.id[k] = src.id[i];
  dst.species[k] = src.species[i];
  for (int d = 0; d < 3; d++) {
    dst.x[d][k] = src.x[d][i];
    dst.v[d][k] = src.v[d][i];
    dst.f[d][k] = src.f[d][i];
  }
}

/* The leavers' slots (slot order) into perm[0, count) without moving anyone, their count left on
 * the device in g->counter: they stay in their slots, counted in n, until the sort phase puts them
 * last and drops them (cuda_halo_resort), so a step sorts the owned particles once. */
int cuda_leavers_select(struct cuda_sim *g) {
  const int n = g->n;
  if (!g->leaver_flags_ready) /* (set-up: no kick-drift before this migration) */
    k_leaver_flags<<<blocks_of(n), CUDA_BLOCK>>>(g->prm, n, g->a.x[0], g->a.x[1], g->a.x[2],
                                                 g->iota);
  g->leaver_flags_ready = 0;
  return cuda_select_slots(g, g->iota, g->perm, g->counter, n, "leaver selection");
}

extern "C" int cuda_halo_find_leavers(cuda_sim_t *g, int *m) {
  *m = 0;
  g->n_leaving = 0;
  if (g->n == 0) return 0;
  if (cuda_leavers_select(g) || cuda_counts_down(g, m, g->counter, 1, "leaver selection"))
    return -1;
  g->n_leaving = *m;
  return 0;
}

/* out must have room for m particles. */
extern "C" int cuda_halo_take_leavers(cuda_sim_t *g, int m, particles_t *out) {
  out->n_local = m;
  out->n_ghost = 0;
  if (m == 0) return 0;
  k_leaver_gather<<<blocks_of(m), CUDA_BLOCK>>>(m, g->perm, g->a, g->b);
  return fields_down(g, &g->b, 0, m, out, 0, 1);
}

extern "C" int cuda_halo_add_owned(cuda_sim_t *g, const particles_t *in) {
  const int m = in->n_local, n0 = g->n;
  if (cuda_grow(g, n0 + m)) return -1;
  struct stage st = {0, {0}, {0}, {0}};
  stage_add(&st, in->id, g->a.id + n0, (size_t)m * 8);
  stage_add(&st, in->species, g->a.species + n0, (size_t)m * 4);
  for (int d = 0; d < 3; d++) {
    stage_add(&st, in->x[d], g->a.x[d] + n0, (size_t)m * 8);
    stage_add(&st, in->v[d], g->a.v[d] + n0, (size_t)m * 8);
    stage_add(&st, in->f[d], g->a.f[d] + n0, (size_t)m * 8);
  }
  const int rc = m > 0 ? stage_up(g, &st) : 0;
  g->n = n0 + m;
  return rc ? -1 : 0;
}

/* The one sort of the owned particles in a step: by bin, the leavers (outside the subdomain:
 * sentinel bin) last, then dropped. The forces move with the particles only where they are read
 * before the force pass rewrites them: by the prediction (Groot-Warren lambda != 1/2), or kept
 * from a checkpoint at set-up (keep_forces). */
extern "C" int cuda_halo_resort(cuda_sim_t *g, int keep_forces) {
  if (cuda_sort_cells(g, g->prm.use_vpred || keep_forces, 0)) return -1;
  g->n -= g->n_leaving;
  g->n_leaving = 0;
  return 0;
}

extern "C" int cuda_halo_boundary(cuda_sim_t *g, particles_t *hb) {
  const int n = g->n;
  int nb = 0;
  hb->n_local = hb->n_ghost = 0;
  g->n_ghost = 0;
  if (n == 0) return 0;
  if (cuda_check(cudaMemset(g->counter, 0, sizeof(int)), "boundary")) return -1;
  k_boundary_keys<<<blocks_of(n), CUDA_BLOCK>>>(g->prm, n, g->a, g->key, g->iota, g->counter);
  size_t tmp = g->sort_tmp_bytes;
  /* Sorted keys go to nbr_count (scratch here; the density pass rewrites it): key_sorted holds the
   * bins of the owned particles, which the pair passes still need. */
  if (cuda_check(cub::DeviceRadixSort::SortPairs(g->sort_tmp, tmp, g->key, (uint32_t *)g->nbr_count,
                                                 g->iota, g->perm, n, 0, 1),
                 "boundary sort") ||
      down(&nb, g->counter, sizeof(int)))
    return -1;
  g->n_boundary = nb;
  if (nb == 0) return 0;
  k_boundary_gather<<<blocks_of(nb), CUDA_BLOCK>>>(nb, g->perm, g->a, g->b, g->prm.use_vpred);
  if (fields_down(g, &g->b, 0, nb, hb, 0, 0)) return -1;
  hb->n_local = nb;
  return 0;
}

extern "C" int cuda_halo_set_ghosts(cuda_sim_t *g, const particles_t *hb) {
  const int ng = hb->n_ghost, n0 = g->n, h0 = hb->n_local;
  if (n0 + ng > g->cap) {
    /* More ghosts than room: grow (after the interior pass in flight) and run this step's pair
     * passes in one part, since the interior lists went with the old arrays. */
    g->split_passes = 0;
    if (cuda_grow(g, n0 + ng)) return -1;
  }
  double *const *vel = g->prm.use_vpred ? g->b.vpred : g->b.v;
  struct stage st = {0, {0}, {0}, {0}};
  stage_add(&st, hb->id + h0, g->b.id + n0, (size_t)ng * 8);
  stage_add(&st, hb->species + h0, g->b.species + n0, (size_t)ng * 4);
  for (int d = 0; d < 3; d++) {
    stage_add(&st, hb->x[d] + h0, g->b.x[d] + n0, (size_t)ng * 8);
    stage_add(&st, hb->v[d] + h0, vel[d] + n0, (size_t)ng * 8);
  }
  const int rc = ng > 0 ? stage_up(g, &st) : 0;
  g->n_ghost = ng;
  return rc || cuda_sort_ghosts(g) ? -1 : 0;
}

extern "C" int cuda_halo_rho_out(cuda_sim_t *g, double *field) {
  const int nb = g->n_boundary;
  if (!g->prm.density || nb == 0) return 0;
  cuda_rho_gather(nb, g->perm, g->rho, g->rho_stage, 0);
  meso_real *tmp = (meso_real *)cuda_pinned(g, (size_t)nb * sizeof(meso_real));
  if (!tmp || down(tmp, g->rho_stage, (size_t)nb * sizeof(meso_real))) return -1;
  for (int k = 0; k < nb; k++) field[k] = (double)tmp[k];
  return 0;
}

extern "C" int cuda_halo_rho_in(cuda_sim_t *g, const double *ghost_rho) {
  const int ng = g->n_ghost;
  if (!g->prm.density || ng == 0) return 0;
  /* The interior force kernel may still run: wait for it before the buffer is rewritten. */
  if (cuda_check(cudaStreamSynchronize(0), "rho halo")) return -1;
  meso_real *tmp = (meso_real *)cuda_pinned(g, (size_t)ng * sizeof(meso_real));
  if (!tmp) return -1;
  for (int k = 0; k < ng; k++) tmp[k] = (meso_real)ghost_rho[k];
  if (cuda_check(
          cudaMemcpy(g->rho_stage, tmp, (size_t)ng * sizeof(meso_real), cudaMemcpyHostToDevice),
          "rho halo"))
    return -1;
  cuda_rho_scatter(g->n, ng, g->perm, g->rho_stage, g->rho, 0);
  return cuda_check(cudaGetLastError(), "rho halo");
}
