/* Device density pass of many-body DPD (Warren 2003): rho_i = sum_{j != i, r < rd} w_rho(r), the
 * Warren or Lucy kernel of meso/physics/density_kernels.h, self term excluded (physics.md 1). One
 * thread per particle; with one rank there are no ghosts, so no rho sync is needed.
 * The same bin scan writes each particle's neighbour list (partners within the largest cutoff, in
 * traversal order) for the force pass: the force kernel then runs only over partners in range, so a
 * warp does not pay the pair body for the ~85% of bin candidates that are out of range. */
#include "cuda_neighbours.cuh"
#include "physics/density_kernels.h"

#include <stdio.h>

template <int KERNEL, int DENSITY>
__global__ void __launch_bounds__(CUDA_BLOCK)
    k_density(const struct dev_params q, int n, int cap, int stride, const int *__restrict__ start,
              const int *__restrict__ gstart, const struct dev_pos *__restrict__ pos,
              const uint32_t *__restrict__ key, meso_real *__restrict__ rho,
              uint32_t *__restrict__ nbr, int *__restrict__ count, int *most) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const struct dev_pos pi = pos[i];
  const struct dev_coef *row = q.coef[pi.species];
  meso_real sum = MESO_R(0.0);
  int m = 0;
  dev_for_each_neighbour(
      q, start, gstart, n, pos, pi, key[i],
      [&](int t, int code, const struct dev_pos &pj, meso_real dx, meso_real dy, meso_real dz) {
        const meso_real r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= q.cut2_max || t == i) return; /* most candidates */
        if (m < stride) nbr[(size_t)m * cap + i] = (uint32_t)t | ((uint32_t)code << NBR_SLOT_BITS);
        m++;
        if (!DENSITY || r2 >= q.rd2_max) return;
        const struct dev_coef &c = row[pj.species];
        if (r2 >= c.rd2) return;
        const meso_real r = meso_sqrt(r2);
        sum += KERNEL == MESO_KERNEL_LUCY ? w_rho_lucy_inv(r, c.inv_rd, c.wnorm)
                                          : w_rho_warren_inv(r, c.inv_rd, c.wnorm);
      });
  if (DENSITY) rho[i] = sum;
  count[i] = m;
  if (m > stride) atomicMax(most, m);
}

template <int KERNEL, int DENSITY> static void launch(struct cuda_sim *g) {
  const int blocks = (g->n + CUDA_BLOCK - 1) / CUDA_BLOCK;
  k_density<KERNEL, DENSITY><<<blocks, CUDA_BLOCK>>>(
      g->prm, g->n, g->cap, g->nbr_stride, g->cell_start, g->prm.multi ? g->gcell_start : NULL,
      g->pos, g->key_sorted, g->rho, g->nbr, g->nbr_count, g->nbr_most);
}

/* Densities and lists; a list longer than the room it had grows the room and runs the pass again
 * (one small device-to-host copy per step tells). */
int cuda_density_pass(struct cuda_sim *g) {
  if (!g->prm.terms || g->n == 0) return 0;
  if (g->nbr_stride == 0 && cuda_nbr_reserve(g, 48)) return -1;
  for (;;) {
    if (cuda_check(cudaMemsetAsync(g->nbr_most, 0, sizeof(int)), "density pass")) return -1;
    if (!g->prm.density)
      launch<MESO_KERNEL_WARREN, 0>(g);
    else if (g->prm.kernel == MESO_KERNEL_LUCY)
      launch<MESO_KERNEL_LUCY, 1>(g);
    else
      launch<MESO_KERNEL_WARREN, 1>(g);
    int most = 0;
    if (cuda_check(cudaMemcpy(&most, g->nbr_most, sizeof(int), cudaMemcpyDeviceToHost),
                   "density pass"))
      return -1;
    if (most == 0) return 0;
    if (cuda_nbr_reserve(g, most + most / 4 + 8)) return -1;
  }
}
