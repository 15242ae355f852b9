/* The CUDA backend's ops (backend/backend.h) on one rank, one GPU, and what the several-rank table
 * (cuda_glue_halo.c) shares: the particles stay on the device between steps; the host copy is
 * refreshed only when an output asks (sync_host). Problems found on the device are recorded there
 * and reported by the list's check phase, once per step. */
#include "backend/cuda/cuda_glue.h"
#include "domain/particle_store.h"

#include <stdlib.h>
#include <string.h>

int backend_cuda_device_count(char *why, size_t len) {
  return cuda_device_count(why, len);
}

const backend_ops_t *backend_cuda_ops(int nranks) {
  return nranks > 1 ? &cuda_ops_ranks : &cuda_ops_one_rank;
}

cuda_sim_t *cuda_backend_device(const sim_state_t *st, const char *backend_name) {
  if (!backend_name || strcmp(backend_name, "cuda") || !st->impl) return NULL;
  return ((const cuda_glue_t *)st->impl)->g;
}

int cuda_glue_create(sim_state_t *st) {
  cuda_glue_t *c = calloc(1, sizeof *c);
  if (!c) {
    snprintf(st->err, sizeof st->err, "out of memory creating the CUDA backend");
    return -1;
  }
  st->impl = c;
  c->g = cuda_sim_create(&st->plan, &st->scene, st->dc.lo, st->dc.hi, st->dc.dims, st->err,
                         sizeof st->err);
  if (!c->g) return -1;
  if (st->dc.rank == 0)
    printf("mdpore: backend cuda on %s (%s-precision pair math), %d rank(s)\n",
           cuda_sim_device_name(c->g), cuda_sim_double_precision() ? "double" : "single",
           st->dc.nranks);
  return 0;
}

void cuda_glue_destroy(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  if (!c) return;
  if (c->g) cuda_sim_destroy(c->g);
  free(c);
  st->impl = NULL;
}

int cuda_glue_setup_begin(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  memset(&c->cp, 0, sizeof c->cp);
  memset(&c->mr, 0, sizeof c->mr);
  c->finished = 0;
  st->host_stale = 1;
  if (cuda_sim_upload(c->g, &st->p)) return -1;
  /* the mode is settled at the first upload (auto: compact when the lists would not fit) */
  if (!c->mode_told && st->dc.rank == 0)
    printf("mdpore: GPU memory mode %s (%s)\n", cuda_sim_memory_mode(c->g),
           strcmp(cuda_sim_memory_mode(c->g), "compact")
               ? "neighbour lists of each step"
               : "no neighbour lists: the force pass scans the bins again");
  c->mode_told = 1;
  return 0;
}

int cuda_glue_kick_drift(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  memset(&c->cp, 0, sizeof c->cp);
  memset(&c->mr, 0, sizeof c->mr);
  c->finished = 0;
  st->host_stale = 1;
  cuda_idle_mark(c->g, CUDA_IDLE_STEP_END, 1); /* the step's first pass follows */
  if (st->dc.nranks > 1) return cuda_halo_kick_drift(c->g);
  return cuda_sim_kick_drift(c->g, st->want_virial);
}

int cuda_glue_predict(sim_state_t *st) {
  if (st->failed) return 0;
  return st->dc.nranks > 1 ? cuda_halo_predict(cuda_glue(st)->g, st->in_setup)
                           : cuda_sim_predict(cuda_glue(st)->g, st->in_setup);
}

/* A step on several ranks: the particle forces of the named effects and the second half kick, in
 * one kernel (one rank: the force pass does it, kick_done). */
int cuda_glue_kick(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  if (st->failed) return 0;
  c->finished = 1;
  return cuda_sim_finish(c->g, 1, 1);
}

/* The end of a list: at set-up the finishing kernel (particle forces unless loaded, finite check);
 * then the device's problem record, the host migration's losses and this rank's failures, combined
 * over the ranks. */
int cuda_glue_check(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  cuda_idle_mark(c->g, CUDA_IDLE_STEP_END, 0); /* closed by the next kick-drift */
  int rc = st->failed;
  if (!rc && !c->finished) rc = cuda_sim_finish(c->g, !st->forces_loaded || !st->in_setup, 0);
  if (!rc) rc = cuda_sim_fetch_problems(c->g, &c->cp);
  step_problem_t pr = st->pr;
  if (rc) step_problem_note(&pr, STEP_NO_MEMORY, -1, NULL, 0);
  const cuda_problem_t *cp = &c->cp;
  /* The CPU path stops at its drift check, before the migration; here the drift's problems wait
   * for this check, so a particle the drift found non-finite (or too fast) has meanwhile been
   * dropped as lost by the host migration (several ranks): the drift's record names the cause. */
  if (c->mr.n_lost && !(cp->kind && cp->at_drift))
    step_problem_note(&pr, STEP_LOST, c->mr.lost_id, c->mr.lost_x, (double)c->mr.n_lost);
  if (cp->kind) {
    step_problem_note(&pr, cp->kind, cp->id, cp->x, cp->value);
    if (cp->kind == CUDA_TOO_FAST) pr.limit = st->plan.max_disp;
    if (cp->kind == CUDA_NONFINITE) pr.field = cp->at_drift ? "velocity or position" : "force";
    if (cp->kind == CUDA_LOST) pr.value = (double)cp->count;
  }
  c->finished = 0;
  return step_check_collective(&pr, st->dc.cart, st->step, cuda_sim_count(c->g), st->n_total,
                               st->err, sizeof st->err);
}

int cuda_glue_thermo_sums(sim_state_t *st, double sums[17]) {
  return cuda_sim_thermo_sums(cuda_glue(st)->g, sums);
}

int cuda_glue_flux_sums(sim_state_t *st, int axis, double sums[2 * MESO_MAX_SPECIES]) {
  return cuda_sim_flux_sums(cuda_glue(st)->g, axis, sums);
}

void cuda_glue_want_pressure(sim_state_t *st, int on) {
  cuda_sim_want_pressure(cuda_glue(st)->g, on);
}

void cuda_glue_rebuild_lists(sim_state_t *st) {
  cuda_sim_rebuild_lists(cuda_glue(st)->g);
}

/* The test-only fault hook writes the device copy, which is the particles' home between steps
 * (a write to st->p would be overwritten by the next download, and never seen by the device). */
int cuda_glue_fault_write(sim_state_t *st, int64_t id, int field, int axis, double value, int add) {
  st->host_stale = 1;
  return cuda_sim_fault_write(cuda_glue(st)->g, id, field, axis, value, add);
}

/* Flooding: the device copy is the particles' home between steps (as for the fault hook). */
int cuda_glue_recolor(sim_state_t *st, int axis, double lo, double hi, int from, int to,
                      long *changed) {
  st->host_stale = 1;
  const double box_lo = st->scene.box_lo[axis], box_len = st->scene.box_hi[axis] - box_lo;
  return cuda_sim_recolor(cuda_glue(st)->g, axis, lo, hi, box_lo, box_len, from, to, changed);
}

void cuda_glue_sync_host(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  if (!c || !st->host_stale) return;
  if (pstore_reserve(&st->p, cuda_sim_count(c->g) + 1) == 0 && cuda_sim_download(c->g, &st->p) == 0)
    st->host_stale = 0;
}

/* One rank: the set-up sorts here (with the loaded forces); a step leaves the sort to the neighbour
 * phase. */
static int sort(sim_state_t *st) {
  if (st->failed) return 0;
  return cuda_sim_sort(cuda_glue(st)->g, st->in_setup, st->forces_loaded && st->in_setup,
                       st->want_virial);
}

static int neighbours(sim_state_t *st) {
  if (st->failed) return 0;
  return cuda_sim_neighbours(cuda_glue(st)->g);
}

/* A step's force pass also ends each particle's step (particle forces, finite check, second half
 * kick: kick_done below); the set-up's leaves it to the check. */
static int pair_forces(sim_state_t *st) {
  if (st->failed) return 0;
  return cuda_sim_pair_forces(cuda_glue(st)->g, st->step, st->want_virial,
                              st->in_setup && st->forces_loaded, !st->in_setup);
}

/* The kick phase of a step on one rank: the force pass did its work (pair_forces). */
static int kick_done(sim_state_t *st) {
  if (!st->failed) cuda_glue(st)->finished = 1;
  return 0;
}

/* --explain remarks shared by both tables: where the fused phases run. */
const char *cuda_glue_phase_note(int phase) {
  switch (phase) {
  case PHASE_AFTER_DRIFT:
    return "in the kick_drift kernel, per particle, with its position before the drift";
  case PHASE_CHECK_DRIFT:
    return "the device records the problems; the step's check reports them";
  case PHASE_DENSITY:
    return "in the neighbour scan";
  case PHASE_WALL_FIELD:
    return "in the neighbour phase, one pass over the lists after the scan";
  case PHASE_PARTICLE_FORCES:
    return "in the finishing kernel (with the kick; at set-up before the check)";
  default:
    return NULL;
  }
}

static const char *phase_note(const plan_t *plan, int phase) {
  switch (phase) {
  case PHASE_MIGRATE:
    return "one rank: the periodic wrap runs in the kick_drift kernel";
  case PHASE_SORT:
    if (cuda_plan_static_tail(plan))
      return "a step's radix sort by cell runs in the neighbour phase, after the prediction (it "
             "does not carry the forces); the static frozen particles are sorted once into the "
             "slots after the others and never sorted or drifted again (the static tail; not with "
             "a skin or --gpu-memory compact)";
    return "a step's radix sort by cell runs in the neighbour phase, after the prediction (it does "
           "not carry the forces); with a skin only when a particle moved more than skin/2";
  case PHASE_GHOSTS:
    return "one rank: cells wrap periodically on the device, no ghosts";
  case PHASE_NEIGHBOURS:
    return "one bin scan builds the lists and sums the densities (--gpu-memory compact, or auto "
           "when the lists would not fit: no lists, the force pass scans the bins again)";
  case PHASE_RHO_SYNC:
    return "one rank: no ghosts";
  case PHASE_PARTICLE_FORCES:
    return "at the end of the force pass's thread, with the kick (at set-up: the finishing kernel, "
           "before the check)";
  case PHASE_KICK:
    return "in the force pass (its thread holds the particle's whole force): no kernel of its own";
  default:
    return cuda_glue_phase_note(phase);
  }
}

const backend_ops_t cuda_ops_one_rank = {
    .name = "cuda",
    .create = cuda_glue_create,
    .destroy = cuda_glue_destroy,
    .setup_begin = cuda_glue_setup_begin,
    .phase =
        {
            [PHASE_KICK_DRIFT] = cuda_glue_kick_drift,
            [PHASE_SORT] = sort,
            [PHASE_PREDICT] = cuda_glue_predict,
            [PHASE_NEIGHBOURS] = neighbours,
            [PHASE_PAIR_FORCES] = pair_forces,
            [PHASE_KICK] = kick_done,
            [PHASE_CHECK] = cuda_glue_check,
        },
    .phase_note = phase_note,
    .thermo_sums = cuda_glue_thermo_sums,
    .sync_host = cuda_glue_sync_host,
    .want_pressure = cuda_glue_want_pressure,
    .rebuild_lists = cuda_glue_rebuild_lists,
    .flux_sums = cuda_glue_flux_sums,
    .fault_write = cuda_glue_fault_write,
    .recolor = cuda_glue_recolor,
    .device_bytes_per_particle = cuda_device_bytes_per_particle,
};
