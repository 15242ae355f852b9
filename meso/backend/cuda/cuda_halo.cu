/* Several ranks, one GPU each: the device side of migration, ghosts and the density halo. Only the
 * particles that cross or border a face travel through the host (plain host copies; Open MPI 4.1 on
 * the GPU machines is not CUDA-aware); the host side reuses the CPU path's exchanges
 * (migrate_particles, ghosts_build, ghosts_sync_scalar) on those few particles, so the images, the
 * stages and the messages are the CPU path's. Owned particles come first in bin order, then the
 * ghosts in bin order (their own bin starts, gcell_start). */
#include "cuda_state.cuh"

#include <stdlib.h>

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

static int down(void *dst, const void *src, size_t bytes) {
  return cuda_check(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToHost), "halo download");
}

static int up(void *dst, const void *src, size_t bytes) {
  return cuda_check(cudaMemcpy(dst, src, bytes, cudaMemcpyHostToDevice), "halo upload");
}

/* Copy slots [off, off + n) of f into p's slots [p0, p0 + n) (id, species, x, v, f). */
static int fields_down(const struct dev_fields *f, int off, int n, particles_t *p, int p0,
                       int with_f) {
  int rc = down(p->id + p0, f->id + off, (size_t)n * 8) |
           down(p->species + p0, f->species + off, (size_t)n * 4);
  for (int d = 0; d < 3; d++) {
    rc |= down(p->x[d] + p0, f->x[d] + off, (size_t)n * 8) |
          down(p->v[d] + p0, f->v[d] + off, (size_t)n * 8);
    if (with_f) rc |= down(p->f[d] + p0, f->f[d] + off, (size_t)n * 8);
  }
  return rc ? -1 : 0;
}

extern "C" int cuda_halo_sort_owned(cuda_sim_t *g, int *n_stay) {
  if (cuda_sort_cells(g)) return -1;
  *n_stay = g->n;
  if (g->n == 0) return 0;
  return down(n_stay, g->cell_start + g->prm.ncell, sizeof(int));
}

/* out must have room for n - n_stay particles. */
extern "C" int cuda_halo_take_leavers(cuda_sim_t *g, int n_stay, particles_t *out) {
  const int m = g->n - n_stay;
  out->n_local = m;
  out->n_ghost = 0;
  if (m > 0 && fields_down(&g->a, n_stay, m, out, 0, 1)) return -1;
  g->n = n_stay;
  return 0;
}

extern "C" int cuda_halo_add_owned(cuda_sim_t *g, const particles_t *in) {
  const int m = in->n_local, n0 = g->n;
  if (n0 + m > g->cap) {
    fprintf(stderr, "mdpore: CUDA backend: %d particles arrive on a GPU with room for %d\n", n0 + m,
            g->cap);
    return -1;
  }
  int rc =
      up(g->a.id + n0, in->id, (size_t)m * 8) | up(g->a.species + n0, in->species, (size_t)m * 4);
  for (int d = 0; d < 3; d++)
    rc |= up(g->a.x[d] + n0, in->x[d], (size_t)m * 8) |
          up(g->a.v[d] + n0, in->v[d], (size_t)m * 8) | up(g->a.f[d] + n0, in->f[d], (size_t)m * 8);
  g->n = n0 + m;
  return rc ? -1 : 0;
}

extern "C" int cuda_halo_resort(cuda_sim_t *g) {
  return cuda_sort_cells(g);
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
  if (fields_down(&g->b, 0, nb, hb, 0, 0)) return -1;
  hb->n_local = nb;
  return 0;
}

extern "C" int cuda_halo_set_ghosts(cuda_sim_t *g, const particles_t *hb) {
  const int ng = hb->n_ghost, n0 = g->n, h0 = hb->n_local;
  if (n0 + ng > g->cap) {
    fprintf(stderr,
            "mdpore: CUDA backend: %d owned + %d ghost particles on a GPU with room for %d\n", n0,
            ng, g->cap);
    return -1;
  }
  double *const *vel = g->prm.use_vpred ? g->b.vpred : g->b.v;
  int rc = up(g->b.id + n0, hb->id + h0, (size_t)ng * 8) |
           up(g->b.species + n0, hb->species + h0, (size_t)ng * 4);
  for (int d = 0; d < 3; d++)
    rc |= up(g->b.x[d] + n0, hb->x[d] + h0, (size_t)ng * 8) |
          up(vel[d] + n0, hb->v[d] + h0, (size_t)ng * 8);
  g->n_ghost = ng;
  return rc || cuda_sort_ghosts(g) ? -1 : 0;
}

extern "C" int cuda_halo_rho_out(cuda_sim_t *g, double *field) {
  const int nb = g->n_boundary;
  if (!g->prm.density || nb == 0) return 0;
  k_rho_gather<<<blocks_of(nb), CUDA_BLOCK>>>(nb, g->perm, g->rho, g->rho_stage);
  meso_real *tmp = (meso_real *)malloc((size_t)nb * sizeof(meso_real));
  if (!tmp) return -1;
  const int rc = down(tmp, g->rho_stage, (size_t)nb * sizeof(meso_real));
  for (int k = 0; k < nb; k++) field[k] = (double)tmp[k];
  free(tmp);
  return rc;
}

extern "C" int cuda_halo_rho_in(cuda_sim_t *g, const double *ghost_rho) {
  const int ng = g->n_ghost;
  if (!g->prm.density || ng == 0) return 0;
  meso_real *tmp = (meso_real *)malloc((size_t)ng * sizeof(meso_real));
  if (!tmp) return -1;
  for (int k = 0; k < ng; k++) tmp[k] = (meso_real)ghost_rho[k];
  const int rc = up(g->rho_stage, tmp, (size_t)ng * sizeof(meso_real));
  free(tmp);
  if (rc) return -1;
  k_rho_scatter<<<blocks_of(ng), CUDA_BLOCK>>>(g->n, ng, g->perm, g->rho_stage, g->rho);
  return cuda_check(cudaGetLastError(), "rho halo");
}
