/* The flux output and the early stop on its error (see run_flux.h). */
#include "run/run_flux.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

int run_flux_open(run_flux_t *rf, sim_t *sim, int restart, long first, int rank) {
  memset(rf, 0, sizeof *rf);
  rf->log.file = rf->log.dset = -1;
  const scene_t *s = sim_scene(sim);
  if (s->flux.every <= 0) return 0;
  rf->on = 1;
  rf->every = s->flux.every;
  rf->target = s->target_error;
  double count[SCENE_MAX_SPECIES], vsum[SCENE_MAX_SPECIES];
  char err[512] = "";
  int bad = sim_flux_sums(sim, s->flux.axis, count, vsum) ||
            flux_def_init(&rf->def, s, count, err, sizeof err);
  if (bad) {
    if (rank == 0 && err[0]) fprintf(stderr, "%s: %s\n", s->file, err);
    return -1;
  }
  if (rank == 0)
    bad = flux_log_open(&rf->log, s, &rf->def, s->flux.path, restart ? first : -1, &rf->steps,
                        &rf->q, rf->q_phase) != 0;
  for (int k = 0; k < rf->def.n_phases; k++) rf->N_phase[k] = count[rf->def.phase[k]];
  rf->samples = rf->q.n;
  MPI_Comm comm = sim_comm(sim);
  MPI_Bcast(&rf->samples, 1, MPI_LONG, 0, comm);
  if (pressure_drop_init(&rf->pd, s, rf->samples, rank)) {
    if (rank == 0) fprintf(stderr, "mdpore: out of memory for the pressure drop\n");
    bad = 1;
  }
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm);
  rf->next_check = rf->samples > FLUX_FIRST_CHECK ? rf->samples : FLUX_FIRST_CHECK;
  return bad ? -1 : 0;
}

/* The Darcy relaxation time of the mean flow, in steps: tau = rho q / (phi G). The mean-flow
 * momentum balance per fluid volume, (rho / phi) dq/dt = G - mu q / k, relaxes as exp(-t / tau)
 * with tau = rho k / (phi mu), and k / mu = q / G at steady state, so tau comes from the run's own
 * mean q. It is also the integrated autocorrelation time of q's thermal fluctuations (Green-Kubo):
 * the response to a body force f per particle, q = (k / mu) n f, equals (n V f / kT) int
 * <dq(0) dq(t)> dt, so that integral is kT k / (mu V), and equipartition gives var q =
 * phi kT / (rho V); their ratio is rho k / (phi mu) (a slit: h^2 / (12 nu), the sum over its modes
 * h^2 / (n^2 pi^2 nu) weighted 8 / (n^2 pi^2)). A run a few times tau long reads its own
 * autocorrelation short (the sphere arrays, docs/permeability.md): tau floors it. G: the body
 * force's, or the mean of the measured one (the pressure drop's series). 0 where undefined (no
 * drive, q and G of opposite signs). */
static double darcy_relaxation_steps(const run_flux_t *rf, double q_mean, double dt) {
  double G = rf->def.G;
  if (!isfinite(G) && rf->pd.on && rf->pd.dp.n > 0) { /* the measured G: mean dp / L_sample */
    double dp = 0;
    for (long k = 0; k < rf->pd.dp.n; k++) dp += rf->pd.dp.x[k];
    G = dp / (double)rf->pd.dp.n / rf->pd.length;
  }
  const double tau = rf->def.mass_density * q_mean / (rf->def.fluid_fraction * G);
  return isfinite(tau) && tau > 0 && dt > 0 ? tau / dt : 0;
}

/* The pressure-diffusion time of the slowest mode, in steps: tau_p = L^2 / (4 pi^2 D),
 * D = k K / (phi mu) = (q / G) K / phi. A body force starts the flow at uniform density; the
 * pressure field that steers it around the constrictions needs the liquid compressed ahead of them
 * and thinned behind, and that mass comes through the pore network, so the density field obeys
 * the pressure-diffusion equation of a liquid of compressibility 1 / K in a porous medium,
 * phi / K dp/dt = div(k / mu grad p) (Bear, Dynamics of Fluids in Porous Media, 1972, 6.3). Its
 * slowest mode in a periodic box of length L along the flow (a mirrored image: the mirrored length)
 * has wave number 2 pi / L. Until it has decayed q is above its steady value, by the same fraction
 * at every forcing (the pressure field is linear in G): 30-40% at the start and e-folding over
 * 1000-2000 steps in Berea crops at 1 rc per voxel, where this estimate gives 1700-3400 steps
 * (docs/permeability.md). 0 without output.flux.bulk_modulus or where q / G is undefined. */
static double pressure_diffusion_steps(const run_flux_t *rf, const scene_t *s, double q_mean,
                                       double relax_steps) {
  const double K = s->flux.bulk_modulus, L = rf->def.length;
  if (!(K > 0) || !(relax_steps > 0) || !(q_mean != 0) || s->dt <= 0) return 0;
  /* q / G = relax_steps dt phi / rho (darcy_relaxation_steps), so D = relax_steps dt K / rho */
  const double D = relax_steps * s->dt * K / rf->def.mass_density;
  const double tau = L * L / (4.0 * PI * PI * D);
  return isfinite(tau) && tau > 0 ? tau / s->dt : 0;
}

/* Rank 0: the steady-state analysis of the series so far: its start floored at the pressure
 * diffusion's transient, its correlation time at the Darcy relaxation time. */
static void analyse(run_flux_t *rf, const scene_t *s) {
  steady_state_analyse(rf->q.x, rf->q.n, &rf->result);
  rf->relax_steps = darcy_relaxation_steps(rf, rf->result.avg.mean, s->dt);
  rf->pressure_steps = pressure_diffusion_steps(rf, s, rf->result.avg.mean, rf->relax_steps);
  if (rf->pressure_steps > 0)
    steady_state_analyse_from(rf->q.x, rf->q.n, rf->pressure_steps / (double)rf->every,
                              &rf->result);
  steady_state_floor_tau(&rf->result, rf->q.x, rf->relax_steps / (double)rf->every);
}

int run_flux_due(const run_flux_t *rf, long step) {
  return rf->on && step % rf->every == 0;
}

int run_flux_wants_virial(const run_flux_t *rf, long step) {
  return rf->pd.on && run_flux_due(rf, step);
}

int run_flux_check_at(const run_flux_t *rf, long step) {
  return rf->on && rf->target > 0 && run_flux_due(rf, step) && rf->samples + 1 >= rf->next_check;
}

int run_flux_sample(run_flux_t *rf, sim_t *sim, long step, int rank) {
  double count[SCENE_MAX_SPECIES], vsum[SCENE_MAX_SPECIES];
  const scene_t *s = sim_scene(sim);
  const int check = run_flux_check_at(rf, step);
  if (sim_flux_sums(sim, rf->def.axis, count, vsum)) return -1;
  flux_sample_t r;
  flux_sample(&rf->def, step, step * s->dt, count, vsum, &r);
  if (rf->pd.on) r.G = pressure_drop_sample(&rf->pd, sim, rank); /* the measured G */
  rf->samples++;
  if (rank == 0) {
    flux_log_row(&rf->log, &r);
    series_push(&rf->steps, (double)step);
    series_push(&rf->q, r.q);
    for (int k = 0; k < rf->def.n_phases; k++) {
      series_push(&rf->q_phase[k], r.q_phase[k]);
      rf->N_phase[k] = r.N_phase[k];
    }
  }
  if (!check) return 0;
  /* The next check once the series has grown by 5% (at least 10 samples): the analysis stays a
   * small part of the run however long it gets. */
  const long grow = rf->samples / 20 > 10 ? rf->samples / 20 : 10;
  rf->next_check = rf->samples + grow;
  int stop = 0;
  if (rank == 0) {
    analyse(rf, s);
    stop = steady_state_converged(&rf->result, rf->target);
  }
  MPI_Bcast(&stop, 1, MPI_INT, 0, sim_comm(sim));
  if (stop) {
    rf->reached = rf->stopped_early = 1;
    rf->stop_step = step;
    if (rank == 0)
      fprintf(stderr,
              "mdpore: flux: relative error of q %.3g <= run.target_error %g at step %ld (steady "
              "from step %.0f, %ld samples used, %.0f independent; Darcy relaxation time %.0f "
              "steps): stopping\n",
              rf->result.rel_err, rf->target, step, rf->steps.x[rf->result.start],
              rf->result.n - rf->result.start, rf->result.n_eff, rf->relax_steps);
  }
  return stop;
}

void run_flux_finish(run_flux_t *rf, const scene_t *s, int rank) {
  if (!rf->on || rank != 0) return;
  analyse(rf, s);
  for (int k = 0; k < rf->def.n_phases; k++) /* each phase over the total's steady window */
    steady_state_window(rf->q_phase[k].x, rf->q_phase[k].n, &rf->result, &rf->phase_result[k]);
  if (rf->pd.on) {
    pressure_drop_analyse(&rf->pd, rf->result.start, &rf->pd_result);
    if (pressure_drop_write_profile(&rf->pd, rf->result.start, rf->pd.profile_path))
      fprintf(stderr, "mdpore: could not write %s\n", rf->pd.profile_path);
  }
  if (rf->target > 0 && !rf->reached) rf->reached = steady_state_converged(&rf->result, rf->target);
  if (rf->reached) return;
  const steady_state_t *r = &rf->result;
  if (rf->target <= 0) { /* no target: still say when q is not a converged value (guardrail) */
    if (r->n > 0 && (!r->steady || !r->avg.plateau))
      fprintf(stderr,
              "mdpore: flux: q = %.4g is NOT converged: %s; the summary's q is the mean of what "
              "was sampled. Run longer (--steps), or set run.target_error to stop at a converged "
              "q.\n",
              r->avg.mean,
              !r->steady ? "no steady state found (MSER-5: the flux still drifts)"
                         : "the blocked error has no plateau (its error bar is underestimated)");
    return;
  }
  const char *why =
      r->before_slow    ? "the run ended within 3x the pressure-diffusion time, while q still "
                          "relaxes from above"
      : !r->steady      ? "no steady state found (MSER-5: the flux still drifts)"
      : !r->avg.plateau ? "the blocked error has no plateau yet (the series is short for its "
                          "correlation time)"
      : r->n - r->start < STEADY_MIN_SAMPLES ? "too few steady samples"
      : r->n - r->start < STEADY_WINDOW_OVER_TRANSIENT * r->mser_start
          ? "the steady window is shorter than 3x the transient before it"
      : (double)(r->n - r->start) < STEADY_SLOW_WINDOW_TIMES * r->tau_slow
          ? "the steady window is shorter than 2x the pressure-diffusion time"
      : r->n_eff < STEADY_MIN_EFFECTIVE
          ? (r->floor_governs ? "fewer than 30 independent samples at the Darcy "
                                "relaxation time of the mean flow"
                              : "fewer than 30 independent samples (the flux is "
                                "correlated over long times)")
          : "the error is still above it";
  fprintf(stderr,
          "mdpore: flux: run.target_error %g NOT reached within the step budget: relative error "
          "of q %.3g after %ld samples, %.0f independent (%s). Run longer (--steps).\n",
          rf->target, r->rel_err, r->n, r->n_eff, why);
}

void run_flux_close(run_flux_t *rf) {
  if (!rf->on) return;
  flux_log_close(&rf->log);
  pressure_drop_free(&rf->pd);
  series_free(&rf->steps);
  series_free(&rf->q);
  for (int k = 0; k < rf->def.n_phases; k++) series_free(&rf->q_phase[k]);
  rf->on = 0;
}
