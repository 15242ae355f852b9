/* The flux output in the run loop (output.flux, run.target_error; docs/scene-format.md): samples
 * of q every output.flux.every steps (analysis/flux.h: the definitions; io/flux_log.h: the file),
 * and with a target the early stop: from FLUX_FIRST_CHECK samples on, each time the series has
 * grown by 5% (at least 10 samples), rank 0 finds the steady part and its error
 * (analysis/steady_state.h) and every rank stops once the relative error of q is at most the
 * target. The correlation time of q is taken as at least the Darcy relaxation time of the mean
 * flow, rho q / (phi G) (run_flux.c): a run a few times that long reads its own autocorrelation
 * short. Without output.flux nothing here allocates or runs. */
#ifndef MESO_RUN_RUN_FLUX_H
#define MESO_RUN_RUN_FLUX_H

#include "analysis/pressure_drop.h"
#include "analysis/steady_state.h"
#include "engine/sim.h"
#include "io/flux_log.h"

#define FLUX_FIRST_CHECK 100

typedef struct run_flux {
  int on;     /* output.flux is set */
  long every; /* output.flux.every */
  flux_def_t def;
  flux_log_t log;
  series_t steps, q;                   /* rank 0: the series (with a restart's earlier rows) */
  series_t q_phase[SCENE_MAX_SPECIES]; /* rank 0: q of each of def.phase (output.flux.phases) */
  double N_phase[SCENE_MAX_SPECIES];   /* their particles at the latest sample */
  steady_state_t phase_result[SCENE_MAX_SPECIES]; /* rank 0, after run_flux_finish: each phase's
                                                     mean and error over result's window */
  long samples;          /* its length, on every rank (the check schedule) */
  long next_check;       /* length at which the next early-stop check runs */
  double target;         /* run.target_error (0: none) */
  int reached;           /* the target was met (at a check, or in the final analysis) */
  int stopped_early;     /* the run stopped before its last step because of it */
  long stop_step;        /* step at which it stopped */
  steady_state_t result; /* rank 0: the latest analysis (the final one after run_flux_finish) */
  pressure_drop_t pd;    /* inlet_force with a sample: the measured G (analysis/pressure_drop.h) */
  pressure_drop_result_t pd_result; /* rank 0, after run_flux_finish */
  double relax_steps; /* rank 0: the Darcy relaxation time of the mean flow in steps, the floor of
                         the flux's correlation time (0: undefined); run_flux.c */
  double pressure_steps; /* rank 0: the pressure-diffusion time of the liquid's slowest mode in
                            steps, with output.flux.bulk_modulus (0: none); run_flux.c */
} run_flux_t;

/* Collective: the definitions (one flux reduction for the counts) and the file; `restart`: the run
 * continues from a checkpoint at step `first` (earlier rows are read back). 0, or -1 after a
 * message on rank 0. */
int run_flux_open(run_flux_t *rf, sim_t *sim, int restart, long first, int rank);
/* Is `step` a flux sample step? */
int run_flux_due(const run_flux_t *rf, long step);
/* Does a sample at `step` need the per-particle virial (the measured pressure drop)? */
int run_flux_wants_virial(const run_flux_t *rf, long step);
/* Would a sample at `step` run an early-stop check? (The same answer on every rank.) */
int run_flux_check_at(const run_flux_t *rf, long step);
/* Collective, at a sample step: reduce, write the row, and check the target when due. Returns 1
 * when the run should stop (target met), 0 to go on, -1 on a device error (message printed). */
int run_flux_sample(run_flux_t *rf, sim_t *sim, long step, int rank);
/* Rank 0, after the loop: analyse the whole series; say on stderr when a target was not met. */
void run_flux_finish(run_flux_t *rf, const scene_t *s, int rank);
void run_flux_close(run_flux_t *rf);

#endif
