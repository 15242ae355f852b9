/* The wall-field pass of wall_boundary (physics/wall_boundary.h; Li et al. 2018, physics.md
 * section 3): for every owned mobile particle, the wall volume fraction phi and its gradient from
 * the frozen particles within r_phi in its neighbour list. Frozen particles get phi = 0 (never
 * read). */
#include "cpu_passes.h"
#include "neighbour_bins.h"

#include <math.h>
#include "physics/pair_forces.h"
#include "physics/wall_boundary.h"

void cpu_wall_field_pass(const plan_t *plan, const particles_t *p, const cell_list_t *cl,
                         const nlist_t *nl, wall_field_t *field) {
  const wall_boundary_params_t *w = &plan->particle.wall_boundary;
  const int nslots = p->n_local + p->n_ghost;
#pragma omp parallel for schedule(static)
  for (int q = 0; q < nslots; q++) {
    const int i = cl->idx[q];
    if (i >= p->n_local) continue;
    const int si = p->species[i];
    double acc[WALL_FIELD_ACC] = {0, 0, 0, 0, 0, 0, 0, 0};
    if (plan->mobile[si]) {
      const double xi = cl->px[q], yi = cl->py[q], zi = cl->pz[q];
      const pair_coef_t *row = plan->coef[si];
      const int m = nl->count[i];
      const int *cand = nl->slot + (size_t)i * (size_t)nl->stride;
      for (int k = 0; k < m; k++) {
        const int t = cand[k];
        const pair_coef_t *c = &row[p->species[cl->idx[t]]];
        if (c->wall_phi2 == 0.0) continue; /* not a wall partner */
        const double dx = xi - cl->px[t], dy = yi - cl->py[t], dz = zi - cl->pz[t];
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 < c->wall_phi2) {
          const double weight = wall_field_add(w->inv_h, r2, dx, dy, dz, acc);
          if (w->moving) wall_field_add_velocity(w, p->species[cl->idx[t]], weight, acc);
        }
        if (r2 < c->rc2) { /* S_i of the stability cap: gamma w_D = gamma w_R^2 */
          const double wR = pair_weight_random_inv(sqrt(r2), c->inv_rc, c->s_exp, c->s_one);
          acc[4] += c->gamma * wR * wR;
        }
      }
    }
    field[i] = wall_field_finish(w, acc);
  }
}
