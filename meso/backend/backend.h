/* The backend interface: the state a simulation keeps on every rank and the ops table each backend
 * (meso/backend/cpu, meso/backend/cuda) fills. The engine (engine/step.c) runs the plan's phase
 * lists (effects/plan.h) by calling ops.phase[PHASE_x] in order; a backend that does a phase inside
 * another one (a fused kernel) leaves its slot NULL and says where it runs in phase_note, which
 * `mdpore run --explain` prints next to the phase. So the explanation is the list that runs. */
#ifndef MESO_BACKEND_BACKEND_H
#define MESO_BACKEND_BACKEND_H

#include "domain/decomp.h"
#include "domain/exchange.h"
#include "domain/ghosts.h"
#include "domain/particles.h"
#include "domain/step_check.h"
#include "effects/plan.h"
#include "scene/scene.h"

#include <stdio.h>

/* What every backend works on (one per rank). */
typedef struct sim_state {
  scene_t scene;
  plan_t plan;
  decomp_t dc;
  particles_t p; /* host particles (the CUDA backend: a copy refreshed on demand) */
  ghost_plan_t ghosts;
  xbuf_t sbuf, rbuf; /* migration buffers */
  long step;
  long n_total; /* global particle count fixed at set-up; checked every step */
  int forces_loaded, want_virial;
  int in_setup;      /* 1 while the set-up list runs */
  double virial[6];  /* local pair virial of the last force pass: 1/2 sum r_ij (x) F_ij */
  step_problem_t pr; /* problems noted by the phases of the running list */
  int failed;        /* a phase failed locally (memory): later local work is skipped */
  int host_stale;    /* the device holds a newer state than p */
  char err[2048];    /* last error message on this rank */
  void *impl;        /* the backend's own state */
  /* steps that passed the drift check (the dt advice of a stop) */
  step_history_t hist;
  double busy_seconds; /* time in the phases that do not communicate (engine/sim_balance.h) */
  /* host wall time in each phase of the step list since set-up (a GPU phase's kernels run
   * asynchronously: their time shows where the host next waits for the device) */
  double phase_seconds[PHASE_COUNT];
  double busy_total;    /* the same since the first set-up                                */
  long busy_since;      /* the step busy_seconds counts from                              */
  double cost_fit[5];   /* load-balance cost fit: its normal equations' sums over the run */
  double frozen_weight; /* load-balance weight of a frozen particle (balance.frozen_weight) */
} sim_state_t;

typedef struct backend_ops {
  const char *name;
  /* Allocate the backend's state (st->impl) once the plan and the decomposition exist. 0 or -1
   * with the reason in st->err. */
  int (*create)(sim_state_t *st);
  void (*destroy)(sim_state_t *st);
  /* Before the set-up list (the particles are in st->p): 0 or -1. */
  int (*setup_begin)(sim_state_t *st);
  /* The phases. A non-check phase returns 0, or -1 when it ran out of memory (the engine notes it
   * and runs the rest of the list, so that collective exchanges stay matched). PHASE_CHECK_DRIFT
   * and PHASE_CHECK are collective and return non-zero to stop the run (message in st->err). */
  int (*phase[PHASE_COUNT])(sim_state_t *st);
  /* For --explain: where a phase with a NULL slot runs, or a remark on one that does run
   * differently here; NULL when there is nothing to add. */
  const char *(*phase_note)(const plan_t *plan, int phase);
  /* Local thermo sums in the CPU path's order (N_mobile, KE, p[3], sum m v_a v_b [6], virial [6]);
   * NULL: the engine sums st->p. */
  int (*thermo_sums)(sim_state_t *st, double sums[17]);
  void (*sync_host)(sim_state_t *st);             /* refresh st->p from the device (NULL: none) */
  void (*want_pressure)(sim_state_t *st, int on); /* the next steps end in a thermo sample */
  void (*rebuild_lists)(sim_state_t *st);         /* sort + new lists next step (bitwise restart) */
  /* Local flux sums along `axis` (output.flux): per species s, the mobile particle count
   * sums[s] and sum v_axis sums[MESO_MAX_SPECIES + s] (frozen species: 0). NULL: the engine sums
   * st->p. 0 or -1. */
  int (*flux_sums)(sim_state_t *st, int axis, double sums[2 * MESO_MAX_SPECIES]);
  /* Test-only (meso/run/run_fault.c): set (add = 0) or add to (add = 1) component `axis` of the
   * position (field 0) or velocity (field 1) of particle `id` where this backend keeps the
   * particles between steps; a rank that does not own it changes nothing. NULL: the engine writes
   * st->p. 0 or -1. */
  int (*fault_write)(sim_state_t *st, int64_t id, int field, int axis, double value, int add);
  /* Flooding (run/run_flood.c): every owned particle of species `from` whose coordinate along
   * `axis` lies in the periodic slab [lo, hi) becomes species `to` (of equal mass; velocities
   * kept); *changed: how many on this rank. NULL: the engine changes st->p. 0 or -1. */
  int (*recolor)(sim_state_t *st, int axis, double lo, double hi, int from, int to, long *changed);
  /* For --explain's memory plan: device bytes per particle of a plan in memory mode gpu_memory
   * (enum scene_gpu_memory; auto counts as fast), the slot margin included. NULL: no device. */
  double (*device_bytes_per_particle)(const plan_t *plan, int nranks, int gpu_memory);
} backend_ops_t;

/* The CPU backend (backend/cpu/cpu_backend.c). */
extern const backend_ops_t backend_cpu_ops;
/* The CUDA backend for one rank or for several (backend/cuda/cuda_glue*.c); NULL when this build
 * has no CUDA. */
const backend_ops_t *backend_cuda_ops(int nranks);
/* Number of visible GPUs, 0 with the reason in why (always 0 without CUDA). */
int backend_cuda_device_count(char *why, size_t len);

#endif
