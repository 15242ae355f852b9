/* Per-step health checks ("hard cases stay numerically stable"): non-finite values, a displacement
 * per step above a safe fraction of the cutoff, particles lost. Local findings are combined
 * collectively so that every rank stops at the same step; the rank that saw the problem prints it.
 * Every message names the cause, the particle (id and position), the step and what to try; for the
 * time step it suggests a dt from the displacements this run has seen (step_history_t).
 */
#ifndef MESO_ENGINE_STEP_CHECK_H
#define MESO_ENGINE_STEP_CHECK_H

#include <mpi.h>
#include <stddef.h>
#include <stdint.h>

enum step_problem_kind {
  STEP_OK = 0,
  STEP_ELSEWHERE,     /* another rank found a problem */
  STEP_NONFINITE,     /* NaN or Inf in x, v or f */
  STEP_TOO_FAST,      /* moved more than plan.max_disp in one step */
  STEP_LOST,          /* particle lost (left the box, or jumped past a neighbour subdomain) */
  STEP_COUNT_CHANGED, /* global particle count changed */
  STEP_NO_MEMORY
};

/* What the steps that passed the drift check saw on this rank: the basis of the dt advice. */
typedef struct {
  double dt;          /* the run's time step */
  long steps_ok;      /* steps that passed the drift check */
  double disp_max_ok; /* largest one-step displacement over them (rc; 0: not tracked, CUDA) */
} step_history_t;

typedef struct {
  int kind;
  int64_t id;
  double x[3];
  double value; /* displacement (TOO_FAST), count of lost particles (LOST) */
  double limit;
  const char *field;          /* "position", "velocity", "force" (NONFINITE) */
  double disp_step;           /* largest displacement of this step on this rank (CPU drift) */
  const step_history_t *hist; /* set by the engine before a check (NULL: no dt advice) */
} step_problem_t;

/* Record a problem (the first one of the most serious kind is kept). */
void step_problem_note(step_problem_t *pr, int kind, int64_t id, const double x[3], double value);

/* After a drift check that passed: count the step and keep its largest displacement. */
void step_history_pass(step_history_t *h, const step_problem_t *pr);

/* Collective: combine the local problem and the particle count; print a message on the rank(s) that
 * saw a problem (into err too). n_local/n_expected: global count check (n_expected < 0: skip).
 * Returns STEP_OK on every rank, or the local kind (STEP_ELSEWHERE on ranks without one). */
int step_check_collective(step_problem_t *pr, MPI_Comm comm, long step, long n_local,
                          long n_expected, char *err, size_t errlen);

#endif
