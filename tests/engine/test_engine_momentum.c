/* Momentum is conserved to rounding in an mDPD + thermostat run without body force (pair forces are
 * antisymmetric, F_ij = -F_ji), on however many ranks this runs; particle count is conserved
 * (sim_step checks it every step) and the temperature stays near kT = 1. */
#include "common/mpi_singleton.h"
#include "test_engine_common.h"

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  scene_t s;
  test_scene_mdpd(&s, 6.0, 5.0, 5.0);
  effect_name_in_scene(&s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(&s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(&s, EFFECT_DPD_THERMOSTAT);
  sim_t *sim = sim_create(&s, MPI_COMM_WORLD);
  CHECK(sim, "sim_create");
  const int n = 900; /* density 6 */
  CHECK(test_fill_random(sim, &s, n, 0.0, 31) == 0, "fill");
  /* Remove the mean velocity so the total momentum starts at (almost) zero. */
  particles_t *p = sim_particles(sim);
  double mom[3] = {0, 0, 0};
  for (int i = 0; i < p->n_local; i++)
    for (int d = 0; d < 3; d++) mom[d] += p->v[d][i];
  MPI_Allreduce(MPI_IN_PLACE, mom, 3, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  for (int i = 0; i < p->n_local; i++)
    for (int d = 0; d < 3; d++) p->v[d][i] -= mom[d] / n;
  CHECK(sim_setup(sim) == 0, "setup");
  thermo_t t0, t;
  sim_thermo(sim, &t0);
  const int steps = 300;
  double tsum = 0;
  for (int k = 0; k < steps; k++) {
    CHECK(sim_step(sim) == 0, "step %d failed", k);
    sim_thermo(sim, &t);
    if (k >= steps / 2) tsum += t.temperature;
  }
  double drift = 0;
  for (int d = 0; d < 3; d++) drift = fmax(drift, fabs(t.momentum[d] - t0.momentum[d]));
  /* Scale: momentum of one particle at kT = 1 times N. */
  const double rel = drift / n;
  const double tmean = tsum / (steps - steps / 2);
  if (rank == 0)
    printf("momentum drift over %d steps: max |P - P0| = %.3e (per particle %.3e); <T> = %.3f; N = "
           "%ld\n",
           steps, drift, rel, tmean, t.n_total);
  CHECK(t.n_total == n, "particle count %ld != %d", t.n_total, n);
  CHECK(rel < 1e-12, "momentum not conserved: %.3e per particle", rel);
  CHECK(fabs(tmean - 1.0) < 0.1, "temperature %.3f far from kT = 1", tmean);
  sim_destroy(sim);
  MPI_Finalize();
  return 0;
}
