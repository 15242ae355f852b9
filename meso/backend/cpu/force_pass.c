/* The fused pair-force kernel: one loop over neighbours evaluating the pair terms the plan selects
 * (physics.md section 1, paper eq. 1):
 *   F_ij = [ A w_c + B (rho_i + rho_j) w_d ] e - gamma w_R^2 (e . v_ij) e + sigma w_R xi_ij /
 * sqrt(dt) e The term set is a compile-time constant of each specialised copy (force_loop is
 * inlined with constant flags), so unused terms cost nothing. From j's side the same pair sees
 * exactly negated r_ij and v_ij and the same rho_i + rho_j, so F_ji = -F_ij bitwise and momentum is
 * conserved to rounding. */
#include "cpu_passes.h"
#include "neighbour_bins.h"
#include "physics/pair_forces.h"
#include "physics/pair_random.h"

#include <math.h>

static inline __attribute__((always_inline)) void force_loop(const plan_t *plan, particles_t *p,
                                                             const cell_list_t *cl,
                                                             force_pass_args_t *a, const int terms,
                                                             const int per_virial) {
  double cut2[SCENE_MAX_SPECIES] = {0};
  for (int s = 0; s < plan->n_species; s++)
    for (int b = 0; b < plan->n_species; b++)
      if (plan->coef[s][b].cut2 > cut2[s]) cut2[s] = plan->coef[s][b].cut2;
  const int nslots = p->n_local + p->n_ghost, n_local = p->n_local;
  const int32_t *species = p->species;
  const int64_t *id = p->id;
  const double *rho = p->rho;
  const double *vx = p->vpred[0] ? p->vpred[0] : p->v[0];
  const double *vy = p->vpred[1] ? p->vpred[1] : p->v[1];
  const double *vz = p->vpred[2] ? p->vpred[2] : p->v[2];
  double *fx = p->f[0], *fy = p->f[1], *fz = p->f[2], *pv = p->virial;
  const uint64_t seed = a->seed, step = a->step;
  const double inv_sqrt_dt = 1.0 / sqrt(a->dt), s_exp = plan->weight_exp;
  const int s_one = plan->weight_exp_is_one;
  double wxx = 0, wyy = 0, wzz = 0, wxy = 0, wxz = 0, wyz = 0;
#pragma omp parallel for schedule(static) reduction(+ : wxx, wyy, wzz, wxy, wxz, wyz)
  for (int q = 0; q < nslots; q++) {
    const int i = cl->idx[q];
    if (i >= n_local) continue;
    const double xi = cl->px[q], yi = cl->py[q], zi = cl->pz[q];
    const int si = species[i];
    const pair_coef_t *row = plan->coef[si];
    const double cmax = cut2[si];
    const double rho_i = (terms & PAIR_TERM_MANYBODY) ? rho[i] : 0.0;
    const double vxi = vx[i], vyi = vy[i], vzi = vz[i];
    const int64_t id_i = id[i];
    int lo[9], hi[9];
    const int nrows = neighbour_rows(cl, cl->cell_of[i], lo, hi);
    double sfx = 0, sfy = 0, sfz = 0;
    double vxx = 0, vyy = 0, vzz = 0, vxy = 0, vxz = 0, vyz = 0;
    for (int r = 0; r < nrows; r++)
      for (int t = lo[r]; t < hi[r]; t++) {
        const double dx = xi - cl->px[t], dy = yi - cl->py[t], dz = zi - cl->pz[t];
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= cmax || r2 == 0.0) continue; /* r2 == 0: i itself (no direction, no force) */
        const int j = cl->idx[t];
        const pair_coef_t *c = &row[species[j]];
        if (r2 >= c->cut2) continue;
        const double dist = sqrt(r2), inv_r = 1.0 / dist;
        double fp = 0.0; /* magnitude along e = r_ij / r */
        if ((terms & PAIR_TERM_CONSERVATIVE) && r2 < c->rc2)
          fp += pair_conservative_inv(c->A, dist, c->inv_rc);
        if ((terms & PAIR_TERM_MANYBODY) && r2 < c->rd2)
          fp += pair_manybody_inv(c->B, rho_i + rho[j], dist, c->inv_rd);
        if ((terms & PAIR_TERM_THERMOSTAT) && r2 < c->rc2) {
          const double wR = pair_weight_random_inv(dist, c->inv_rc, s_exp, s_one);
          const double e_dot_v =
              (dx * (vxi - vx[j]) + dy * (vyi - vy[j]) + dz * (vzi - vz[j])) * inv_r;
          const double xi_ij = pair_random_xi(seed, step, id_i, id[j]);
          fp += pair_thermostat(c->gamma, c->sigma, wR, e_dot_v, xi_ij, inv_sqrt_dt);
        }
        const double s = fp * inv_r;
        sfx += s * dx;
        sfy += s * dy;
        sfz += s * dz;
        /* Virial r_ij (x) F_ij = s r_ij (x) r_ij, halved: each pair is seen from both sides. */
        const double hs = 0.5 * s;
        vxx += hs * dx * dx;
        vyy += hs * dy * dy;
        vzz += hs * dz * dz;
        vxy += hs * dx * dy;
        vxz += hs * dx * dz;
        vyz += hs * dy * dz;
      }
    fx[i] = sfx;
    fy[i] = sfy;
    fz[i] = sfz;
    if (per_virial) {
      double *w = pv + 6 * (size_t)i;
      w[0] = vxx, w[1] = vyy, w[2] = vzz, w[3] = vxy, w[4] = vxz, w[5] = vyz;
    }
    wxx += vxx, wyy += vyy, wzz += vzz, wxy += vxy, wxz += vxz, wyz += vyz;
  }
  a->virial[0] = wxx, a->virial[1] = wyy, a->virial[2] = wzz;
  a->virial[3] = wxy, a->virial[4] = wxz, a->virial[5] = wyz;
}

/* One specialised copy per (term set, per-particle virial). */
#define FORCE_CASE(T)                                                                              \
  case T:                                                                                          \
    if (per_virial)                                                                                \
      force_loop(plan, p, cl, a, T, 1);                                                            \
    else                                                                                           \
      force_loop(plan, p, cl, a, T, 0);                                                            \
    break;

void cpu_force_pass(const plan_t *plan, particles_t *p, const cell_list_t *cl,
                    force_pass_args_t *a) {
  const int per_virial = a->per_particle_virial && p->virial != NULL;
  switch (plan->pair_terms & 7) {
    FORCE_CASE(0)
    FORCE_CASE(1)
    FORCE_CASE(2)
    FORCE_CASE(3)
    FORCE_CASE(4)
    FORCE_CASE(5)
    FORCE_CASE(6)
    FORCE_CASE(7)
  }
}
