/* Device wall-field pass of wall_boundary (physics/wall_boundary.h; Li et al. 2018, physics.md
 * section 3): phi_i and grad phi_i of every owned mobile particle from the frozen partners within
 * r_phi in its neighbour list of this step, the same sums as backend/cpu/wall_field_pass.c (in the
 * pair math's precision). Runs after the list scan of the neighbour phase, before any force launch;
 * the force pass reads phi_i (no slip) and the next kick_drift kernel the whole field
 * (reflection). */
#include "cuda_neighbours.cuh"
#include "physics/pair_forces.h"
#include "physics/wall_boundary.h"

/* LISTS 0: the compact memory mode (the bins scanned again, in the lists' order). */
template <int LISTS>
__global__ void __launch_bounds__(CUDA_BLOCK)
    k_wall_field(const struct dev_params q, int n, int cap, const struct dev_pos *__restrict__ pos,
                 const uint32_t *__restrict__ nbr, const int *__restrict__ count,
                 const int *__restrict__ start, const int *__restrict__ gstart,
                 const uint32_t *__restrict__ key, wall_field_t *__restrict__ field) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const struct dev_pos pi = pos[i];
  const struct dev_coef *row = q.coef[pi.species];
  const wall_boundary_params_t *w = &q.pe.wall_boundary;
  const meso_real inv_h = (meso_real)w->inv_h;
  meso_real acc[WALL_FIELD_ACC] = {0, 0, 0, 0, 0, 0, 0, 0};
  const auto partner = [&](const struct dev_pos &pj, meso_real dx, meso_real dy, meso_real dz) {
    const struct dev_coef &c = row[pj.species];
    if (c.wall_phi2 == MESO_R(0.0)) return; /* not a wall partner */
    const meso_real r2 = dx * dx + dy * dy + dz * dz;
    if (r2 < c.wall_phi2) {
      const meso_real weight = wall_field_add(inv_h, r2, dx, dy, dz, acc);
      if (w->moving) wall_field_add_velocity(w, pj.species, weight, acc);
    }
    if (r2 < c.rc2) { /* S_i of the stability cap */
      const meso_real wR = pair_weight_random_inv(meso_sqrt(r2), c.inv_rc, c.s_exp, c.s_one);
      acc[4] += c.gamma * wR * wR;
    }
  };
  if (LISTS) {
    const int m = q.mobile[pi.species] ? count[i] : 0;
    nbr_for_each(nbr, i, m, cap, [&](uint32_t e) {
      const struct dev_pos pj = pos[e & ((1u << NBR_SLOT_BITS) - 1)];
      meso_real dx, dy, dz;
      dev_offset_sep(q, pi, pj, e >> NBR_SLOT_BITS, &dx, &dy, &dz);
      partner(pj, dx, dy, dz);
    });
  } else if (q.mobile[pi.species]) {
    dev_for_each_neighbour(
        q, start, gstart, n, pos, pi, key[i],
        [&](int t, int code, const struct dev_pos &pj, meso_real dx, meso_real dy, meso_real dz) {
          (void)code;
          /* the lists hold the partners within the largest cutoff */
          if (t != i && dx * dx + dy * dy + dz * dz < q.list_cut2) partner(pj, dx, dy, dz);
        },
        q.scan_cut2);
  }
  field[i] = wall_field_finish(w, acc);
}

void cuda_wall_field(struct cuda_sim *g) {
  if (!g->wall_field || g->n == 0) return;
  const int blocks = (g->n + CUDA_BLOCK - 1) / CUDA_BLOCK;
  if (g->compact)
    k_wall_field<0><<<blocks, CUDA_BLOCK>>>(g->prm, g->n, g->cap, g->pos, NULL, NULL, g->cell_start,
                                            g->prm.multi ? g->gcell_start : NULL, g->key_sorted,
                                            g->wall_field);
  else
    k_wall_field<1><<<blocks, CUDA_BLOCK>>>(g->prm, g->n, g->cap, g->pos, g->nbr, g->nbr_count,
                                            NULL, NULL, NULL, g->wall_field);
}
