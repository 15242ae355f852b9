/* The step plan follows the named effects (sim_explain, mdpore run --explain):
 *  - standard DPD (dpd_conservative + dpd_thermostat): no density pass, no rho sync, no rho array;
 *  - mDPD (+ mdpd_repulsion): a density pass and a rho ghost sync, in that order, before the
 * forces;
 *  - box_walls printed with its faces; body_force as a particle-force pass;
 * and scenes the engine cannot run are refused at sim_create with a message: a non-periodic axis
 * without box_walls, a subdomain thinner than the cutoff, both users of the pair amplitude A. */
#include "common/mpi_singleton.h"
#include "test_engine_common.h"

static char *explain(const scene_t *s, int nranks) {
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  sim_explain(s, nranks, f);
  fclose(f);
  return buf;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  scene_t s;
  test_scene_mdpd(&s, 10, 10, 10);
  effect_name_in_scene(&s, EFFECT_DPD_CONSERVATIVE);
  effect_name_in_scene(&s, EFFECT_DPD_THERMOSTAT);
  s.pair[0][0].A = 25; /* standard DPD a */
  char *t = explain(&s, 2);
  printf("--- standard DPD ---\n%s", t);
  CHECK(!strstr(t, "density pass"), "DPD plan has a density pass");
  CHECK(!strstr(t, "rho"), "DPD plan mentions rho");
  CHECK(strstr(t, "force pass: dpd_conservative, dpd_thermostat"), "force pass line missing");
  CHECK(strstr(t, "2 x 1 x 1") || strstr(t, "1 x 2 x 1") || strstr(t, "1 x 1 x 2"),
        "decomposition");
  free(t);
  sim_t *sim = sim_create(&s, MPI_COMM_SELF);
  CHECK(sim && sim_particles(sim)->rho == NULL, "DPD scene allocated a rho array");
  sim_destroy(sim);

  test_scene_mdpd(&s, 10, 10, 10);
  effect_name_in_scene(&s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(&s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(&s, EFFECT_DPD_THERMOSTAT);
  effect_name_in_scene(&s, EFFECT_BODY_FORCE);
  effect_name_in_scene(&s, EFFECT_BOX_WALLS);
  s.periodic[2] = 0;
  SCENE_EFFECT_OPTIONS(&s, EFFECT_BODY_FORCE, body_force_params_t)->g[0][0] = 0.02;
  t = explain(&s, 1);
  printf("--- mDPD with walls and body force ---\n%s", t);
  const char *dens = strstr(t, "density pass (Warren kernel, rd = 0.75");
  const char *sync = strstr(t, "ghost sync: rho");
  const char *force = strstr(t, "force pass: mdpd_attraction, mdpd_repulsion, dpd_thermostat");
  const char *part = strstr(t, "particle forces: body_force");
  CHECK(dens && sync && force && part, "mDPD plan lacks a pass");
  CHECK(dens < sync && sync < force && force < part, "passes out of order");
  CHECK(strstr(t, "box_walls: reflect on faces z = 0 and z = 10"), "box walls line");
  {
    /* --explain prints the plan's own step list: every phase, numbered, in the order it runs. */
    plan_t pl;
    char perr[512];
    CHECK(plan_build(&pl, &s, perr, sizeof perr) == 0, "plan: %s", perr);
    const char *at = strstr(t, "every step");
    for (int k = 0; at && k < pl.n_step; k++) {
      char line[64];
      snprintf(line, sizeof line, "%2d. %s:", k + 1, step_phase_names[pl.step[k]]);
      const char *next = strstr(at, line);
      CHECK(next != NULL, "explain lacks '%s' after the previous phase", line);
      at = next;
    }
    CHECK(at != NULL, "explain has no step list");
  }
  free(t);
  sim = sim_create(&s, MPI_COMM_SELF);
  CHECK(sim && sim_particles(sim)->rho != NULL, "mDPD scene has no rho array");
  sim_destroy(sim);

  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) fprintf(stderr, "(three expected error messages follow)\n");
  s.effect[EFFECT_BOX_WALLS] = 0; /* z not periodic, no walls */
  CHECK(sim_create(&s, MPI_COMM_SELF) == NULL, "non-periodic axis without box_walls accepted");
  effect_name_in_scene(&s, EFFECT_BOX_WALLS);
  s.box_hi[0] = 0.9; /* thinner than rc = 1 */
  CHECK(sim_create(&s, MPI_COMM_SELF) == NULL, "subdomain thinner than the cutoff accepted");
  s.box_hi[0] = 10;
  effect_name_in_scene(&s, EFFECT_DPD_CONSERVATIVE);
  CHECK(sim_create(&s, MPI_COMM_SELF) == NULL, "mdpd_attraction + dpd_conservative accepted");
  s.effect[EFFECT_DPD_CONSERVATIVE] = 0;
  /* The effects' own checks run on scenes built in code too: reverse Poiseuille flow along the
   * wall-bounded axis z is refused by body_force's check, naming the key. */
  SCENE_EFFECT_OPTIONS(&s, EFFECT_BODY_FORCE, body_force_params_t)->reverse_axis = 2;
  char err[512];
  plan_t plan;
  CHECK(plan_build(&plan, &s, err, sizeof err) != 0 &&
            strstr(err, "effects.body_force.reverse_along") && strstr(err, "periodic axis"),
        "reverse_along a non-periodic axis accepted (or unclear message: %s)", err);
  SCENE_EFFECT_OPTIONS(&s, EFFECT_BODY_FORCE, body_force_params_t)->reverse_axis = 1;
  CHECK(plan_build(&plan, &s, err, sizeof err) == 0, "a valid scene refused: %s", err);
  /* The plan lists the phases the effects need, in order, and --explain prints that list. */
  CHECK(plan_has_phase(&plan, 0, PHASE_AFTER_DRIFT) && plan_has_phase(&plan, 0, PHASE_DENSITY) &&
            plan_has_phase(&plan, 0, PHASE_PARTICLE_FORCES) &&
            plan_has_phase(&plan, 1, PHASE_RHO_SYNC) && !plan_has_phase(&plan, 1, PHASE_KICK),
        "phase lists");
  CHECK(plan.half_dt == 0.5 * s.dt && plan.inv_sqrt_dt == 1.0 / sqrt(s.dt) &&
            plan.predict_c == (s.vv_lambda - 0.5) * s.dt,
        "derived time-step constants");
  MPI_Finalize();
  return 0;
}
