/* Density pass of many-body DPD (Warren 2003): rho_i = sum_{j != i, r < rd} w_rho(r; rd), with the
 * Warren or the Lucy kernel (meso/physics/density_kernels.h). Self term excluded (physics.md 1). */
#include "cpu_passes.h"
#include "neighbour_bins.h"
#include "physics/density_kernels.h"

#include <math.h>

static inline __attribute__((always_inline)) void
density_loop(const plan_t *plan, particles_t *p, const cell_list_t *cl, const int kernel) {
  double cut2[SCENE_MAX_SPECIES] = {0};
  for (int a = 0; a < plan->n_species; a++)
    for (int b = 0; b < plan->n_species; b++)
      if (plan->coef[a][b].rd2 > cut2[a]) cut2[a] = plan->coef[a][b].rd2;
  const int nslots = p->n_local + p->n_ghost;
  const int n_local = p->n_local;
  const int32_t *species = p->species;
  double *rho = p->rho;
#pragma omp parallel for schedule(static)
  for (int q = 0; q < nslots; q++) {
    const int i = cl->idx[q];
    if (i >= n_local) continue;
    const double xi = cl->px[q], yi = cl->py[q], zi = cl->pz[q];
    const pair_coef_t *row = plan->coef[species[i]];
    const double cmax = cut2[species[i]];
    int lo[9], hi[9];
    const int nrows = neighbour_rows(cl, cl->cell_of[i], lo, hi);
    double sum = 0.0;
    for (int r = 0; r < nrows; r++)
      for (int t = lo[r]; t < hi[r]; t++) {
        const double dx = xi - cl->px[t], dy = yi - cl->py[t], dz = zi - cl->pz[t];
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= cmax) continue;
        const int j = cl->idx[t];
        const pair_coef_t *c = &row[species[j]];
        if (r2 >= c->rd2 || j == i) continue;
        const double dist = sqrt(r2);
        sum += kernel == MESO_KERNEL_LUCY ? w_rho_lucy(dist, c->rd) : w_rho_warren(dist, c->rd);
      }
    rho[i] = sum;
  }
}

void cpu_density_pass(const plan_t *plan, particles_t *p, const cell_list_t *cl) {
  if (plan->density_kernel == MESO_KERNEL_LUCY)
    density_loop(plan, p, cl, MESO_KERNEL_LUCY);
  else
    density_loop(plan, p, cl, MESO_KERNEL_WARREN);
}
