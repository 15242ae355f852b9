/* The fused pair-force kernel: one loop over neighbours evaluating the pair terms the plan selects
 * (physics.md section 1, paper eq. 1):
 *   F_ij = [ A w_c + B (rho_i + rho_j) w_d ] e - gamma w_R^2 (e . v_ij) e + sigma w_R xi_ij /
 * sqrt(dt) e The term set is a compile-time constant of each specialised copy (force_loop is
 * inlined with constant flags), so unused terms cost nothing; so is the generator of xi_ij
 * (plan.pair_rng, dpd_thermostat's option rng): the default Philox4x32-10 path has no test per
 * pair. From j's side the same pair sees
 * exactly negated r_ij and v_ij and the same rho_i + rho_j, so F_ji = -F_ij bitwise and momentum is
 * conserved to rounding. */
#include "cpu_passes.h"
#include "neighbour_bins.h"
#include "physics/pair_forces.h"
#include "physics/pair_random.h"
#include "physics/wall_boundary.h"

#include <math.h>

typedef struct {
  const double *vx, *vy, *vz; /* velocities the thermostat sees (predicted when allocated) */
  double inv_sqrt_dt;
} force_consts_t;

/* Force (and virial) on owned particle i at bin slot q. terms, per_virial and rng (enum pair_rng)
 * are compile-time constants after inlining; w accumulates this thread's global virial. */
static inline __attribute__((always_inline)) void
force_on(const plan_t *plan, particles_t *p, const cell_list_t *cl, const force_pass_args_t *a,
         const force_consts_t *k, int q, int i, const nlist_t *nl, double w[6], const int terms,
         const int per_virial, const int rng) {
  const double xi = cl->px[q], yi = cl->py[q], zi = cl->pz[q];
  const int si = p->species[i];
  const pair_coef_t *row = plan->coef[si];
  if (!plan->mobile[si]) { /* frozen: never integrated, so its force is not needed; the pairs
                              with mobile partners are evaluated from their side */
    p->f[0][i] = p->f[1][i] = p->f[2][i] = 0.0;
    if (per_virial)
      for (int c6 = 0; c6 < 6; c6++) p->virial[6 * (size_t)i + c6] = 0.0;
    return;
  }
  const double rho_i = (terms & PAIR_TERM_MANYBODY) ? p->rho[i] : 0.0;
  const double vxi = k->vx[i], vyi = k->vy[i], vzi = k->vz[i];
  /* wall_boundary's no slip: Li's ratio(phi_i), capped for stability, for the thermostat of the
   * pairs with wall particles (physics/wall_boundary.h; computed by the wall-field pass) */
  double wall_ratio = 1.0, wall_sqrt_ratio = 1.0;
  if (terms & PAIR_TERM_WALL_NO_SLIP) {
    wall_ratio = plan->particle.wall_boundary.field[i].ratio;
    wall_sqrt_ratio = plan->particle.wall_boundary.field[i].sqrt_ratio;
  }
  const int64_t id_i = p->id[i];
  const uint64_t seed = a->seed, step = a->step; /* the generator's key: loop-invariant */
  const int m = nl->count[i], m_near = nl->count_near[i];
  const int *cand = nl->slot + (size_t)i * (size_t)nl->stride;
  double sfx = 0, sfy = 0, sfz = 0;
  double vxx = 0, vyy = 0, vzz = 0, vxy = 0, vxz = 0, vyz = 0;
  /* Near part (within rd: all terms), then far part (no many-body term). */
  for (int n = 0; n < m; n++) {
    const int near = (terms & PAIR_TERM_MANYBODY) && n < m_near;
    const int t = cand[n];
    const double dx = xi - cl->px[t], dy = yi - cl->py[t], dz = zi - cl->pz[t];
    const double r2 = dx * dx + dy * dy + dz * dz;
    const int j = cl->idx[t];
    const pair_coef_t *c = &row[p->species[j]];
    if (r2 >= c->cut2 || r2 == 0.0) continue; /* r2 == 0: coincident particles (no direction) */
    const double dist = sqrt(r2), inv_r = 1.0 / dist;
    double fp = 0.0; /* magnitude along e = r_ij / r */
    if ((terms & PAIR_TERM_CONSERVATIVE) && r2 < c->rc2)
      fp += pair_conservative_inv(c->A, dist, c->inv_rc);
    if (near && r2 < c->rd2) fp += pair_manybody_inv(c->B, rho_i + p->rho[j], dist, c->inv_rd);
    if ((terms & PAIR_TERM_THERMOSTAT) && r2 < c->rc2) {
      const double wR = pair_weight_random_inv(dist, c->inv_rc, c->s_exp, c->s_one);
      const double e_dot_v =
          (dx * (vxi - k->vx[j]) + dy * (vyi - k->vy[j]) + dz * (vzi - k->vz[j])) * inv_r;
      const double xi_ij = pair_random_xi_rng(rng, seed, step, id_i, p->id[j]);
      const int wall = (terms & PAIR_TERM_WALL_NO_SLIP) && c->wall_phi2 > 0.0;
      fp += pair_thermostat(wall ? wall_ratio * c->gamma : c->gamma,
                            wall ? wall_sqrt_ratio * c->sigma : c->sigma, wR, e_dot_v, xi_ij,
                            k->inv_sqrt_dt);
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
  p->f[0][i] = sfx;
  p->f[1][i] = sfy;
  p->f[2][i] = sfz;
  if (per_virial) {
    double *pv = p->virial + 6 * (size_t)i;
    pv[0] = vxx, pv[1] = vyy, pv[2] = vzz, pv[3] = vxy, pv[4] = vxz, pv[5] = vyz;
  }
  w[0] += vxx, w[1] += vyy, w[2] += vzz, w[3] += vxy, w[4] += vxz, w[5] += vyz;
}

/* One parallel loop per (term set, per-particle virial, generator): the outlined OpenMP function
 * of each copy sees constant flags, so unused terms are compiled out. Threads add their virial in
 * a critical section (the global virial only feeds thermo output, never the dynamics). */
#define FORCE_LOOP(T, V, R)                                                                        \
  _Pragma("omp parallel") {                                                                        \
    double w[6] = {0, 0, 0, 0, 0, 0};                                                              \
    _Pragma("omp for schedule(static)") for (int q = 0; q < nslots; q++) {                         \
      const int i = cl->idx[q];                                                                    \
      if (i < p->n_local) force_on(plan, p, cl, a, &k, q, i, nl, w, T, V, R);                      \
    }                                                                                              \
    _Pragma("omp critical") for (int c = 0; c < 6; c++) a->virial[c] += w[c];                      \
  }

#define FORCE_VIRIAL(T, R)                                                                         \
  if (per_virial)                                                                                  \
    FORCE_LOOP(T, 1, R)                                                                            \
  else                                                                                             \
    FORCE_LOOP(T, 0, R)

/* A term set without the thermostat draws no random numbers: one copy. */
#define FORCE_CASE(T)                                                                              \
  case T:                                                                                          \
    FORCE_VIRIAL(T, PAIR_RNG_PHILOX)                                                               \
    break;

/* With the thermostat: one copy per generator. */
#define FORCE_CASE_XI(T)                                                                           \
  case T:                                                                                          \
    if (rng == PAIR_RNG_FAST) {                                                                    \
      FORCE_VIRIAL(T, PAIR_RNG_FAST)                                                               \
    } else if (rng == PAIR_RNG_PHILOX2X32) {                                                       \
      FORCE_VIRIAL(T, PAIR_RNG_PHILOX2X32)                                                         \
    } else {                                                                                       \
      FORCE_VIRIAL(T, PAIR_RNG_PHILOX)                                                             \
    }                                                                                              \
    break;

void cpu_force_pass(const plan_t *plan, particles_t *p, const cell_list_t *cl, const nlist_t *nl,
                    force_pass_args_t *a) {
  const int per_virial = a->per_particle_virial && p->virial != NULL;
  const int rng = plan->pair_rng;
  force_consts_t k = {.inv_sqrt_dt = a->inv_sqrt_dt};
  k.vx = p->vpred[0] ? p->vpred[0] : p->v[0];
  k.vy = p->vpred[1] ? p->vpred[1] : p->v[1];
  k.vz = p->vpred[2] ? p->vpred[2] : p->v[2];
  for (int c = 0; c < 6; c++) a->virial[c] = 0.0;
  const int nslots = p->n_local + p->n_ghost;
  switch (plan->pair_terms & 15) { /* 8 (wall no slip) comes with 4 (its check) */
    FORCE_CASE(0)
    FORCE_CASE(1)
    FORCE_CASE(2)
    FORCE_CASE(3)
    FORCE_CASE_XI(4)
    FORCE_CASE_XI(5)
    FORCE_CASE_XI(6)
    FORCE_CASE_XI(7)
    FORCE_CASE_XI(12)
    FORCE_CASE_XI(13)
    FORCE_CASE_XI(14)
    FORCE_CASE_XI(15)
  }
}
