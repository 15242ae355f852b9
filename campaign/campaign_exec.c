/* Execute a campaign: each run is `mpiexec -n NP mdpore run scene.yaml` (plain `mdpore run` at
 * NP = 1) in its own folder, stdout and stderr to RUN/run.log, up to --jobs of them at once (the
 * slots: campaign_jobs.c chooses their number). A folder that already holds summary.json is a
 * finished run and is reused. No scheduler beyond that: bigger campaigns launch the folders'
 * commands elsewhere (--emit-scenes, commands.txt) and --collect them.
 *
 * The runs are independent processes: each its own scene, seed and folder; what they share is the
 * wall patch database in the cache, which the first to need it builds under a lock while the others
 * wait (meso/populate/wall_patches.c). So a run's result is bitwise the same at any --jobs.
 *
 * The child gets the environment this process started with (/proc/self/environ), not the one
 * MPI_Init left behind: a singleton MPI process carries variables that would make a nested mpiexec
 * think it runs inside a job. SIGINT/SIGTERM/SIGHUP are passed on to every running child (each in
 * its own process group), then we wait for them to exit: killing the campaign kills its runs and
 * leaves no process behind; their folders then have no summary (mdpore run writes it atomically at
 * the end) and are rerun. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "campaign.h"

/* The process groups of the running children, read by the signal handler: a slot is written with
 * the signals blocked, so the handler never sees a child it cannot reach. */
static volatile pid_t child_pid[CAMP_MAX_JOBS];

static void forward(int sig) {
  for (int i = 0; i < CAMP_MAX_JOBS; i++)
    if (child_pid[i] > 0) kill(-child_pid[i], sig);
  /* wait for them (up to ~10 s, then SIGKILL): whoever killed us may check at once that nothing
   * is left, and a run must not outlive its campaign to write a summary the rerun then trusts
   * half-way (it would be complete, but the campaign reported the run as not done) */
  for (int tick = 0; tick <= 1000; tick++) {
    int left = 0;
    for (int i = 0; i < CAMP_MAX_JOBS; i++) {
      if (child_pid[i] <= 0) continue;
      const pid_t w = waitpid(child_pid[i], NULL, WNOHANG);
      if (w == child_pid[i] || (w < 0 && errno == ECHILD))
        child_pid[i] = 0;
      else if (tick == 1000)
        kill(-child_pid[i], SIGKILL);
      else
        left++;
    }
    if (!left) break;
    const struct timespec ts = {0, 10000000};
    nanosleep(&ts, NULL);
  }
  signal(sig, SIG_DFL);
  raise(sig);
}

/* The environment at exec time plus the extra NAME=VALUE entries (which replace the same names),
 * NULL-terminated (malloc'd; NULL: use environ). */
static char **start_env(char **blob_out, char *const *extra) {
  FILE *f = fopen("/proc/self/environ", "rb");
  if (!f) return NULL;
  size_t cap = 1 << 16, n = 0, r;
  char *blob = malloc(cap);
  while (blob && (r = fread(blob + n, 1, cap - n - 1, f)) > 0) {
    n += r;
    if (n + 1 >= cap) {
      char *t = realloc(blob, cap *= 2);
      if (!t) free(blob);
      blob = t;
    }
  }
  fclose(f);
  if (!blob) return NULL;
  blob[n] = 0;
  size_t count = 0, n_extra = 0;
  for (size_t i = 0; i < n; i++) count += blob[i] == 0;
  while (extra && extra[n_extra]) n_extra++;
  char **env = calloc(count + n_extra + 2, sizeof *env);
  size_t k = 0;
  for (size_t i = 0; env && i < n; i += strlen(blob + i) + 1) {
    if (!blob[i]) continue;
    int replaced = 0;
    for (size_t e = 0; e < n_extra && !replaced; e++) {
      const size_t len = strcspn(extra[e], "=") + 1;
      replaced = !strncmp(blob + i, extra[e], len);
    }
    if (!replaced) env[k++] = blob + i;
  }
  for (size_t e = 0; env && e < n_extra; e++) env[k++] = extra[e];
  *blob_out = blob;
  return env;
}

pid_t camp_spawn_start(const char *dir, char **argv, const char *log, char *const *extra_env) {
  int slot = -1;
  for (int i = 0; i < CAMP_MAX_JOBS && slot < 0; i++)
    if (child_pid[i] <= 0) slot = i;
  if (slot < 0) {
    fprintf(stderr, "mdpore permeability: more than %d children at once\n", CAMP_MAX_JOBS);
    return -1;
  }
  char *blob = NULL;
  char **env = start_env(&blob, extra_env);
  sigset_t block, old;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  sigaddset(&block, SIGHUP);
  sigprocmask(SIG_BLOCK, &block, &old);
  pid_t pid = fork();
  if (pid < 0) {
    sigprocmask(SIG_SETMASK, &old, NULL);
    fprintf(stderr, "mdpore permeability: fork: %s\n", strerror(errno));
    free(env);
    free(blob);
    return -1;
  }
  if (pid == 0) {
    setpgid(0, 0);
    /* our handler (inherited until exec) would act on the parent's children: default actions,
     * then the signals unblocked (the mask survives exec) */
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    signal(SIGHUP, SIG_DFL);
    sigprocmask(SIG_SETMASK, &old, NULL);
    if (dir && chdir(dir)) _exit(126);
    if (log) {
      int fd = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd < 0) _exit(126);
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    if (env)
      execvpe(argv[0], argv, env);
    else
      execvp(argv[0], argv);
    fprintf(stderr, "mdpore permeability: cannot start %s: %s\n", argv[0], strerror(errno));
    _exit(127);
  }
  setpgid(pid, pid);
  child_pid[slot] = pid;
  sigprocmask(SIG_SETMASK, &old, NULL);
  free(env);
  free(blob);
  return pid;
}

void camp_spawn_forget(pid_t pid) {
  for (int i = 0; i < CAMP_MAX_JOBS; i++)
    if (child_pid[i] == pid) child_pid[i] = 0;
}

pid_t camp_spawn_wait(pid_t pid, int *exit_status) {
  int status = 0;
  pid_t w;
  while ((w = waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
  }
  if (w < 0) return -1;
  camp_spawn_forget(w);
  *exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return w;
}

void camp_forward_signals(int on) {
  signal(SIGINT, on ? forward : SIG_DFL);
  signal(SIGTERM, on ? forward : SIG_DFL);
  signal(SIGHUP, on ? forward : SIG_DFL);
}

int camp_spawn(const char *dir, char **argv, const char *log) {
  /* a signal to us while the child runs goes to its process group too (mdpore couple spawns
   * campaigns, which spawn runs: killing the loop kills the run) */
  void (*old_int)(int) = signal(SIGINT, forward), (*old_term)(int) = signal(SIGTERM, forward),
       (*old_hup)(int) = signal(SIGHUP, forward);
  int st = -1;
  const pid_t pid = camp_spawn_start(dir, argv, log, NULL);
  if (pid > 0 && camp_spawn_wait(pid, &st) < 0) st = -1;
  signal(SIGINT, old_int);
  signal(SIGTERM, old_term);
  signal(SIGHUP, old_hup);
  return st;
}

/* argv of one run: the launcher split on spaces, then the binary. */
static int run_argv(const camp_opts *o, char *buf, char **argv, int max) {
  int n = 0;
  if (o->np > 1) {
    snprintf(buf, 512, "%s", o->mpiexec);
    for (char *tok = strtok(buf, " "); tok && n < max - 8; tok = strtok(NULL, " ")) argv[n++] = tok;
    static char np_flag[] = "-n";
    static char np_text[32];
    snprintf(np_text, sizeof np_text, "%d", o->np);
    argv[n++] = np_flag;
    argv[n++] = np_text;
  }
  static char run_word[] = "run", scene[] = "scene.yaml";
  argv[n++] = (char *)o->self_exe;
  argv[n++] = run_word;
  argv[n++] = scene;
  argv[n] = NULL;
  return n;
}

/* --target-error-k (campaign_rounds.c): the argv that brings run r to its round's step. A run
 * without a summary starts afresh for target_step steps; one whose summary is at step S continues
 * from the checkpoint of S for target_step - S more (`mdpore run --restart FILE --steps N`, which
 * the engine continues bitwise as one uninterrupted run, its flux log cut back to S and read back
 * for the analysis). The checkpoint of S is hard-linked to checkpoint_<S>.h5 before the
 * continuation writes its own checkpoint.h5: a continuation killed after writing it, but before
 * its summary, leaves the summary at S, and the next attempt continues from that link again. The
 * buffers are static: the child has its copy once spawned. -1 (message) when the link fails. */
static int round_argv(const camp_opts *o, const camp_run *r, char **argv, int *continued) {
  static char buf[512], steps_text[32], ckpt[CAMP_PATH + 64];
  static char steps_flag[] = "--steps", restart_flag[] = "--restart";
  const int n = run_argv(o, buf, argv, 56) - 1; /* ... run | scene.yaml */
  int a = n;
  *continued = r->last_step > 0 && r->last_step < r->target_step;
  snprintf(steps_text, sizeof steps_text, "%lld",
           *continued ? r->target_step - r->last_step : r->target_step);
  argv[a++] = steps_flag;
  argv[a++] = steps_text;
  if (*continued) {
    char from[CAMP_PATH + 96], at[CAMP_PATH + 96];
    snprintf(ckpt, sizeof ckpt, "checkpoint_%lld.h5", r->last_step);
    snprintf(from, sizeof from, "%s/%s", r->dir, CAMP_CHECKPOINT_FILE);
    snprintf(at, sizeof at, "%s/%s", r->dir, ckpt);
    if (access(at, R_OK) && link(from, at)) {
      fprintf(stderr,
              "mdpore permeability: %s: cannot keep the checkpoint of step %lld to continue the "
              "run from (%s)\n",
              from, r->last_step, strerror(errno));
      return -1;
    }
    argv[a++] = restart_flag;
    argv[a++] = ckpt;
  }
  static char scene[] = "scene.yaml";
  argv[a++] = scene;
  argv[a] = NULL;
  return 0;
}

/* One slot of the pool: the run it executes and when it started. */
typedef struct {
  pid_t pid;
  int run;
  double t0;
  long long from_step; /* --target-error-k: the step a continuation started from (0: fresh) */
} slot_t;

/* The run's summary read back, or the failure counted. */
static void finish(campaign *c, int i, int st, int *failed) {
  camp_run *r = &c->runs[i];
  char why[CAMP_PATH + 256];
  if (st != 0) {
    fprintf(stderr, "mdpore permeability: run %d/%d failed (exit %d): see %s/run.log\n", i + 1,
            c->n_runs, st, r->dir);
    (*failed)++;
    return;
  }
  camp_read_summary(r, why, sizeof why);
  if (!r->have) fprintf(stderr, "mdpore permeability: warning: %s\n", why);
}

int camp_execute(const camp_opts *o, campaign *c) {
  camp_forward_signals(1);
  int on_gpu = 0;
  const int jobs = camp_jobs(o, c, &on_gpu);
  char *const *env = camp_jobs_env(o, jobs);
  /* --job-mode auto: replicas where they were measured faster (one H200, 5 runs: 2.7x the
   * sequential campaign at 6e4 particles per run, 1.5x at 6e6; processes 0.66x and 1.5x); on the
   * CPU both modes took the same time, so processes (bench/RESULTS.md, docs/permeability.md). */
  const int replicas = o->job_replicas > 0 || (o->job_replicas < 0 && on_gpu);
  if (replicas && jobs > 1 && o->np == 1 && !(o->target_error_k > 0)) {
    camp_forward_signals(0);
    return camp_execute_replicas(o, c, jobs, env);
  }
  if (o->job_replicas > 0 && jobs > 1)
    fprintf(stderr, "mdpore permeability: --job-mode replicas is for one-rank runs without "
                    "--target-error-k: the runs at once are processes\n");
  camp_progress p;
  camp_progress_start(&p, c->n_runs, jobs);
  char buf[512], *argv[64], why[CAMP_PATH + 256], path[CAMP_PATH + 64];
  const int rounds = o->target_error_k > 0; /* each run brought to its target_step */
  run_argv(o, buf, argv, 64);
  slot_t slot[CAMP_MAX_JOBS];
  int failed = 0, next = 0, ended = -1; /* ended: a run that ended, its progress line not printed */
  double ended_wall = 0;
  p.running = 0;
  for (;;) {
    /* fill the free slots (a reused run takes none) */
    while (next < c->n_runs && p.running < jobs) {
      const int i = next++;
      camp_run *r = &c->runs[i];
      snprintf(path, sizeof path, "%s/summary.json", r->dir);
      if (rounds && access(path, R_OK) == 0) camp_read_summary(r, why, sizeof why);
      if (access(path, R_OK) == 0 && (!rounds || r->last_step >= r->target_step)) {
        r->reused = 1;
        camp_read_summary(r, why, sizeof why);
        fprintf(stderr, "mdpore permeability: run %d/%d (axis %c, g = %g): reused %s\n", i + 1,
                c->n_runs, 'x' + r->axis, r->g, r->dir);
        if (!r->have) fprintf(stderr, "mdpore permeability: warning: %s\n", why);
        camp_progress_done(&p, r, 0);
        continue;
      }
      int continued = 0;
      if (rounds && round_argv(o, r, argv, &continued)) {
        finish(c, i, -1, &failed);
        camp_progress_done(&p, r, 0);
        continue;
      }
      if (continued)
        fprintf(stderr,
                "mdpore permeability: run %d/%d (axis %c, g = %g): continued from step %lld to "
                "%lld in %s\n",
                i + 1, c->n_runs, 'x' + r->axis, r->g, r->last_step, r->target_step, r->dir);
      else
        fprintf(stderr, "mdpore permeability: run %d/%d (axis %c, g = %g): running in %s\n", i + 1,
                c->n_runs, 'x' + r->axis, r->g, r->dir);
      if (!continued) unlink(path); /* a continued run keeps the summary of its checkpoint */
      slot_t *s = &slot[p.running];
      s->run = i;
      s->t0 = camp_now();
      s->from_step = continued ? r->last_step : 0;
      char log[64] = "run.log"; /* a continuation's: run_from_<S>.log, each its own */
      if (continued) snprintf(log, sizeof log, "run_from_%lld.log", r->last_step);
      s->pid = camp_spawn_start(r->dir, argv, log, env);
      if (s->pid < 0) {
        finish(c, i, -1, &failed);
        camp_progress_done(&p, r, 0);
        continue;
      }
      p.run_t0[p.running] = s->t0;
      p.running++;
    }
    /* the line of the run that ended, once its slot runs the next: "N running" is what runs now */
    if (ended >= 0) camp_progress_done(&p, &c->runs[ended], ended_wall);
    ended = -1;
    if (p.running == 0) break;
    /* the first of the running children to end frees its slot */
    int st = -1;
    pid_t w;
    while ((w = waitpid(-1, &st, 0)) < 0 && errno == EINTR) {
    }
    if (w < 0) {
      fprintf(stderr, "mdpore permeability: waitpid: %s\n", strerror(errno));
      camp_forward_signals(0);
      return -1;
    }
    int k = 0;
    while (k < p.running && slot[k].pid != w) k++;
    if (k == p.running) continue; /* not a run of ours */
    camp_spawn_forget(w);
    const slot_t done = slot[k];
    slot[k] = slot[p.running - 1];
    p.run_t0[k] = p.run_t0[p.running - 1];
    p.running--;
    finish(c, done.run, WIFEXITED(st) ? WEXITSTATUS(st) : -1, &failed);
    if (done.from_step > 0 && c->runs[done.run].last_step == c->runs[done.run].target_step) {
      /* continued to its step: the link of the checkpoint it started from is not needed again */
      snprintf(path, sizeof path, "%s/checkpoint_%lld.h5", c->runs[done.run].dir, done.from_step);
      unlink(path);
    }
    ended = done.run;
    ended_wall = camp_now() - done.t0;
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
