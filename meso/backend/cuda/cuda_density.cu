/* Device density pass of many-body DPD (Warren 2003): rho_i = sum_{j != i, r < rd} w_rho(r), the
 * Warren or Lucy kernel of meso/physics/density_kernels.h, self term excluded (physics.md 1). One
 * thread per particle; with one rank there are no ghosts, so no rho sync is needed. */
#include "cuda_neighbours.cuh"
#include "physics/density_kernels.h"

template <int KERNEL>
__global__ void __launch_bounds__(CUDA_BLOCK)
    k_density(const struct dev_params q, int n, const int *__restrict__ start,
              const double *__restrict__ x, const double *__restrict__ y,
              const double *__restrict__ z, const int32_t *__restrict__ species,
              meso_real *__restrict__ rho) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const struct dev_coef *row = q.coef[species[i]];
  meso_real sum = MESO_R(0.0);
  dev_for_each_neighbour(q, start, x, y, z, x[i], y[i], z[i],
                         [&](int t, double dxd, double dyd, double dzd) {
                           const meso_real dx = (meso_real)dxd, dy = (meso_real)dyd,
                                           dz = (meso_real)dzd;
                           const meso_real r2 = dx * dx + dy * dy + dz * dz;
                           const struct dev_coef &c = row[species[t]];
                           if (t == i || r2 >= c.rd2) return;
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
    k_density<MESO_KERNEL_LUCY><<<blocks, CUDA_BLOCK>>>(g->prm, g->n, g->cell_start, g->a.x[0],
                                                        g->a.x[1], g->a.x[2], g->a.species, g->rho);
  else
    k_density<MESO_KERNEL_WARREN><<<blocks, CUDA_BLOCK>>>(g->prm, g->n, g->cell_start, g->a.x[0],
                                                          g->a.x[1], g->a.x[2], g->a.species,
                                                          g->rho);
}
