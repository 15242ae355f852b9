/* Execute a campaign: the runs one after another, each `mpiexec -n NP mdpore run scene.yaml` (plain
 * `mdpore run` at NP = 1) in its own folder, stdout and stderr to RUN/run.log. A folder that already
 * holds summary.json is a finished run and is reused. No scheduler: bigger campaigns launch the
 * folders' commands elsewhere (--emit-scenes, commands.txt) and --collect them.
 *
 * The child gets the environment this process started with (/proc/self/environ), not the one
 * MPI_Init left behind: a singleton MPI process carries variables that would make a nested mpiexec
 * think it runs inside a job. SIGINT/SIGTERM/SIGHUP are passed on to the running child (its process
 * group), so killing the campaign kills its run; the folder then has no summary and is rerun. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "campaign.h"

static volatile pid_t child_pid = 0;

static void forward(int sig) {
  if (child_pid > 0) kill(-child_pid, sig);
  signal(sig, SIG_DFL);
  raise(sig);
}

/* The environment at exec time, NULL-terminated (malloc'd; NULL: use environ). */
static char **start_env(char **blob_out) {
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
  size_t count = 0;
  for (size_t i = 0; i < n; i++) count += blob[i] == 0;
  char **env = calloc(count + 2, sizeof *env);
  size_t k = 0;
  for (size_t i = 0; env && i < n; i += strlen(blob + i) + 1)
    if (blob[i]) env[k++] = blob + i;
  *blob_out = blob;
  return env;
}

int camp_spawn(const char *dir, char **argv, const char *log) {
  char *blob = NULL;
  char **env = start_env(&blob);
  pid_t pid = fork();
  if (pid < 0) {
    fprintf(stderr, "mdpore permeability: fork: %s\n", strerror(errno));
    return -1;
  }
  if (pid == 0) {
    setpgid(0, 0);
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
  child_pid = pid;
  /* a signal to us while the child runs goes to its process group too (mdpore couple spawns
   * campaigns, which spawn runs: killing the loop kills the run) */
  void (*old_int)(int) = signal(SIGINT, forward), (*old_term)(int) = signal(SIGTERM, forward),
       (*old_hup)(int) = signal(SIGHUP, forward);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  child_pid = 0;
  signal(SIGINT, old_int);
  signal(SIGTERM, old_term);
  signal(SIGHUP, old_hup);
  free(env);
  free(blob);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return -1;
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

int camp_execute(const camp_opts *o, campaign *c) {
  signal(SIGINT, forward);
  signal(SIGTERM, forward);
  signal(SIGHUP, forward);
  camp_progress p;
  camp_progress_start(&p, c->n_runs);
  char buf[512], *argv[64], why[CAMP_PATH + 256], path[CAMP_PATH + 32];
  run_argv(o, buf, argv, 64);
  int failed = 0;
  for (int i = 0; i < c->n_runs; i++) {
    camp_run *r = &c->runs[i];
    snprintf(path, sizeof path, "%s/summary.json", r->dir);
    double t0 = camp_now();
    if (access(path, R_OK) == 0) {
      r->reused = 1;
      camp_read_summary(r, why, sizeof why);
      fprintf(stderr, "mdpore permeability: run %d/%d (axis %c, g = %g): reused %s\n", i + 1,
              c->n_runs, 'x' + r->axis, r->g, r->dir);
    } else {
      fprintf(stderr, "mdpore permeability: run %d/%d (axis %c, g = %g): running in %s\n", i + 1,
              c->n_runs, 'x' + r->axis, r->g, r->dir);
      unlink(path);
      int st = camp_spawn(r->dir, argv, "run.log");
      if (st != 0) {
        fprintf(stderr, "mdpore permeability: run %d/%d failed (exit %d): see %s/run.log\n", i + 1,
                c->n_runs, st, r->dir);
        failed++;
        camp_progress_done(&p, r, camp_now() - t0);
        continue;
      }
      camp_read_summary(r, why, sizeof why);
    }
    if (!r->have) fprintf(stderr, "mdpore permeability: warning: %s\n", why);
    camp_progress_done(&p, r, camp_now() - t0);
  }
  signal(SIGINT, SIG_DFL);
  signal(SIGTERM, SIG_DFL);
  signal(SIGHUP, SIG_DFL);
  if (failed) {
    fprintf(stderr,
            "mdpore permeability: %d of %d runs failed; rerun the same command to retry "
            "them (finished runs are reused)\n",
            failed, c->n_runs);
    return -1;
  }
  return 0;
}
