/* Load balancing in the run driver (docs/scene-format.md "Load balancing"): the cuts placed by cost
 * before the set-up (balance.cuts: cost), moved again during the run when the measured busy-time
 * imbalance exceeds balance.threshold (checked every balance.every steps), and the imbalance the
 * summary reports. */
#ifndef MESO_RUN_RUN_BALANCE_H
#define MESO_RUN_RUN_BALANCE_H

#include "engine/sim.h"
#include "run/run_stats.h"

typedef struct {
  double weight_uniform; /* weight imbalance of the uniform cuts (< 0: unknown, a restart) */
  double seconds;        /* time spent placing cuts and moving particles                  */
  long rebalances;
} run_balance_t;

/* Before sim_setup (collective): with balance.cuts: cost and a fresh start, place the cuts and
 * move the particles (a restart keeps its checkpoint's cuts). 0, or -1 (message printed). */
int run_balance_start(run_balance_t *rb, sim_t *sim, int restart, int rank);
/* After sim_step (collective, every rank at the same step): every balance.every steps before the
 * last, move the cuts when the busy-time imbalance exceeds balance.threshold. 0, or -1 (message
 * printed). */
int run_balance_step(run_balance_t *rb, sim_t *sim, long step, long last, int rank);
/* The imbalance of the last period into the summary statistics (collective). */
void run_balance_finish(const run_balance_t *rb, sim_t *sim, run_stats_t *st);

#endif
