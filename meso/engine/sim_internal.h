/* The simulation object behind sim.h (engine-internal, and for benchmarks and tests that look at
 * the backend's state): the per-rank state every backend works on and the backend's ops table. */
#ifndef MESO_ENGINE_SIM_INTERNAL_H
#define MESO_ENGINE_SIM_INTERNAL_H

#include "backend/backend.h"
#include "engine/sim.h"

struct sim {
  sim_state_t st;
  const backend_ops_t *ops;
  int is_setup;
};

/* Run one phase list of the plan (engine/step.c), adding to the problems already noted in
 * sim->st.pr. 0, or the collective check's non-zero code. */
int sim_run_phases(sim_t *sim, const unsigned char *list, int n);
/* The ops table of scene backend `backend` (enum scene_backend) on `nranks` ranks; NULL when this
 * build cannot run it (engine/backend_select.c). */
const backend_ops_t *sim_backend_ops(int backend, int nranks);

/* The backend state (for tests and benchmarks that query the device). */
static inline sim_state_t *sim_state(sim_t *sim) {
  return &sim->st;
}

#endif
