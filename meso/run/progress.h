/* Progress line with ETA on stderr. Rule: shown by rank 0 only when output.progress is true (the
 * default) AND stderr is a terminal; redrawn in place at most once every 2 seconds. Logs and pipes
 * stay clean. */
#ifndef MESO_RUN_PROGRESS_H
#define MESO_RUN_PROGRESS_H

typedef struct {
  int on;
  long first, last;
  double t0, last_print;
} progress_t;

void progress_start(progress_t *pr, int enabled, int rank, long first, long last);
/* step: the step just done; T and p: the latest thermo sample, taken at sample_step. */
void progress_update(progress_t *pr, long step, long sample_step, double T, double p);
void progress_end(progress_t *pr);

#endif
