/* What the run driver averages for its final summary (rank 0): thermo samples in the sampling
 * window (steps >= output.profile.start, or the second half of the run without a profile), the
 * surface tension series when a profile axis is set, the loop timing, and the flux analysis
 * (output.flux; its own window: from the MSER-5 truncation on). */
#ifndef MESO_RUN_RUN_STATS_H
#define MESO_RUN_RUN_STATS_H

#include "analysis/block_average.h"
#include "analysis/profile.h"
#include "engine/sim.h"

enum {
  STAT_T,
  STAT_KE,
  STAT_PXX,
  STAT_PYY,
  STAT_PZZ,
  STAT_PXY,
  STAT_PXZ,
  STAT_PYZ,
  STAT_P,
  STAT_GAMMA,
  STAT_COUNT
};
extern const char *const run_stat_names[STAT_COUNT];

typedef struct {
  long window_start, sample_every, first_step, last_step;
  long sample_from; /* first step sampled: window_start, or the run's first for a run that may
                     * stop early (run.target_error), whose window run_stats_finish then fixes */
  int gamma_axis;   /* -1: no surface tension (no profile axis) */
  double gamma_len;
  series_t s[STAT_COUNT];
  double loop_seconds, total_seconds;
  long n_total, steps_done;
  int nranks;
  /* Geometry scenes: penetration samples taken, samples with a penetration, the most particles
   * and the deepest seen at once (analysis/penetration.h). */
  int penetration_on;
  long penetration_samples, penetration_bad_samples, penetration_max;
  double penetration_depth;
  /* The pore core's density (analysis/penetration.h): mobile particles per rc^3 in the pore voxels
   * at least core_rc from the solid, one value per sample of the window; core_voxels 0: none. */
  series_t core_density;
  long core_voxels, core_start;
  double core_rc, core_volume;
  /* Load balance (engine/sim_balance.h): max / mean over the ranks of the busy time in the step
   * loop since the last rebalancing and over the whole run (0: not measured, a GPU backend) and of
   * the particle weight;
   * the weight imbalance before the first cut placement by cost; rebalancings and their time. */
  double imbalance_busy, imbalance_busy_run, imbalance_weight, imbalance_weight_uniform;
  double balance_seconds, frozen_weight; /* the frozen weight in use at the end (fitted or set) */
  double busy_mean_seconds;              /* mean over the ranks of the busy seconds of the run */
  /* rank 0: each rank's busy seconds since the last move and over the run (nranks values, in
   * rank order; NULL when not measured) */
  double *busy_rank_since_move, *busy_rank_run;
  long rebalances;
  /* output.flux: its series and final analysis (run/run_flux.h; NULL or off: none). */
  const struct run_flux *flux;
  /* flood: its census and breakthrough (run/run_flood.h; NULL or off: none). */
  const struct run_flood *flood;
} run_stats_t;

void run_stats_init(run_stats_t *st, const scene_t *scene, long first, long last, int nranks);
int run_stats_wants(const run_stats_t *st, long step);
void run_stats_add(run_stats_t *st, const thermo_t *t);
/* At the end of the run, `last` the step it ended at (earlier than planned after an early stop):
 * without a profile the window is the second half of the steps actually run, and the samples
 * before it are dropped. A run that stops early on its flux error then still has its averages. */
void run_stats_finish(run_stats_t *st, long last);
void run_stats_free(run_stats_t *st);

/* Rank 0: print the human summary to `out` and write the summary JSON atomically. 0 or -1. */
int run_summary_write(const run_stats_t *st, const scene_t *scene, const profile_t *profile,
                      FILE *out, const char *json_path);

#endif
