/* Driving the OpenFOAM tools: one bash subprocess per tool with the OpenFOAM environment sourced,
 * then simpleFoam in chunks until the residuals and the flow rate have settled. */
#define _GNU_SOURCE /* nftw */
#include "foam_case.h"

#include <dirent.h>
#include <ftw.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

/* The mdpore process may be an MPI singleton: drop the launcher's variables so that OpenFOAM's own
 * mpirun (or a serial tool) does not try to join this process's MPI session. */
static void scrub_mpi_environment(void) {
  char names[512][128];
  int n = 0;
  for (char **e = environ; *e && n < 512; e++) {
    if (strncmp(*e, "PMIX_", 5) && strncmp(*e, "OMPI_", 5)) continue;
    if (!strncmp(*e, "OMPI_ALLOW_RUN_AS_ROOT", 22) ||
        !strncmp(*e, "OMPI_MCA_rmaps_base_oversub", 27) || !strncmp(*e, "OMPI_MCA_btl_vader", 18))
      continue;
    size_t len = strcspn(*e, "=");
    if (len >= sizeof names[0]) continue;
    memcpy(names[n], *e, len);
    names[n++][len] = 0;
  }
  for (int i = 0; i < n; i++) unsetenv(names[i]);
}

/* Run `command` (words only) in the case folder with output to dir/log; returns its exit status. */
static int run_tool(const char *dir, const char *command, const char *log, int verbose) {
  const char *bashrc = mdp_foam_bashrc();
  if (verbose) fprintf(stderr, "mdpore foam: %s (log %s/%s)\n", command, dir, log);
  fflush(NULL);
  pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    scrub_mpi_environment();
    /* The OpenFOAM bashrc treats its positional parameters as settings: clear them first. */
    const char *script = "rc=$1 dir=$2 cmd=$3 log=$4; set --; "
                         "[ -n \"$rc\" ] && . \"$rc\" >/dev/null 2>&1; cd \"$dir\" || exit 97; "
                         "$cmd > \"$log\" 2>&1";
    execl("/bin/bash", "bash", "-c", script, "mdpore-foam", bashrc ? bashrc : "", dir, command, log,
          (char *)NULL);
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* Error with the last lines of a tool's log. */
static int tool_failed(const char *dir, const char *tool, const char *log, int status, char *err) {
  char path[4200], tail[1024] = "", line[512];
  snprintf(path, sizeof path, "%s/%s", dir, log);
  FILE *f = fopen(path, "r");
  char ring[6][512];
  int n = 0;
  while (f && fgets(line, sizeof line, f)) snprintf(ring[n++ % 6], sizeof ring[0], "%s", line);
  if (f) fclose(f);
  for (int i = n > 6 ? n - 6 : 0; i < n; i++)
    strncat(tail, ring[i % 6], sizeof tail - strlen(tail) - 1);
  snprintf(err, MDP_FOAM_ERR_LEN, "%s failed (exit %d); see %.900s; last lines:\n%s", tool, status,
           path, tail);
  return 1;
}

static int log_mentions(const char *path, const char *text) {
  FILE *f = fopen(path, "r");
  char line[1024];
  int found = 0;
  while (f && !found && fgets(line, sizeof line, f)) found = strstr(line, text) != NULL;
  if (f) fclose(f);
  return found;
}

static double now_s(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int rm_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw) {
  (void)sb, (void)flag, (void)ftw;
  return remove(path);
}

/* A folder name that is a positive time ("20", "1.5e+03"). */
static int is_later_time(const char *name) {
  char *end;
  double t = strtod(name, &end);
  return end != name && !*end && t > 0;
}

/* Remove every result after time 0 (serial and processor folders) and the function-object output,
 * so that a run can start again from the initial fields. */
static int mdp_foam_clear_results(const char *dir, char *err) {
  char sub[4200], path[4600];
  const char *where[2] = {dir, NULL};
  DIR *top = opendir(dir);
  struct dirent *e;
  char procs[64][64];
  int np = 0;
  while (top && (e = readdir(top)))
    if (!strncmp(e->d_name, "processor", 9) && np < 64)
      snprintf(procs[np++], 64, "%.60s", e->d_name);
  if (top) closedir(top);
  for (int p = -1; p < np; p++) {
    if (p >= 0) snprintf(sub, sizeof sub, "%s/%s", dir, procs[p]), where[0] = sub;
    DIR *d = opendir(where[0]);
    while (d && (e = readdir(d))) {
      if (!is_later_time(e->d_name)) continue;
      snprintf(path, sizeof path, "%s/%s", where[0], e->d_name);
      nftw(path, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
    }
    if (d) closedir(d);
  }
  snprintf(path, sizeof path, "%s/postProcessing", dir);
  if (nftw(path, rm_entry, 16, FTW_DEPTH | FTW_PHYS) != 0 && errno != ENOENT) {
    snprintf(err, MDP_FOAM_ERR_LEN, "%.1500s: cannot remove: %s", path, strerror(errno));
    return 1;
  }
  return 0;
}

int mdp_foam_run(const char *dir, const mdp_image_t *img, const mdp_foam_opts_t *o,
                 mdp_foam_result_t *res, char *err) {
  memset(res, 0, sizeof *res);
  double t0 = now_s();
  long long cells = 0;
  if (mdp_foam_write_case(dir, img, o, err)) return 1;
  int st;
  if ((st = run_tool(dir, "blockMesh", "log.blockMesh", o->verbose)))
    return tool_failed(dir, "blockMesh", "log.blockMesh", st, err);
  if (mdp_foam_write_pore_set(dir, img, o, &cells, err)) return 1;
  if ((st = run_tool(dir, "subsetMesh poreCells -patch walls -overwrite", "log.subsetMesh",
                     o->verbose)))
    return tool_failed(dir, "subsetMesh", "log.subsetMesh", st, err);
  if (o->smooth_walls) {
    if (mdp_foam_smooth_walls(dir, img, o, &res->smooth, err)) return 1;
    if ((st = run_tool(dir, "checkMesh -constant", "log.checkMesh", o->verbose)) < 0)
      return tool_failed(dir, "checkMesh", "log.checkMesh", st, err);
    char path[4200];
    int fatal = 0;
    snprintf(path, sizeof path, "%s/log.checkMesh", dir);
    if (mdp_foam_parse_checkmesh(path, &res->smooth.mesh_volume, res->smooth.mesh_check,
                                 sizeof res->smooth.mesh_check, &fatal) ||
        fatal || !isfinite(res->smooth.mesh_volume)) {
      snprintf(err, MDP_FOAM_ERR_LEN,
               "--walls smooth: the moved mesh fails checkMesh (%s); see %.900s",
               res->smooth.mesh_check, path);
      return 1;
    }
    if (o->verbose)
      fprintf(stderr,
              "mdpore foam: smooth walls: %lld of %lld wall points moved (max %.3f voxel), %lld "
              "held back; checkMesh: %s\n",
              res->smooth.moved_points, res->smooth.wall_points, res->smooth.max_move,
              res->smooth.limited_points, res->smooth.mesh_check);
  }
  if (mdp_foam_write_fields(dir, o, err)) return 1;
  res->cells = (int)cells;
  const char *app = o->simple ? "simpleFoam" : "pimpleFoam";
  char solver[128];
  if (o->np > 1) {
    if ((st = run_tool(dir, "decomposePar -force", "log.decomposePar", o->verbose)))
      return tool_failed(dir, "decomposePar", "log.decomposePar", st, err);
    /* In containers mdpore often runs as root, which Open MPI refuses without this flag. */
    snprintf(solver, sizeof solver, "mpirun %s-np %d %s -parallel",
             geteuid() == 0 ? "--allow-run-as-root " : "", o->np, app);
  } else {
    snprintf(solver, sizeof solver, "%s", app);
  }
  mdp_foam_opts_t run_o = *o; /* dt may shrink */
  double tol = o->tol_residual, q_prev = NAN;
  int done = 0, have_rows = 0, stopped_early = 0;
  for (int run = 0; done < o->max_iter; run++) {
    /* The first run is short and, for simpleFoam, without residual control, so that the flux has
     * a few checks to judge before simpleFoam may stop itself. */
    int collect = have_rows < 3 || stopped_early;
    int len = collect ? 5 * o->check_every : o->chunk;
    int end = done + len < o->max_iter ? done + len : o->max_iter;
    if (mdp_foam_write_control(dir, &run_o, done, end, collect ? 0 : tol, err)) return 1;
    char log[64], path[4200];
    snprintf(log, sizeof log, "log.%s.%d", app, run);
    st = run_tool(dir, solver, log, o->verbose);
    double *rows = NULL, last_time = 0;
    int n = 0, solver_conv = 0, diverged = 0;
    snprintf(path, sizeof path, "%s/%s", dir, log);
    /* A crash on a floating-point error is a diverging march; any other failure is an error. */
    if (st) {
      if (o->simple || !log_mentions(path, "Floating point exception"))
        return tool_failed(dir, app, log, st, err);
      diverged = 1;
    }
    mdp_foam_parse_log(path, o->axis, &last_time, &res->res_p, &res->res_u, &solver_conv);
    int last = (int)lround(last_time / (o->simple ? 1.0 : run_o.dt));
    if (!diverged && mdp_foam_read_flow(dir, &rows, &n, err)) {
      free(rows);
      return 1;
    }
    double q = NAN, dq = NAN, dq_prev = NAN;
    if (n >= 1) {
      const double *r = rows + 5 * (n - 1);
      memcpy(res->int_u, r + 1, sizeof res->int_u);
      res->int_mag_u = r[4];
      q = r[1 + o->axis];
      /* Flux change over the last check interval, and the distance to the converged value it
       * implies when the iteration converges geometrically (late iterations do, with a rate close
       * to 1 for SIMPLE): remaining = |dq| rho / (1 - rho), rho = dq_n / dq_{n-1}. */
      double q_before = n >= 2 ? rows[5 * (n - 2) + 1 + o->axis] : q_prev;
      dq = q - q_before;
      if (n >= 3) dq_prev = q_before - rows[5 * (n - 3) + 1 + o->axis];
    }
    free(rows);
    have_rows = n;
    double scale = fmax(fabs(q), 1e-300), rho = dq_prev != 0 ? dq / dq_prev : NAN;
    res->flux_change = fabs(dq) / scale;
    res->flux_error = rho > 0 && rho < 1 ? res->flux_change * rho / (1 - rho) : NAN;
    if (res->flux_change < 1e-13) res->flux_error = res->flux_change; /* settled to round-off */
    /* The drive pushes along +axis: a flux that is not positive and finite, changes that grow from
     * check to check (above round-off: the ratio of two round-off changes means nothing), or a
     * pressure residual still of order one after two runs (a neutral oscillation) mean that the
     * pseudo-time step is too large. */
    const int growing = n >= 4 && fabs(rho) > 1.2 && res->flux_change > 1e-12;
    if (!o->simple && (diverged || !(q > 0) || !isfinite(q) || growing ||
                       (last >= 2 * o->chunk && res->res_p > 0.1))) {
      if (res->restarts >= 4) {
        snprintf(err, MDP_FOAM_ERR_LEN,
                 "pimpleFoam diverged even with time step %g (see %.900s/%s); try --solver simple",
                 run_o.dt, dir, log);
        return 1;
      }
      res->restarts++;
      run_o.dt *= 0.25;
      if (o->verbose)
        fprintf(stderr, "mdpore foam: diverging at step %d; restarting with time step %g\n", last,
                run_o.dt);
      if (mdp_foam_clear_results(dir, err)) return 1;
      done = 0, have_rows = 0, q_prev = NAN, tol = o->tol_residual;
      continue;
    }
    q_prev = q;
    res->iterations = last;
    res->dt = run_o.dt;
    if (o->verbose)
      fprintf(stderr,
              "mdpore foam: step %d: residual p %.3g U %.3g, flux change %.3g, est. error %.3g\n",
              last, res->res_p, res->res_u, res->flux_change, res->flux_error);
    /* Converged: residuals below tolerance, flux change and estimated remaining error below the
     * flux tolerance (a rate that is not yet geometric gives no estimate and does not pass).
     * OpenFOAM normalises a residual by the field's deviation from its mean, so a velocity that is
     * uniform over the cells (a slit two cells wide) keeps a normalised residual of order one at
     * convergence: a flux settled to round-off over three checks waives the U residual. */
    int settled = n >= 3 && res->flux_change < 1e-13 && fabs(dq_prev) < 1e-13 * scale;
    if (res->res_p < o->tol_residual && (res->res_u < o->tol_residual || settled) &&
        res->flux_change < o->tol_flux && res->flux_error < o->tol_flux) {
      res->converged = 1;
      break;
    }
    /* simpleFoam met its p target but U or the flux still move: collect a few more checks
     * without residual control, then go on with a tighter target. */
    stopped_early = o->simple && solver_conv;
    if (stopped_early) tol = fmax(tol * 0.1, 1e-14);
    done = last;
  }
  res->wall_s = now_s() - t0;
  return 0;
}
