/* Global reductions of the state for the outputs. sim_thermo: kinetic energy and temperature of
 * the mobile particles, momentum, and the full virial pressure tensor
 *   P_ab = ( sum_i m v_a v_b + 1/2 sum_{i != j} r_ij,a F_ij,b ) / V
 * with all pair force parts (conservative, dissipative, random; physics.md section 2). Temperature
 * counts 3 (N_mobile - 1) degrees of freedom (total momentum is conserved without body force).
 * sim_flux_sums: per species, mobile count and sum of v along one axis (the flux output). */
#include "engine/sim_internal.h"

#include <string.h>

void sim_thermo(sim_t *sim, thermo_t *out) {
  sim_state_t *st = &sim->st;
  const particles_t *p = &st->p;
  const plan_t *plan = &st->plan;
  const int on_device = sim->ops->thermo_sums != NULL;
  enum { N_MOBILE, KE, PX, PY, PZ, K0, NV = K0 + 6, NVAL = NV + 6 };
  double v[NVAL] = {0}, g[NVAL];
  if (on_device && sim->ops->thermo_sums(st, v)) memset(v, 0, sizeof v); /* message printed */
  for (int i = 0; i < (on_device ? 0 : p->n_local); i++) {
    const int s = p->species[i];
    const double m = plan->mass[s];
    const double vx = p->v[0][i], vy = p->v[1][i], vz = p->v[2][i];
    v[K0 + 0] += m * vx * vx;
    v[K0 + 1] += m * vy * vy;
    v[K0 + 2] += m * vz * vz;
    v[K0 + 3] += m * vx * vy;
    v[K0 + 4] += m * vx * vz;
    v[K0 + 5] += m * vy * vz;
    if (!plan->mobile[s]) continue;
    v[N_MOBILE] += 1.0;
    v[KE] += 0.5 * m * (vx * vx + vy * vy + vz * vz);
    v[PX] += m * vx;
    v[PY] += m * vy;
    v[PZ] += m * vz;
  }
  if (!on_device)
    for (int k = 0; k < 6; k++) v[NV + k] = st->virial[k];
  /* Reduce on rank 0 and broadcast: bitwise identical values on every rank. */
  MPI_Reduce(v, g, NVAL, MPI_DOUBLE, MPI_SUM, 0, st->dc.cart);
  MPI_Bcast(g, NVAL, MPI_DOUBLE, 0, st->dc.cart);
  long n_local = p->n_local, n_total = 0;
  MPI_Allreduce(&n_local, &n_total, 1, MPI_LONG, MPI_SUM, st->dc.cart);
  memset(out, 0, sizeof *out);
  out->step = st->step;
  out->time = st->step * st->scene.dt;
  out->n_total = n_total;
  out->n_mobile = (long)g[N_MOBILE];
  out->ke = g[KE];
  out->temperature = out->n_mobile > 1 ? 2.0 * g[KE] / (3.0 * (double)(out->n_mobile - 1)) : 0.0;
  for (int d = 0; d < 3; d++) out->momentum[d] = g[PX + d];
  out->volume = 1.0;
  for (int d = 0; d < 3; d++) out->volume *= st->scene.box_hi[d] - st->scene.box_lo[d];
  for (int k = 0; k < 6; k++) out->pressure[k] = (g[K0 + k] + g[NV + k]) / out->volume;
}

int sim_flux_sums(sim_t *sim, int axis, double count[SCENE_MAX_SPECIES],
                  double vsum[SCENE_MAX_SPECIES]) {
  sim_state_t *st = &sim->st;
  const particles_t *p = &st->p;
  const plan_t *plan = &st->plan;
  double v[2 * MESO_MAX_SPECIES] = {0}, g[2 * MESO_MAX_SPECIES];
  int bad = 0;
  if (sim->ops->flux_sums) {
    bad = sim->ops->flux_sums(st, axis, v) != 0; /* message printed */
  } else {
    for (int i = 0; i < p->n_local; i++) {
      const int s = p->species[i];
      if (!plan->mobile[s]) continue;
      v[s] += 1.0;
      v[MESO_MAX_SPECIES + s] += p->v[axis][i];
    }
  }
  /* Reduce on rank 0 and broadcast (as sim_thermo): the same bits on every rank. */
  MPI_Reduce(v, g, 2 * MESO_MAX_SPECIES, MPI_DOUBLE, MPI_SUM, 0, st->dc.cart);
  MPI_Bcast(g, 2 * MESO_MAX_SPECIES, MPI_DOUBLE, 0, st->dc.cart);
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, st->dc.cart);
  for (int s = 0; s < SCENE_MAX_SPECIES; s++) {
    count[s] = g[s];
    vsum[s] = g[MESO_MAX_SPECIES + s];
  }
  return bad ? -1 : 0;
}
