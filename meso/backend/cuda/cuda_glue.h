/* The host glue of the CUDA backend (internal to meso/backend/cuda): the backend state behind
 * sim_state_t.impl and what the one-rank and several-rank ops tables share. */
#ifndef MESO_BACKEND_CUDA_GLUE_H
#define MESO_BACKEND_CUDA_GLUE_H

#include "backend/backend.h"
#include "backend/cuda/cuda_backend.h"
#include "domain/migrate.h"

typedef struct {
  cuda_sim_t *g;
  cuda_problem_t cp;   /* the device's problem record of the running list */
  migrate_report_t mr; /* several ranks: particles lost in the host-side migration */
  int finished;        /* the finishing kernel ran in this list (kick or set-up check) */
  /* Several ranks: host copies of the boundary set + its ghosts, of the leavers/arrivals, and the
   * densities of the boundary set + ghosts (cuda_glue_halo.c). */
  particles_t halo_b, halo_m;
  decomp_t halo_dc; /* dc without the self-exchange along axes not cut between ranks */
  xbuf_t mig_in;    /* one axis cut: the records that stay and arrive (migrate_records) */
  double *halo_rho;
  int halo_rho_cap, halo_ready;
  int mode_told; /* the memory mode was printed (after the first upload) */
} cuda_glue_t;

static inline cuda_glue_t *cuda_glue(sim_state_t *st) {
  return st->impl;
}

/* Shared by both ops tables (cuda_glue.c). */
int cuda_glue_create(sim_state_t *st);
void cuda_glue_destroy(sim_state_t *st);
int cuda_glue_setup_begin(sim_state_t *st);
int cuda_glue_kick_drift(sim_state_t *st);
int cuda_glue_predict(sim_state_t *st);
int cuda_glue_kick(sim_state_t *st);
int cuda_glue_check(sim_state_t *st);
int cuda_glue_thermo_sums(sim_state_t *st, double sums[17]);
int cuda_glue_flux_sums(sim_state_t *st, int axis, double sums[2 * MESO_MAX_SPECIES]);
void cuda_glue_sync_host(sim_state_t *st);
void cuda_glue_want_pressure(sim_state_t *st, int on);
void cuda_glue_rebuild_lists(sim_state_t *st);
int cuda_glue_fault_write(sim_state_t *st, int64_t id, int field, int axis, double value, int add);
int cuda_glue_recolor(sim_state_t *st, int axis, double lo, double hi, int from, int to,
                      long *changed);
const char *cuda_glue_phase_note(int phase);

extern const backend_ops_t cuda_ops_one_rank, cuda_ops_ranks;

#endif
