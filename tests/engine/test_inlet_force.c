/* inlet_force puts momentum in through its slab only: in an mDPD + thermostat run (pair forces
 * conserve momentum) with an inlet force g on species "liquid" in the slab [lo, hi) along x, the
 * total momentum changes in each velocity-Verlet step by exactly
 *   dP = dt/2 g (N_slab(t) + N_slab(t + dt))
 * (the force enters both half kicks), N_slab counting the liquid particles in the slab at the
 * force evaluations; particles of species "tracer" (force 0) and particles outside the slab get
 * nothing. A slab that wraps the periodic face (positions of any image) counts the same way.
 * Asserted to rounding per step, on however many ranks this runs. */
#include "common/mpi_singleton.h"
#include "effects/inlet_force.h"
#include "test_engine_common.h"

/* Liquid particles in the slab (their positions now), all ranks. */
static double count_in_slab(sim_t *sim, const inlet_force_params_t *b) {
  particles_t *p = sim_particles(sim);
  double n = 0;
  for (int i = 0; i < p->n_local; i++)
    n += p->species[i] == 0 && inlet_force_in_slab(b, p->x[b->axis][i]);
  MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_DOUBLE, MPI_SUM, sim_comm(sim));
  return n;
}

static void momentum(sim_t *sim, double P[3]) {
  particles_t *p = sim_particles(sim);
  P[0] = P[1] = P[2] = 0;
  for (int i = 0; i < p->n_local; i++)
    for (int d = 0; d < 3; d++) P[d] += p->v[d][i]; /* mass 1 */
  MPI_Allreduce(MPI_IN_PLACE, P, 3, MPI_DOUBLE, MPI_SUM, sim_comm(sim));
}

static int run_case(double lo, double hi, const double g[3], int rank) {
  scene_t s;
  test_scene_mdpd(&s, 8.0, 5.0, 5.0);
  s.n_species = 2;
  snprintf(s.species[1].name, SCENE_NAME_LEN, "tracer");
  s.species[1].mass = 1.0;
  effect_name_in_scene(&s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(&s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(&s, EFFECT_DPD_THERMOSTAT);
  effect_name_in_scene(&s, EFFECT_INLET_FORCE);
  inlet_force_options_t *o = SCENE_EFFECT_OPTIONS(&s, EFFECT_INLET_FORCE, inlet_force_options_t);
  for (int d = 0; d < 3; d++) o->force.g[0][d] = g[d];
  o->force.axis = 0;
  o->force.lo = lo;
  o->force.hi = hi;
  inlet_force_params_t slab = o->force;
  slab.box_lo = 0;
  slab.box_len = 8.0;
  sim_t *sim = sim_create(&s, MPI_COMM_WORLD);
  CHECK(sim, "sim_create");
  CHECK(test_fill_random(sim, &s, 1200, 0.25, 77) == 0, "fill");
  CHECK(sim_setup(sim) == 0, "setup");
  double P0[3], P1[3], n0 = count_in_slab(sim, &slab), worst = 0, n_sum = 0;
  momentum(sim, P0);
  const int steps = 200;
  for (int k = 0; k < steps; k++) {
    CHECK(sim_step(sim) == 0, "step %d failed", k);
    const double n1 = count_in_slab(sim, &slab);
    momentum(sim, P1);
    for (int d = 0; d < 3; d++) {
      const double expect = 0.5 * s.dt * g[d] * (n0 + n1);
      worst = fmax(worst, fabs(P1[d] - P0[d] - expect));
    }
    n_sum += n1;
    n0 = n1;
    for (int d = 0; d < 3; d++) P0[d] = P1[d];
  }
  const double mean_n = n_sum / steps, expect_n = 0.75 * 1200 * (hi - lo) / 8.0;
  if (rank == 0)
    printf("slab [%g, %g): <N_slab> = %.1f liquid particles (uniform: %.1f); max |dP - dt/2 g "
           "(N(t) + N(t+dt))| per step = %.3e (one step's input %.3e)\n",
           lo, hi, mean_n, expect_n, worst, s.dt * g[0] * mean_n);
  CHECK(worst < 1e-9, "momentum input per step off by %.3e", worst);
  /* The slab holds a fraction of the liquid, not all of it (a force on every particle would pass
   * the test above only with N_slab = N). */
  CHECK(mean_n > 0.5 * expect_n && mean_n < 1.5 * expect_n, "slab count %.1f vs %.1f", mean_n,
        expect_n);
  sim_destroy(sim);
  return 0;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const double g[3] = {0.3, -0.1, 0.05};
  int bad = run_case(2.0, 4.0, g, rank); /* inside the box */
  bad |= run_case(7.0, 8.0, g, rank);    /* at the periodic face */
  MPI_Finalize();
  return bad;
}
