/* Load balancing of a simulation (docs/scene-format.md "Load balancing"): cuts placed by cost
 * (domain/balance.h), particles moved to their new owners (domain/redistribute.h), the backend
 * rebuilt on the new subdomains; the imbalance measured as max / mean busy time over the ranks. */
#ifndef MESO_ENGINE_SIM_BALANCE_H
#define MESO_ENGINE_SIM_BALANCE_H

#include "engine/sim.h"

typedef struct {
  double weight_before, weight_after; /* max / mean particle weight over the ranks             */
  double cost_before, cost_after;     /* the same for the cost (weight x measured s per weight) */
  double seconds;                     /* wall time of the rebalancing (all ranks' max)          */
  double frozen_weight;               /* the frozen particle weight the cuts used               */
  int fitted;                         /* 1: that weight was fitted to the measured busy times   */
  int moved;                          /* 1 when the cuts moved                                  */
} sim_balance_report_t;

/* Place the cuts by cost and move the particles (collective). measured = 0: cost = particle weight
 * (1 per mobile particle, the frozen weight per frozen one: balance.frozen_weight until a fit
 * replaces it); measured = 1 (CPU backend; the CUDA backend runs asynchronously and balances on
 * weight only): the busy seconds since the last sim_busy_reset fitted over the ranks as
 * a mobile + b frozen, the frozen weight becomes b / a; when the ranks' compositions cannot tell
 * them apart, each particle's weight is scaled by its rank's busy seconds per unit weight. Before sim_setup, or after it: then the backend is rebuilt on the new
 * subdomains and set up again with the particles' forces as they are (like a restart from a
 * checkpoint). 0, or -1 with a message on rank 0. */
int sim_balance(sim_t *sim, int measured, sim_balance_report_t *rep);

/* Adopt the cuts cuts[d][0..dims[d]] (a checkpoint's), moving particles if there are any.
 * Collective; 0, or -1 with a message on rank 0. */
int sim_set_cuts(sim_t *sim, double *const cuts[3]);
/* This rank's cut arrays (dims[d] + 1 values per axis) and grid dims. */
void sim_cuts(const sim_t *sim, const double *cuts[3], int dims[3]);

/* Busy time: the seconds this rank spent in phases that do not communicate (the pair passes, the
 * lists, the integration), summed since the last reset. Meaningful on the CPU backend only
 * (sim_busy_measured). */
double sim_busy_seconds(const sim_t *sim);
/* Host wall seconds spent in each phase of the step list (effects/plan.h PHASE_*) since set-up or
 * the last reset (benchmarks: where a step's time goes). */
const double *sim_phase_seconds(const sim_t *sim);
void sim_phase_seconds_reset(sim_t *sim);
/* The frozen particle weight in use (balance.frozen_weight, or the last fit). */
double sim_frozen_weight(const sim_t *sim);
void sim_busy_reset(sim_t *sim);
int sim_busy_measured(const sim_t *sim);

/* Collective: max / mean over the ranks of the busy seconds since the last reset (busy), of those
 * since the first set-up (busy_run; 0 when not measured) and of the particle weight. */
void sim_imbalance(sim_t *sim, double *busy, double *busy_run, double *weight);
/* Collective: the mean over the ranks of the busy seconds since the first set-up (0 when not
 * measured). */
double sim_busy_mean(sim_t *sim);
/* Collective: every rank's busy seconds since the last reset (since_move) and since the first
 * set-up (run), in rank order (slab order along an axis cut alone), into arrays of nranks values
 * on rank 0 (other ranks pass NULL). */
void sim_busy_per_rank(sim_t *sim, double *since_move, double *run);

#endif
