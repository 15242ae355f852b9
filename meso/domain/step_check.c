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

void step_history_pass(step_history_t *h, const step_problem_t *pr) {
  h->steps_ok++;
  if (pr->disp_step > h->disp_max_ok) h->disp_max_ok = pr->disp_step;
}

/* What the run saw before this step, and a dt to try. The one-step displacement of the fastest
 * particle grows about linearly with dt (v dt + f dt^2 / 2m with v set by kT), so
 *   dt_try = dt * (limit / 2) / displacement
 * keeps it at half the safe limit; without a displacement (non-finite values), dt / 2. */
static void dt_advice(const step_problem_t *pr, double displacement, char *out, size_t len) {
  const step_history_t *h = pr->hist;
  if (!h || !(h->dt > 0)) {
    snprintf(out, len, "try a smaller dt (run.dt)");
    return;
  }
  const double dt_try =
      displacement > 0 && pr->limit > 0 ? h->dt * 0.5 * pr->limit / displacement : 0.5 * h->dt;
  char seen[256] = "";
  if (h->steps_ok > 0 && h->disp_max_ok > 0)
    snprintf(seen, sizeof seen,
             "; the %ld step(s) before ran at dt %g with displacements up to %.3g rc on this rank "
             "(dt <= %.3g keeps those at half the limit)",
             h->steps_ok, h->dt, h->disp_max_ok,
             pr->limit > 0 ? h->dt * 0.5 * pr->limit / h->disp_max_ok : h->dt);
  else if (h->steps_ok > 0)
    snprintf(seen, sizeof seen, "; the %ld step(s) before ran at dt %g", h->steps_ok, h->dt);
  snprintf(out, len, "try run.dt <= %.3g (dt %g now)%s, or weaker forcing", dt_try, h->dt, seen);
}

static void describe(const step_problem_t *pr, long step, char *err, size_t errlen) {
  const char *head = "mdpore: step";
  char advice[512];
  switch (pr->kind) {
  case STEP_NONFINITE:
    dt_advice(pr, 0, advice, sizeof advice);
    snprintf(err, errlen,
             "%s %ld: particle %lld at (%g, %g, %g): non-finite %s (NaN or Inf): the integration "
             "blew up: time step too large or forces too strong: %s; check the pair parameters",
             head, step, (long long)pr->id, pr->x[0], pr->x[1], pr->x[2],
             pr->field ? pr->field : "value", advice);
    break;
  case STEP_TOO_FAST:
    dt_advice(pr, pr->value, advice, sizeof advice);
    snprintf(err, errlen,
             "%s %ld: particle %lld at (%g, %g, %g) moved %g rc in one step (safe limit %g = half "
             "the cutoff): time step too large or forcing too strong: %s",
             head, step, (long long)pr->id, pr->x[0], pr->x[1], pr->x[2], pr->value, pr->limit,
             advice);
    break;
  case STEP_LOST:
    dt_advice(pr, 0, advice, sizeof advice);
    snprintf(err, errlen,
             "%s %ld: particle lost: %g particle(s) left the box through a non-periodic face or "
             "moved farther than a neighbouring subdomain; first: particle %lld at (%g, %g, %g). "
             "Try walls on the non-periodic faces (box_walls, bounce_back) or %s",
             head, step, pr->value, (long long)pr->id, pr->x[0], pr->x[1], pr->x[2], advice);
    break;
  case STEP_COUNT_CHANGED:
    snprintf(err, errlen,
             "%s %ld: particle lost: the global particle count changed from %ld to %ld (a "
             "migration or wall lost track of particles; try a smaller dt, or report it with the "
             "scene)",
             head, step, (long)pr->limit, (long)pr->value);
    break;
  case STEP_NO_MEMORY:
    snprintf(err, errlen, "%s %ld: out of memory (try more ranks or a smaller box)", head, step);
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
