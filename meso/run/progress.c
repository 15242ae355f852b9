/* Progress + ETA on stderr (see progress.h). */
#include "run/progress.h"

#include <mpi.h>
#include <stdio.h>
#include <unistd.h>

void progress_start(progress_t *pr, int enabled, int rank, long first, long last) {
  pr->on = enabled && rank == 0 && isatty(fileno(stderr));
  pr->first = first;
  pr->last = last;
  pr->t0 = pr->last_print = MPI_Wtime();
}

void progress_update(progress_t *pr, long step, long sample_step, double T, double p) {
  if (!pr->on) return;
  const double now = MPI_Wtime();
  if (now - pr->last_print < 2.0 && step != pr->last) return;
  pr->last_print = now;
  const double done = (double)(step - pr->first), total = (double)(pr->last - pr->first);
  const double eta = done > 0 ? (now - pr->t0) * (total - done) / done : 0;
  fprintf(stderr,
          "\rstep %ld / %ld (%3.0f%%)  T = %.4f  p = %.4g (step %ld)  elapsed %.0f s  ETA "
          "%02d:%02d:%02d   ",
          step, pr->last, total > 0 ? 100 * done / total : 100.0, T, p, sample_step, now - pr->t0,
          (int)(eta / 3600), (int)(eta / 60) % 60, (int)eta % 60);
  fflush(stderr);
}

void progress_end(progress_t *pr) {
  if (pr->on) fputc('\n', stderr);
}
