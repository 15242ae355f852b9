/* Load balancing in the run driver (run_balance.h). */
#include "run/run_balance.h"
#include "engine/sim_balance.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int run_balance_start(run_balance_t *rb, sim_t *sim, int restart, int rank) {
  memset(rb, 0, sizeof *rb);
  const scene_t *s = sim_scene(sim);
  double busy, busy_run;
  sim_imbalance(sim, &busy, &busy_run, &rb->weight_uniform);
  if (restart) rb->weight_uniform = -1;
  if (s->balance.cuts != SCENE_CUTS_COST || restart) return 0;
  sim_balance_report_t rep;
  if (sim_balance(sim, 0, &rep)) return -1;
  rb->seconds += rep.seconds;
  if (rank == 0)
    printf("mdpore: load balancing: cuts placed by cost (frozen particle weight %g): particle "
           "weight imbalance %.3f with uniform cuts -> %.3f (%.3g s)\n",
           s->balance.frozen_weight, rep.weight_before, rep.weight_after, rep.seconds);
  return 0;
}

int run_balance_step(run_balance_t *rb, sim_t *sim, long step, long last, int rank) {
  const scene_t *s = sim_scene(sim);
  if (s->balance.every <= 0 || step % s->balance.every != 0 || step >= last ||
      !sim_busy_measured(sim))
    return 0;
  double busy, busy_run, weight;
  sim_imbalance(sim, &busy, &busy_run, &weight);
  if (!(busy > s->balance.threshold)) return 0;
  sim_balance_report_t rep;
  if (sim_balance(sim, 1, &rep)) {
    if (rank == 0) fprintf(stderr, "mdpore: run stopped at step %ld (load balancing)\n", step);
    return -1;
  }
  rb->rebalances++;
  rb->seconds += rep.seconds;
  if (rank == 0)
    printf("mdpore: step %ld: busy-time imbalance %.3f > balance.threshold %.3g: cuts moved by "
           "measured cost (frozen particle weight %.3g%s; %.3g s)\n",
           step, busy, s->balance.threshold, rep.frozen_weight,
           rep.fitted ? " fitted to the ranks' busy times" : ", each rank's time per weight",
           rep.seconds);
  return 0;
}

void run_balance_finish(const run_balance_t *rb, sim_t *sim, run_stats_t *st) {
  sim_imbalance(sim, &st->imbalance_busy, &st->imbalance_busy_run, &st->imbalance_weight);
  st->frozen_weight = sim_frozen_weight(sim);
  st->busy_mean_seconds = sim_busy_mean(sim);
  st->imbalance_weight_uniform = rb->weight_uniform;
  st->balance_seconds = rb->seconds;
  st->rebalances = rb->rebalances;
  if (!sim_busy_measured(sim) || st->nranks < 2) return;
  int rank = 0;
  MPI_Comm_rank(sim_comm(sim), &rank);
  double *since = NULL, *run = NULL;
  if (rank == 0) { /* (the summary leaves the arrays out when these fail) */
    since = malloc((size_t)st->nranks * sizeof *since);
    run = malloc((size_t)st->nranks * sizeof *run);
  }
  int ok = rank != 0 || (since && run);
  MPI_Bcast(&ok, 1, MPI_INT, 0, sim_comm(sim));
  if (ok) sim_busy_per_rank(sim, since, run);
  if (rank == 0 && ok) {
    st->busy_rank_since_move = since;
    st->busy_rank_run = run;
  } else {
    free(since);
    free(run);
  }
}
