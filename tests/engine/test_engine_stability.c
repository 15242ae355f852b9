/* Hard cases stop cleanly instead of producing garbage:
 *  - a time step far too large makes particles jump more than half the cutoff in one step: sim_step
 *    returns non-zero and names the cause;
 *  - a non-periodic box with reflecting box_walls keeps every particle inside over a driven run
 *    (count conserved, all positions within the box). */
#include "common/mpi_singleton.h"
#include "test_engine_common.h"

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  scene_t s;
  test_scene_mdpd(&s, 5, 5, 5);
  effect_name_in_scene(&s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(&s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(&s, EFFECT_DPD_THERMOSTAT);
  s.dt = 0.5; /* far too large for mDPD */
  sim_t *sim = sim_create(&s, MPI_COMM_WORLD);
  CHECK(sim, "sim_create");
  CHECK(test_fill_random(sim, &s, 750, 0.0, 8) == 0, "fill");
  CHECK(sim_setup(sim) == 0, "setup");
  int rc = 0, k;
  for (k = 0; k < 20 && rc == 0; k++) rc = sim_step(sim);
  CHECK(rc != 0, "dt = 0.5 ran 20 steps without a complaint");
  const char *msg = sim_last_error(sim);
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) printf("stopped at step %d: %s\n", k, msg);
  CHECK(strstr(msg, "time step too large") || strstr(msg, "stopped"),
        "message does not name the cause");
  sim_destroy(sim);

  test_scene_mdpd(&s, 6, 5, 5);
  effect_name_in_scene(&s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(&s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(&s, EFFECT_DPD_THERMOSTAT);
  effect_name_in_scene(&s, EFFECT_BOX_WALLS);
  effect_name_in_scene(&s, EFFECT_BODY_FORCE);
  s.periodic[0] = 0;
  SCENE_EFFECT_OPTIONS(&s, EFFECT_BODY_FORCE, body_force_params_t)->g[0][0] =
      2.0; /* pushes everything against the wall at x = 6 */
  sim = sim_create(&s, MPI_COMM_WORLD);
  CHECK(sim, "sim_create (walls)");
  CHECK(test_fill_random(sim, &s, 900, 0.0, 9) == 0, "fill");
  CHECK(sim_setup(sim) == 0, "setup");
  for (k = 0; k < 200; k++) CHECK(sim_step(sim) == 0, "walls: step %d: %s", k, sim_last_error(sim));
  CHECK(sim_check_count(sim) == 0, "count changed");
  particles_t *p = sim_particles(sim);
  double xmin = 1e9, xmax = -1e9, xsum = 0;
  for (int i = 0; i < p->n_local; i++) {
    xmin = fmin(xmin, p->x[0][i]);
    xmax = fmax(xmax, p->x[0][i]);
    xsum += p->x[0][i];
  }
  MPI_Allreduce(MPI_IN_PLACE, &xmin, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &xmax, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &xsum, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0)
    printf("walls: x in [%.4f, %.4f], mean x %.3f (pushed towards x = 6)\n", xmin, xmax,
           xsum / 900);
  CHECK(xmin >= 0 && xmax < 6, "particle outside the walls");
  CHECK(xsum / 900 > 3.2, "body force did not push the fluid towards the wall");
  sim_destroy(sim);
  MPI_Finalize();
  return 0;
}
