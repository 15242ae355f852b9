/* --job-mode replicas: a campaign's runs stepped in one process per batch (campaign.h).
 *
 * The runs that have no summary yet are taken in order, `jobs` at a time; each batch is one
 * `mdpore run --replicas DIR1/scene.yaml DIR2/scene.yaml ...` (meso/run/run_replicas.c): one
 * start-up and, on a GPU, one context, the runs' kernels overlapping on per-thread streams. Each run
 * writes into its own folder the files it writes alone (the summary names its outputs by the paths
 * it opened: absolute here). The batch's stdout and stderr go to the first run's run.log, which
 * every other run of the batch gets as a hard link. A run that failed has no summary; the others of
 * its batch finish. The runs' results are the same bits as in process mode (each replica is its own
 * simulation; bench/RESULTS.md measures the wall time of the two modes). */
#define _GNU_SOURCE
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "campaign.h"

/* A run executed in the batch: its summary read back, or the failure counted. */
static void finish(campaign *c, int i, int batch_status, int *failed) {
  camp_run *r = &c->runs[i];
  char path[CAMP_PATH + 64], why[CAMP_PATH + 256];
  snprintf(path, sizeof path, "%s/summary.json", r->dir);
  if (access(path, R_OK)) {
    fprintf(stderr, "mdpore permeability: run %d/%d failed (its batch exited %d): see %s/run.log\n",
            i + 1, c->n_runs, batch_status, r->dir);
    (*failed)++;
    return;
  }
  camp_read_summary(r, why, sizeof why);
  if (!r->have) fprintf(stderr, "mdpore permeability: warning: %s\n", why);
}

int camp_execute_replicas(const camp_opts *o, campaign *c, int jobs, char *const *env) {
  camp_forward_signals(1);
  camp_progress p;
  camp_progress_start(&p, c->n_runs, jobs);
  static char run_word[] = "run", replicas_flag[] = "--replicas";
  static char scene[CAMP_MAX_JOBS][CAMP_PATH + 16];
  char *argv[CAMP_MAX_JOBS + 4], path[CAMP_PATH + 64], why[CAMP_PATH + 256], log[CAMP_PATH + 16];
  int batch[CAMP_MAX_JOBS], failed = 0, next = 0;
  p.running = 0;
  while (next < c->n_runs) {
    int k = 0;
    while (next < c->n_runs && k < jobs) {
      const int i = next++;
      camp_run *r = &c->runs[i];
      snprintf(path, sizeof path, "%s/summary.json", r->dir);
      if (access(path, R_OK) == 0) {
        r->reused = 1;
        camp_read_summary(r, why, sizeof why);
        fprintf(stderr, "mdpore permeability: run %d/%d (axis %c, g = %g): reused %s\n", i + 1,
                c->n_runs, 'x' + r->axis, r->g, r->dir);
        if (!r->have) fprintf(stderr, "mdpore permeability: warning: %s\n", why);
        camp_progress_done(&p, r, 0);
        continue;
      }
      fprintf(stderr, "mdpore permeability: run %d/%d (axis %c, g = %g): running in %s\n", i + 1,
              c->n_runs, 'x' + r->axis, r->g, r->dir);
      batch[k++] = i;
    }
    if (k == 0) break;
    int n = 0;
    argv[n++] = (char *)o->self_exe;
    argv[n++] = run_word;
    argv[n++] = replicas_flag;
    for (int b = 0; b < k; b++) {
      snprintf(scene[b], sizeof scene[b], "%s/scene.yaml", c->runs[batch[b]].dir);
      argv[n++] = scene[b];
    }
    argv[n] = NULL;
    snprintf(log, sizeof log, "%s/run.log", c->runs[batch[0]].dir);
    fprintf(stderr,
            "mdpore permeability: %d run%s at once in one process (--job-mode replicas; log: "
            "%s)\n",
            k, k > 1 ? "s" : "", log);
    /* every run's run.log: the batch's (made here, so that the links exist before it runs) */
    FILE *made = fopen(log, "w");
    if (made) fclose(made);
    for (int b = 1; b < k; b++) {
      snprintf(path, sizeof path, "%s/run.log", c->runs[batch[b]].dir);
      unlink(path);
      if (link(log, path))
        fprintf(stderr, "mdpore permeability: warning: cannot link %s to %s\n", path, log);
    }
    const double t0 = camp_now();
    int status = -1;
    const pid_t pid = camp_spawn_start(NULL, argv, log, env);
    if (pid > 0) {
      for (int b = 0; b < k; b++) p.run_t0[b] = t0;
      p.running = k;
      if (camp_spawn_wait(pid, &status) < 0) status = -1;
    }
    p.running = 0;
    const double wall = camp_now() - t0;
    const camp_run *ended[CAMP_MAX_JOBS];
    for (int b = 0; b < k; b++) {
      finish(c, batch[b], status, &failed);
      ended[b] = &c->runs[batch[b]];
    }
    camp_progress_batch_done(&p, ended, k, wall);
  }
  camp_forward_signals(0);
  if (failed) {
    fprintf(stderr,
            "mdpore permeability: %d of %d runs failed; rerun the same command to retry "
            "them (finished runs are reused)\n",
            failed, c->n_runs);
    return -1;
  }
  return 0;
}
