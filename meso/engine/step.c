/* The step and the set-up, as the plan lists them (effects/plan.h): each phase is the backend's
 * ops.phase[PHASE_x] (backend/backend.h), run in order. A phase that fails locally (out of memory)
 * is noted and the list goes on, so that every rank still enters the collective exchanges; the
 * collective checks (PHASE_CHECK_DRIFT, PHASE_CHECK) stop the run on every rank together. The step
 * index advances after the drift check: the forces of a step are keyed on its new index. */
#include "engine/sim_internal.h"

#include <string.h>

/* Phases that talk to other ranks: their time includes waiting for them, so it is not busy time
 * (the load-balance measure, engine/sim_balance.h). */
static int communicates(int phase) {
  return phase == PHASE_CHECK_DRIFT || phase == PHASE_MIGRATE || phase == PHASE_GHOSTS ||
         phase == PHASE_RHO_SYNC || phase == PHASE_CHECK;
}

int sim_run_phases(sim_t *sim, const unsigned char *list, int n) {
  sim_state_t *st = &sim->st;
  for (int k = 0; k < n; k++) {
    const int phase = list[k];
    int (*op)(sim_state_t *) = sim->ops->phase[phase];
    const int is_check = phase == PHASE_CHECK_DRIFT || phase == PHASE_CHECK;
    if (is_check) st->pr.hist = &st->hist; /* a stop suggests a dt from what passed */
    const int timed = op && !communicates(phase);
    const double t0 = op ? MPI_Wtime() : 0;
    const int rc = op ? op(st) : 0;
    if (op) {
      const double dt = MPI_Wtime() - t0;
      if (!st->in_setup) st->phase_seconds[phase] += dt;
      if (timed) {
        st->busy_seconds += dt;
        st->busy_total += dt;
      }
    }
    if (is_check) {
      if (rc) return rc;
      if (phase == PHASE_CHECK_DRIFT && !st->in_setup) step_history_pass(&st->hist, &st->pr);
      memset(&st->pr, 0, sizeof st->pr);
      if (phase == PHASE_CHECK_DRIFT) st->step++;
      continue;
    }
    if (rc) {
      step_problem_note(&st->pr, STEP_NO_MEMORY, -1, NULL, 0);
      st->failed = 1;
    }
  }
  return 0;
}

int sim_step(sim_t *sim) {
  memset(&sim->st.pr, 0, sizeof sim->st.pr);
  sim->st.failed = 0;
  return sim_run_phases(sim, sim->st.plan.step, sim->st.plan.n_step);
}
