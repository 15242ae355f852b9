/* Collective per-step health checks (see step_check.h). */
#include "step_check.h"

#include <stdio.h>
#include <string.h>

void step_problem_note(step_problem_t *pr, int kind, int64_t id, const double x[3], double value) {
  if (kind <= pr->kind) return;
  pr->kind = kind;
  pr->id = id;
  if (x) memcpy(pr->x, x, sizeof pr->x);
  pr->value = value;
}

static void describe(const step_problem_t *pr, long step, char *err, size_t errlen) {
  const char *head = "mdpore: step";
  switch (pr->kind) {
  case STEP_NONFINITE:
    snprintf(err, errlen,
             "%s %ld: particle %lld at (%g, %g, %g): non-finite %s (NaN or Inf): the integration "
             "blew up: time step too large or forces too strong",
             head, step, (long long)pr->id, pr->x[0], pr->x[1], pr->x[2],
             pr->field ? pr->field : "value");
    break;
  case STEP_TOO_FAST:
    snprintf(err, errlen,
             "%s %ld: particle %lld at (%g, %g, %g) moved %g in one step (safe limit %g = half the "
             "cutoff): time step too large or forcing too strong",
             head, step, (long long)pr->id, pr->x[0], pr->x[1], pr->x[2], pr->value, pr->limit);
    break;
  case STEP_LOST:
    snprintf(
        err, errlen,
        "%s %ld: particle lost: %g particle(s) left the box through a non-periodic face or moved "
        "farther than a neighbouring subdomain; first: particle %lld at (%g, %g, %g)",
        head, step, pr->value, (long long)pr->id, pr->x[0], pr->x[1], pr->x[2]);
    break;
  case STEP_COUNT_CHANGED:
    snprintf(err, errlen,
             "%s %ld: particle lost: the global particle count changed from %ld to %ld", head, step,
             (long)pr->limit, (long)pr->value);
    break;
  case STEP_NO_MEMORY:
    snprintf(err, errlen, "%s %ld: out of memory", head, step);
    break;
  default:
    snprintf(err, errlen, "%s %ld: stopped: another rank found a problem (see its message)", head,
             step);
  }
}

int step_check_collective(step_problem_t *pr, MPI_Comm comm, long step, long n_local,
                          long n_expected, char *err, size_t errlen) {
  long v[2] = {pr->kind != STEP_OK, n_local}, g[2];
  MPI_Allreduce(v, g, 2, MPI_LONG, MPI_SUM, comm);
  int rank;
  MPI_Comm_rank(comm, &rank);
  if (g[0] == 0 && (n_expected < 0 || g[1] == n_expected)) return STEP_OK;
  if (g[0] == 0) { /* only the count is off: report it once */
    pr->kind = STEP_COUNT_CHANGED;
    pr->limit = (double)n_expected;
    pr->value = (double)g[1];
    describe(pr, step, err, errlen);
    if (rank == 0) fprintf(stderr, "%s\n", err);
    return STEP_COUNT_CHANGED;
  }
  if (pr->kind == STEP_OK) {
    pr->kind = STEP_ELSEWHERE;
    describe(pr, step, err, errlen);
    return STEP_ELSEWHERE;
  }
  describe(pr, step, err, errlen);
  fprintf(stderr, "%s (rank %d)\n", err, rank);
  return pr->kind;
}
