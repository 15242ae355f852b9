/* The per-particle virial (on request, for pressure profiles) adds up to the pair part of the
 * thermo pressure tensor: sum_i W_i,ab = P_ab V - sum_i m v_a v_b. And forces do not depend on the
 * number of OpenMP threads: each particle's sum is done by one thread in a fixed order, so 1 and 3
 * threads give bitwise identical forces (needed for bitwise restarts). */
#include "common/mpi_singleton.h"
#include "test_engine_common.h"

#ifdef _OPENMP
#include <omp.h>
#endif

static sim_t *build(const scene_t *s) {
  sim_t *sim = sim_create(s, MPI_COMM_SELF);
  if (!sim) return NULL;
  sim_request_virial(sim, 1);
  if (test_fill_random(sim, s, 700, 0.0, 4242) || sim_setup(sim)) return NULL;
  return sim;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  scene_t s;
  test_scene_mdpd(&s, 5, 5, 5);
  effect_name_in_scene(&s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(&s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(&s, EFFECT_DPD_THERMOSTAT);
#ifdef _OPENMP
  omp_set_num_threads(1);
#endif
  sim_t *a = build(&s);
  CHECK(a, "build");
  for (int k = 0; k < 5; k++) CHECK(sim_step(a) == 0, "step");
  particles_t *p = sim_particles(a);
  CHECK(p->virial != NULL, "no per-particle virial after sim_request_virial");
  double w[6] = {0}, kin[6] = {0};
  for (int i = 0; i < p->n_local; i++) {
    for (int c = 0; c < 6; c++) w[c] += p->virial[6 * i + c];
    const double *v[3] = {p->v[0], p->v[1], p->v[2]};
    kin[0] += v[0][i] * v[0][i], kin[1] += v[1][i] * v[1][i], kin[2] += v[2][i] * v[2][i];
    kin[3] += v[0][i] * v[1][i], kin[4] += v[0][i] * v[2][i], kin[5] += v[1][i] * v[2][i];
  }
  thermo_t t;
  sim_thermo(a, &t);
  double err = 0, scale = 0;
  for (int c = 0; c < 6; c++) {
    const double pair = t.pressure[c] * t.volume - kin[c];
    err = fmax(err, fabs(pair - w[c]));
    scale = fmax(scale, fabs(w[c]));
  }
  printf("per-particle virial vs thermo pair virial: max diff %.3e (scale %.3e)\n", err, scale);
  CHECK(scale > 0 && err < 1e-10 * scale, "per-particle virial does not add up");

#ifdef _OPENMP
  omp_set_num_threads(3);
#endif
  sim_t *b = build(&s);
  CHECK(b, "build (3 threads)");
  for (int k = 0; k < 5; k++) CHECK(sim_step(b) == 0, "step");
  particles_t *q = sim_particles(b);
  CHECK(q->n_local == p->n_local, "counts differ");
  long differ = 0;
  for (int i = 0; i < p->n_local; i++)
    for (int d = 0; d < 3; d++) differ += p->f[d][i] != q->f[d][i] || p->x[d][i] != q->x[d][i];
  printf("1 vs 3 OpenMP threads after 5 steps: %ld differing force/position components\n", differ);
  CHECK(differ == 0, "results depend on the thread count");
  sim_destroy(a);
  sim_destroy(b);
  MPI_Finalize();
  return 0;
}
