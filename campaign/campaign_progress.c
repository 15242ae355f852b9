/* Progress and ETA over the whole campaign, on stderr: runs done / total, elapsed, and the time
 * left estimated from the finished runs: (runs left) x (mean particle-steps of a finished run) /
 * (particle-steps per second of the runs executed by this process). Reused runs count as done and
 * into the mean size, not into the rate. */
#include <stdio.h>
#include <time.h>

#include "campaign.h"

double camp_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void camp_progress_start(camp_progress *p, int total) {
  p->t0 = camp_now();
  p->total = total;
  p->done = 0;
  p->ps_done_all = p->ps_exec = p->s_exec = 0;
  p->n_finished = 0;
}

static void hms(double s, char *out, int len) {
  long t = (long)(s + 0.5);
  if (t >= 3600)
    snprintf(out, len, "%ldh%02ldm%02lds", t / 3600, t / 60 % 60, t % 60);
  else if (t >= 60)
    snprintf(out, len, "%ldm%02lds", t / 60, t % 60);
  else
    snprintf(out, len, "%lds", t);
}

void camp_progress_done(camp_progress *p, const camp_run *r, double wall_seconds) {
  p->done++;
  double ps = (double)r->steps * (double)r->particles;
  if (ps > 0) {
    p->ps_done_all += ps;
    p->n_finished++;
    if (!r->reused) {
      p->ps_exec += ps;
      p->s_exec += wall_seconds;
    }
  }
  char el[32], eta[128] = "unknown (no run executed yet)";
  hms(camp_now() - p->t0, el, sizeof el);
  if (p->done == p->total)
    snprintf(eta, sizeof eta, "0s");
  else if (p->ps_exec > 0 && p->s_exec > 0 && p->n_finished > 0) {
    double rate = p->ps_exec / p->s_exec;
    double left = (double)(p->total - p->done) * (p->ps_done_all / p->n_finished) / rate;
    char t[32];
    hms(left, t, sizeof t);
    snprintf(eta, sizeof eta, "%s (at %.3g M particle-steps/s)", t, rate * 1e-6);
  }
  fprintf(stderr, "mdpore permeability: progress %d/%d runs done, elapsed %s, remaining %s\n",
          p->done, p->total, el, eta);
}
