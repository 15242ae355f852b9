/* Device density pass of many-body DPD (Warren 2003): rho_i = sum_{j != i, r < rd} w_rho(r), the
 * Warren or Lucy kernel of meso/physics/density_kernels.h, self term excluded (physics.md 1). One
 * thread per particle; with one rank there are no ghosts, so no rho sync is needed. */
#include "cuda_neighbours.cuh"
#include "physics/density_kernels.h"

template <int KERNEL>
__global__ void __launch_bounds__(CUDA_BLOCK)
    k_density(const struct dev_params q, int n, const int *__restrict__ start,
              const struct dev_pos *__restrict__ pos, const uint32_t *__restrict__ key,
              meso_real *__restrict__ rho) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const struct dev_pos pi = pos[i];
  const struct dev_coef *row = q.coef[pi.species];
  meso_real sum = MESO_R(0.0);
  dev_for_each_neighbour(q, start, pos, pi, key[i],
                         [&](int t, const struct dev_pos &pj, meso_real dx, meso_real dy,
                             meso_real dz) {
                           const meso_real r2 = dx * dx + dy * dy + dz * dz;
                           if (r2 >= q.rd2_max || t == i) return; /* most candidates */
                           const struct dev_coef &c = row[pj.species];
                           if (r2 >= c.rd2) return;
                           const meso_real r = meso_sqrt(r2);
                           sum += KERNEL == MESO_KERNEL_LUCY ? w_rho_lucy_inv(r, c.inv_rd, c.wnorm)
                                                             : w_rho_warren_inv(r, c.inv_rd, c.wnorm);
                         });
  rho[i] = sum;
}

void cuda_density_pass(struct cuda_sim *g) {
  if (!g->prm.density || g->n == 0) return;
  const int blocks = (g->n + CUDA_BLOCK - 1) / CUDA_BLOCK;
  if (g->prm.kernel == MESO_KERNEL_LUCY)
    k_density<MESO_KERNEL_LUCY><<<blocks, CUDA_BLOCK>>>(g->prm, g->n, g->cell_start, g->pos,
                                                        g->key_sorted, g->rho);
  else
    k_density<MESO_KERNEL_WARREN><<<blocks, CUDA_BLOCK>>>(g->prm, g->n, g->cell_start, g->pos,
                                                          g->key_sorted, g->rho);
}
