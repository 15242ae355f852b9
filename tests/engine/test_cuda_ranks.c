/* CUDA path on several ranks, one GPU each: forces and densities at setup, and
 * positions after 20 steps (particles migrate and ghosts are rebuilt every step), agree between one
 * GPU (MPI_COMM_SELF on rank 0) and all ranks' GPUs, to float rounding (same bounds as
 * test_cuda_forces.c; the ghost order differs, so sums differ in the last bits). The scene is
 * test_cuda_forces.c's: mDPD + thermostat + frozen species + walls + reverse body force, lambda
 * 0.65. Skipped (exit 77) without a GPU. Run under mpiexec with 2 ranks (nvidia-h200-x2). */
#include "common/mpi_singleton.h"
#include "test_cuda_common.h"

static void scene_of(scene_t *s) {
  test_scene_mdpd(s, 8.0, 6.0, 7.0);
  s->n_species = 2;
  snprintf(s->species[1].name, SCENE_NAME_LEN, "wall");
  s->species[1].mass = 1.0;
  s->species[1].frozen = 1;
  s->pair[0][1].A = s->pair[1][0].A = -30;
  s->periodic[2] = 0;
  s->vv_lambda = 0.65;
  effect_name_in_scene(s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(s, EFFECT_DPD_THERMOSTAT);
  effect_name_in_scene(s, EFFECT_BODY_FORCE);
  effect_name_in_scene(s, EFFECT_BOX_WALLS);
  SCENE_EFFECT_OPTIONS(s, EFFECT_BODY_FORCE, body_force_params_t)->g[0][0] = 0.3;
  /* reverse Poiseuille along a periodic axis (a wall-bounded one is refused by the plan) */
  SCENE_EFFECT_OPTIONS(s, EFFECT_BODY_FORCE, body_force_params_t)->reverse_axis = 1;
  s->backend = SCENE_BACKEND_CUDA;
}

/* Per-id x, f, rho of all ranks summed onto rank 0 of comm (each id lives on one rank). */
static int collect(sim_t *sim, int n, MPI_Comm comm, test_state_t *st) {
  if (test_state_get(sim, n, st)) return -1;
  int rank;
  MPI_Comm_rank(comm, &rank);
  double *bufs[3] = {st->x, st->f, st->rho};
  const int len[3] = {3 * n, 3 * n, n};
  for (int k = 0; k < 3; k++)
    MPI_Reduce(rank ? bufs[k] : MPI_IN_PLACE, bufs[k], len[k], MPI_DOUBLE, MPI_SUM, 0, comm);
  return 0;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  test_cuda_require_gpu();
  int rank, size;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  scene_t s;
  scene_of(&s);
  const int n = 2016, steps = 20;
  sim_t *one = NULL;
  if (rank == 0) {
    one = sim_create(&s, MPI_COMM_SELF);
    CHECK(one && !test_fill_random(one, &s, n, 0.3, 77) && !sim_setup(one), "1-GPU simulation");
  }
  sim_t *all = sim_create(&s, MPI_COMM_WORLD);
  CHECK(all && !test_fill_random(all, &s, n, 0.3, 77) && !sim_setup(all), "%d-GPU simulation",
        size);
  test_state_t a, b;
  CHECK(!collect(all, n, MPI_COMM_WORLD, &b), "collect");
  int ok = 1;
  if (rank == 0) {
    CHECK(!test_state_get(one, n, &a), "state");
    double fscale = 0, df = 0, drho = 0;
    for (int k = 0; k < 3 * n; k++) {
      fscale = fmax(fscale, fabs(a.f[k]));
      df = fmax(df, fabs(a.f[k] - b.f[k]));
    }
    for (int i = 0; i < n; i++) drho = fmax(drho, fabs(a.rho[i] - b.rho[i]) / fmax(a.rho[i], 1.0));
    printf("setup, 1 vs %d GPUs: max |df| = %.3e of the largest force component, max relative "
           "drho = %.3e\n",
           size, df / fscale, drho);
    ok = df <= 2e-5 * fscale && drho <= 2e-6;
    test_state_free(&a);
  }
  test_state_free(&b);
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  CHECK(ok, "forces or densities differ between 1 and %d GPUs", size);
  for (int k = 0; k < steps; k++) {
    if (rank == 0) CHECK(!sim_step(one), "1-GPU step %d", k);
    CHECK(!sim_step(all), "%d-GPU step %d", size, k);
  }
  CHECK(!collect(all, n, MPI_COMM_WORLD, &b), "collect");
  if (rank == 0) {
    CHECK(!test_state_get(one, n, &a), "state");
    const double L[3] = {8.0, 6.0, 7.0};
    double dx = 0;
    for (int i = 0; i < n; i++)
      for (int d = 0; d < 3; d++) {
        const double e = a.x[3 * i + d] - b.x[3 * i + d];
        dx = fmax(dx, fabs(e - L[d] * rint(e / L[d])));
      }
    printf("after %d steps, 1 vs %d GPUs: max |dx| = %.3e\n", steps, size, dx);
    ok = dx <= 1e-5;
    test_state_free(&a);
  }
  test_state_free(&b);
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  CHECK(ok, "trajectories differ between 1 and %d GPUs", size);
  thermo_t t;
  sim_thermo(all, &t);
  CHECK(t.n_total == n, "particle count %ld != %d", t.n_total, n);
  sim_destroy(all);
  if (one) sim_destroy(one);
  MPI_Finalize();
  return 0;
}
