/* Progress and ETA over the whole campaign, on stderr: runs done / total, how many are running,
 * elapsed, and the time left estimated from the finished runs. The rate is one run's: the
 * particle-steps per second of the runs executed by this process (each run's own wall time, so at
 * --jobs N it is the rate of a run that shares the machine with the others). The work left is
 * (runs not done) x (mean particle-steps of a finished run), less what the running ones have done
 * at that rate so far, and it is shared by min(jobs, runs not done) runs at once. At --jobs 1 this
 * is (runs left) x (mean size) / rate, as it always was. Reused runs count as done and into the
 * mean size, not into the rate. */
#include <stdio.h>
#include <time.h>

#include "campaign.h"

double camp_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void camp_progress_start(camp_progress *p, int total, int jobs) {
  p->t0 = camp_now();
  p->total = total;
  p->jobs = jobs > 0 ? jobs : 1;
  p->running = 0;
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

/* One run counted done (its particle-steps into the mean size, and into the rate when executed). */
static void count_done(camp_progress *p, const camp_run *r, double wall_seconds) {
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
}

static void print_line(camp_progress *p);

void camp_progress_done(camp_progress *p, const camp_run *r, double wall_seconds) {
  count_done(p, r, wall_seconds);
  print_line(p);
}

void camp_progress_batch_done(camp_progress *p, const camp_run *const *runs, int n,
                              double wall_seconds) {
  for (int i = 0; i < n; i++) count_done(p, runs[i], wall_seconds);
  print_line(p);
}

static void print_line(camp_progress *p) {
  char el[32], eta[128] = "unknown (no run executed yet)", running[32] = "";
  const double now = camp_now();
  hms(now - p->t0, el, sizeof el);
  if (p->done == p->total)
    snprintf(eta, sizeof eta, "0s");
  else if (p->ps_exec > 0 && p->s_exec > 0 && p->n_finished > 0) {
    const double rate = p->ps_exec / p->s_exec;
    const int not_done = p->total - p->done;
    const double mean = p->ps_done_all / p->n_finished;
    double work = (double)not_done * mean;
    for (int k = 0; k < p->running; k++) { /* a running run has done at most a mean run */
      const double d = rate * (now - p->run_t0[k]);
      work -= d < mean ? d : mean;
    }
    const int at_once = not_done < p->jobs ? not_done : p->jobs;
    const double left = work > 0 ? work / (rate * at_once) : 0;
    char t[32];
    hms(left, t, sizeof t);
    snprintf(eta, sizeof eta, "%s (at %.3g M particle-steps/s%s)", t, rate * at_once * 1e-6,
             at_once > 1 ? ", the runs at once together" : "");
  }
  if (p->jobs > 1) snprintf(running, sizeof running, ", %d running", p->running);
  fprintf(stderr, "mdpore permeability: progress %d/%d runs done%s, elapsed %s, remaining %s\n",
          p->done, p->total, running, el, eta);
}
