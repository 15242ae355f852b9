/* Density pass of many-body DPD (Warren 2003): rho_i = sum_{j != i, r < rd} w_rho(r; rd), with the
 * Warren or the Lucy kernel (meso/physics/density_kernels.h). Self term excluded (physics.md 1). */
#include "cpu_passes.h"
#include "neighbour_bins.h"
#include "physics/density_kernels.h"

#include <math.h>

/* rho of owned particle i (slot q in bin order); kernel is a compile-time constant after inlining.
 */
/* rho of owned particle i (slot q in bin order); kernel is a compile-time constant after inlining.
 * Only the near part of the neighbour list (within the row's largest rd) is visited. */
static inline __attribute__((always_inline)) double
density_of(const plan_t *plan, const particles_t *p, const cell_list_t *cl, int q, int i,
           const nlist_t *nl, const int kernel) {
  const double xi = cl->px[q], yi = cl->py[q], zi = cl->pz[q];
  const pair_coef_t *row = plan->coef[p->species[i]];
  const int m = nl->count_near[i];
  const int *cand = nl->slot + (size_t)i * (size_t)nl->stride;
  double sum = 0.0;
  for (int k = 0; k < m; k++) {
    const int t = cand[k], j = cl->idx[t];
    const double dx = xi - cl->px[t], dy = yi - cl->py[t], dz = zi - cl->pz[t];
    const double r2 = dx * dx + dy * dy + dz * dz;
    const pair_coef_t *c = &row[p->species[j]];
    if (r2 >= c->rd2) continue; /* species-dependent rd only */
    const double r = sqrt(r2);
    sum += kernel == MESO_KERNEL_LUCY ? w_rho_lucy_inv(r, c->inv_rd, c->wnorm)
                                      : w_rho_warren_inv(r, c->inv_rd, c->wnorm);
  }
  return sum;
}

#define DENSITY_LOOP(KERNEL)                                                                       \
  _Pragma("omp parallel for schedule(static)") for (int q = 0; q < nslots; q++) {                  \
    const int i = cl->idx[q];                                                                      \
    if (i < p->n_local) p->rho[i] = density_of(plan, p, cl, q, i, nl, KERNEL);                     \
  }

void cpu_density_pass(const plan_t *plan, particles_t *p, const cell_list_t *cl,
                      const nlist_t *nl) {
  const int nslots = p->n_local + p->n_ghost;
  if (plan->density_kernel == MESO_KERNEL_LUCY)
    DENSITY_LOOP(MESO_KERNEL_LUCY)
  else
    DENSITY_LOOP(MESO_KERNEL_WARREN)
}
