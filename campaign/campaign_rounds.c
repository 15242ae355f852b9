/* The campaign-level stopping rule, --target-error-k E (campaign.h, camp_rounds; docs/
 * permeability.md, "Stopping on the error of k"). Users want the error of k, not of each run, so
 * the runs do not stop on their own error: round 1 runs every run for --round-steps; after each
 * round the Darcy range of every axis is fitted to its admissible rows as collect does
 * (campaign_checks.c, campaign_linear.c: the error inflated by sqrt(chi2/dof) where the rows
 * scatter); while the relative error of k is above E on an axis, the next round continues its runs
 * from their checkpoints: those the checks leave out as unsteady (or without a flux result), and
 * every admissible one while the rows define no Darcy range, to twice their steps (at most
 * --max-steps, as a run of the per-run rule); the Darcy range's by camp_allocate (the most information about the slope per particle-step), until E is met or the
 * step budget (steps of all runs together) is spent. Each round is recorded in WORKDIR/rounds.txt
 * before it runs: a killed campaign replays the recorded rounds (every run already at its round's
 * step is reused, one short of it continued) and plans the next from where the last one left the
 * runs, so it reaches the same rounds it would have uninterrupted. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign.h"
#include "common/atomic_file.h"
#include "common/json_out.h"

camp_rounds_report camp_rounds_done;

#define LEDGER_NAME "rounds.txt"
#define LEDGER_HEAD                                                                                \
  "# mdpore permeability rounds: round R STEP RUN (the step each run reaches in round R)"

/* One axis after a round: its admissible rows and their Darcy range, and the runs to extend before
 * they can be rows (unsteady, or no flux result). */
typedef struct {
  int has_runs;
  int n_rows;
  camp_run *rows[CAMP_MAX_RUNS]; /* admissible, in increasing G */
  camp_linear L;
  double rel_err; /* of the Darcy range's k (NAN: no range) */
  int n_pending;
  camp_run *pending[CAMP_MAX_RUNS];
} axis_state;

static int by_g(const void *a, const void *b) {
  const camp_run *x = *(camp_run *const *)a, *y = *(camp_run *const *)b;
  return (x->G > y->G) - (x->G < y->G);
}

static void evaluate(const camp_opts *o, campaign *c, int axis, axis_state *st) {
  char why[CAMP_PATH + 256];
  camp_run *rows[CAMP_MAX_RUNS], *out[CAMP_MAX_GRADIENTS];
  camp_flag flags[CAMP_MAX_GRADIENTS];
  int n = 0, n_out = 0;
  memset(st, 0, sizeof *st);
  st->rel_err = NAN;
  for (int i = 0; i < c->n_runs; i++) {
    camp_run *r = &c->runs[i];
    if (r->axis != axis) continue;
    st->has_runs = 1;
    camp_read_summary(r, why, sizeof why);
    if (r->have)
      rows[n++] = r;
    else
      st->pending[st->n_pending++] = r; /* ran, but no flux result yet */
  }
  qsort(rows, (size_t)n, sizeof rows[0], by_g);
  camp_checks lim;
  camp_checks_of(o, c, &lim);
  st->n_rows = camp_admit_rows(rows, n, &lim, out, flags, &n_out);
  for (int i = 0; i < st->n_rows; i++) st->rows[i] = rows[i];
  for (int i = 0; i < n_out; i++)
    if (!strcmp(flags[i].check, "unsteady")) st->pending[st->n_pending++] = out[i];
  if (st->n_rows < 2) return;
  double G[CAMP_MAX_RUNS], q[CAMP_MAX_RUNS], s[CAMP_MAX_RUNS];
  for (int i = 0; i < st->n_rows; i++) {
    G[i] = st->rows[i]->G;
    q[i] = st->rows[i]->q;
    s[i] = st->rows[i]->q_err; /* the body drive: G is exact */
  }
  camp_darcy_range(G, q, s, st->n_rows, c->viscosity, &st->L);
  if (st->L.accepted) st->rel_err = st->L.k_err / fabs(st->L.k);
}

/* One ledger line "round R STEP RUN": 0 with R, STEP >= 1 and the offset of RUN, else -1 (strtol,
 * not sscanf: a number beyond its type is refused, not clamped). */
static int parse_ledger_line(const char *line, long *round, long long *step, int *run_at) {
  if (strncmp(line, "round ", 6)) return -1;
  char *end;
  errno = 0;
  *round = strtol(line + 6, &end, 10);
  if (errno || end == line + 6 || *end != ' ') return -1;
  const char *s = end;
  *step = strtoll(s, &end, 10);
  if (errno || end == s || *end != ' ' || *step < 1) return -1;
  *run_at = (int)(end - line) + (int)strspn(end, " ");
  return line[*run_at] ? 0 : -1;
}

int camp_rounds_read_ledger(const char *workdir, const campaign *c, camp_rounds_report *rep) {
  char path[CAMP_PATH + 32], line[CAMP_PATH + 128];
  snprintf(path, sizeof path, "%s/%s", workdir, LEDGER_NAME);
  FILE *f = fopen(path, "r");
  rep->n_rounds = 0;
  if (!f) return 0; /* a fresh campaign */
  int ln = 0, rc = 0;
  while (fgets(line, sizeof line, f) && !rc) {
    ln++;
    if (!strchr(line, '\n') && !feof(f)) { /* the rest would be read as a line of its own */
      fprintf(stderr,
              "mdpore permeability: %s:%d: a line longer than %d characters: expected 'round R "
              "STEP RUN' lines\n",
              path, ln, (int)sizeof line - 2);
      rc = -1;
      break;
    }
    if (line[0] == '#' || line[0] == '\n') continue;
    line[strcspn(line, "\n")] = 0;
    long round = 0;
    long long step = 0;
    int off = 0;
    if (parse_ledger_line(line, &round, &step, &off) || round < 1 || round > CAMP_MAX_ROUNDS ||
        round > rep->n_rounds + 1) {
      fprintf(stderr,
              "mdpore permeability: %s:%d: expected 'round R STEP RUN' (R from 1, one more than "
              "the last at most, up to %d; STEP >= 1), got '%.200s'\n",
              path, ln, CAMP_MAX_ROUNDS, line);
      rc = -1;
      break;
    }
    if (round > rep->n_rounds) { /* a new round: every run starts at its step of the last */
      for (int i = 0; i < c->n_runs; i++)
        rep->step[round - 1][i] = round > 1 ? rep->step[round - 2][i] : 0;
      rep->n_rounds = round;
    }
    for (int i = 0; i < c->n_runs; i++) /* a run of another campaign in this folder: ignored */
      if (!strcmp(c->runs[i].dir, line + off)) rep->step[round - 1][i] = step;
  }
  fclose(f);
  return rc;
}

static int write_ledger(const char *workdir, const campaign *c, const camp_rounds_report *rep) {
  char path[CAMP_PATH + 32], tmp[CAMP_PATH + 96];
  snprintf(path, sizeof path, "%s/%s", workdir, LEDGER_NAME);
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) {
    fprintf(stderr, "mdpore permeability: %s: cannot write the rounds (%s)\n", path,
            strerror(errno));
    return -1;
  }
  fprintf(f, "%s\n", LEDGER_HEAD);
  for (int r = 0; r < rep->n_rounds; r++)
    for (int i = 0; i < c->n_runs; i++)
      if (r == 0 || rep->step[r][i] != rep->step[r - 1][i])
        fprintf(f, "round %d %lld %s\n", r + 1, rep->step[r][i], c->runs[i].dir);
  return atomic_commit(f, tmp, path);
}

/* Brings every run to its step of round r (camp_execute reuses those there already). */
static int execute_round(const camp_opts *o, campaign *c, camp_rounds_report *rep, int r) {
  for (int i = 0; i < c->n_runs; i++) {
    c->runs[i].target_step = rep->step[r][i];
    c->runs[i].reused = 0;
  }
  const double t0 = camp_now();
  const int rc = camp_execute(o, c);
  int ran = 0;
  for (int i = 0; i < c->n_runs; i++) ran += !c->runs[i].reused;
  rep->wall_seconds[r] = ran ? camp_now() - t0 : NAN; /* NAN: recorded, all reused */
  return rc;
}

static long long steps_of_round(const camp_rounds_report *rep, int r, int i) {
  return rep->step[r][i] - (r > 0 ? rep->step[r - 1][i] : 0);
}

/* Plans round r + 1 from the runs after round r: rep->step[r + 1]. Returns the runs advanced. */
static int plan(const camp_opts *o, const campaign *c, camp_rounds_report *rep, int r,
                const axis_state *ax, long long *budget_left) {
  long long *next = rep->step[r + 1];
  int advanced = 0;
  for (int i = 0; i < c->n_runs; i++) next[i] = rep->step[r][i];
  for (int d = 0; d < 3; d++) {
    const axis_state *st = &ax[d];
    if (!st->has_runs || rep->met[d]) continue;
    /* the runs that are not rows yet, and without a Darcy range every row (short windows can
     * scatter beyond their error bars): twice their steps, up to a run's --max-steps */
    const int no_range = !isfinite(st->rel_err);
    for (int j = 0; j < st->n_pending + (no_range ? st->n_rows : 0); j++) {
      const camp_run *p = j < st->n_pending ? st->pending[j] : st->rows[j - st->n_pending];
      const int i = (int)(p - c->runs);
      long long add = rep->step[r][i];
      if (add > o->max_steps - rep->step[r][i]) add = o->max_steps - rep->step[r][i];
      add = add / o->flux_every * o->flux_every;
      if (add > *budget_left) add = *budget_left / o->flux_every * o->flux_every;
      if (add <= 0) continue;
      next[i] += add;
      *budget_left -= add;
      advanced++;
    }
    if (no_range) continue;
    camp_alloc_row rows[CAMP_MAX_RUNS];
    long long ext[CAMP_MAX_RUNS];
    for (int j = 0; j < st->L.rows; j++) {
      const camp_run *row = st->rows[j];
      const long long at = rep->step[r][(int)(row - c->runs)];
      const long long from = row->steady_from > 0 && row->steady_from < at ? row->steady_from : 0;
      rows[j] =
          (camp_alloc_row){row->G, row->q_err, (double)(at - from), (double)row->particles, at};
    }
    camp_allocate(rows, st->L.rows, st->rel_err, o->target_error_k, o->flux_every, budget_left,
                  ext);
    for (int j = 0; j < st->L.rows; j++)
      if (ext[j] > 0) {
        next[(int)(st->rows[j] - c->runs)] += ext[j];
        advanced++;
      }
  }
  return advanced;
}

/* Each run's share of var(k) on its axis: (G_i^2 / s_i^2) / W over the Darcy range's rows. */
static void shares(const campaign *c, const axis_state *ax, camp_rounds_report *rep) {
  for (int i = 0; i < c->n_runs; i++) rep->share[i] = NAN;
  for (int d = 0; d < 3; d++) {
    const axis_state *st = &ax[d];
    if (!isfinite(st->rel_err)) continue;
    double W = 0;
    for (int j = 0; j < st->L.rows; j++)
      W += st->rows[j]->G * st->rows[j]->G / (st->rows[j]->q_err * st->rows[j]->q_err);
    for (int j = 0; j < st->L.rows; j++)
      rep->share[st->rows[j] - c->runs] =
          st->rows[j]->G * st->rows[j]->G / (st->rows[j]->q_err * st->rows[j]->q_err) / W;
  }
}

/* Round r's totals over the runs: how many it advanced, their steps and particle-steps. */
static void round_totals(const campaign *c, const camp_rounds_report *rep, int r, int *runs,
                         double *steps, double *psteps) {
  *runs = 0;
  *steps = *psteps = 0;
  for (int i = 0; i < c->n_runs; i++) {
    const long long s = steps_of_round(rep, r, i);
    *runs += s > 0;
    *steps += (double)s;
    *psteps += (double)s * (double)c->runs[i].particles;
  }
}

static void print_report(const campaign *c, const camp_rounds_report *rep) {
  printf("\n== stopping on the error of k: target %g ==\n", rep->target);
  double ps_all = 0, steps_all = 0;
  printf("  %-6s %-7s %-12s %-14s %-10s", "round", "runs", "steps", "particle-steps", "wall s");
  for (int d = 0; d < 3; d++)
    if (isfinite(rep->k_rel_err[0][d]) || rep->stop_why[d][0])
      printf(" k_%c%c rel err", 'x' + d, 'x' + d);
  printf("\n");
  for (int r = 0; r < rep->n_rounds; r++) {
    double ps, st;
    int runs;
    round_totals(c, rep, r, &runs, &st, &ps);
    ps_all += ps;
    steps_all += st;
    char wall[32] = "(reused)";
    if (isfinite(rep->wall_seconds[r])) snprintf(wall, sizeof wall, "%.1f", rep->wall_seconds[r]);
    printf("  %-6d %-7d %-12.0f %-14.4g %-10s", r + 1, runs, st, ps, wall);
    for (int d = 0; d < 3; d++)
      if (isfinite(rep->k_rel_err[0][d]) || rep->stop_why[d][0]) {
        if (isfinite(rep->k_rel_err[r][d]))
          printf(" %.3g%%", 100 * rep->k_rel_err[r][d]);
        else
          printf(" -");
      }
    printf("\n");
  }
  printf("  per run: steps in each round, total, relative error of q, share of var(k)\n");
  for (int i = 0; i < c->n_runs; i++) {
    const camp_run *r = &c->runs[i];
    printf("  %c G = %-10.5g", 'x' + r->axis, r->G);
    for (int k = 0; k < rep->n_rounds; k++) printf(" %7lld", steps_of_round(rep, k, i));
    printf("  = %-7lld q %.3g%%", rep->step[rep->n_rounds - 1][i],
           r->have ? 100 * r->q_err / fabs(r->q) : NAN);
    if (isfinite(rep->share[i]))
      printf("  share %.1f%%\n", 100 * rep->share[i]);
    else
      printf("  (not in the Darcy range)\n");
  }
  printf("  steps %.0f of the budget %.0f, %.4g particle-steps\n", steps_all, rep->budget_steps,
         ps_all);
  for (int d = 0; d < 3; d++)
    if (rep->stop_why[d][0]) printf("  k_%c%c: %s\n", 'x' + d, 'x' + d, rep->stop_why[d]);
  fflush(stdout);
}

void camp_rounds_json(json_out *j, const campaign *c) {
  const camp_rounds_report *rep = &camp_rounds_done;
  if (rep->n_rounds <= 0) return;
  json_object(j, "campaign_stop");
  json_string(j, "rule",
              "--target-error-k: rounds; each continues the runs that lower var(k) most "
              "per particle-step, G^2 / (s^2 T N), until the target or the budget");
  json_number(j, "target_error_k", rep->target);
  json_number(j, "budget_steps", rep->budget_steps);
  double steps_all = 0, ps_all = 0;
  json_array(j, "rounds");
  for (int r = 0; r < rep->n_rounds; r++) {
    double st, ps;
    int runs;
    round_totals(c, rep, r, &runs, &st, &ps);
    steps_all += st;
    ps_all += ps;
    json_object(j, NULL);
    json_int(j, "round", r + 1);
    json_int(j, "runs_advanced", runs);
    json_number(j, "steps", st);
    json_number(j, "particle_steps", ps);
    json_number(j, "wall_seconds", rep->wall_seconds[r]);
    json_object(j, "k_relative_error");
    for (int d = 0; d < 3; d++)
      if (rep->stop_why[d][0]) {
        const char key[2] = {(char)('x' + d), 0};
        json_number(j, key, rep->k_rel_err[r][d]);
      }
    json_object_end(j);
    json_object_end(j);
  }
  json_array_end(j);
  json_number(j, "steps", steps_all);
  json_number(j, "particle_steps", ps_all);
  json_array(j, "runs");
  for (int i = 0; i < c->n_runs; i++) {
    const camp_run *r = &c->runs[i];
    const char axis[2] = {(char)('x' + r->axis), 0};
    json_object(j, NULL);
    json_string(j, "run", r->dir);
    json_string(j, "axis", axis);
    json_number(j, "G", r->G);
    json_array(j, "steps_per_round");
    for (int k = 0; k < rep->n_rounds; k++) json_int(j, NULL, steps_of_round(rep, k, i));
    json_array_end(j);
    json_int(j, "steps", rep->step[rep->n_rounds - 1][i]);
    json_number(j, "q_relative_error", r->have ? r->q_err / fabs(r->q) : NAN);
    json_number(j, "share_of_var_k", rep->share[i]);
    json_object_end(j);
  }
  json_array_end(j);
  json_object(j, "axes");
  for (int d = 0; d < 3; d++)
    if (rep->stop_why[d][0]) {
      const char key[2] = {(char)('x' + d), 0};
      json_object(j, key);
      json_number(j, "k_relative_error", rep->k_rel_err[rep->n_rounds - 1][d]);
      json_bool(j, "met", rep->met[d]);
      json_string(j, "why", rep->stop_why[d]);
      json_object_end(j);
    }
  json_object_end(j);
  json_object_end(j);
}

static void write_rounds_json(const char *workdir, const campaign *c) {
  char path[CAMP_PATH + 32], tmp[CAMP_PATH + 96];
  snprintf(path, sizeof path, "%s/rounds.json", workdir);
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return;
  json_out j;
  json_begin(&j, f);
  json_string(&j, "format", "mdpore-permeability-rounds");
  json_int(&j, "version", 1);
  camp_rounds_json(&j, c);
  json_end(&j);
  atomic_commit(f, tmp, path);
}

int camp_rounds(const camp_opts *o, campaign *c) {
  camp_rounds_report *rep = &camp_rounds_done;
  memset(rep, 0, sizeof *rep);
  rep->target = o->target_error_k;
  const long long budget =
      o->budget_steps > 0 ? o->budget_steps : (long long)c->n_runs * o->max_steps;
  rep->budget_steps = (double)budget;
  if ((long long)c->n_runs * o->round_steps > budget) {
    fprintf(stderr,
            "mdpore permeability: --budget-steps %lld: expected at least the first round, %d runs "
            "x --round-steps %lld = %lld steps\n",
            budget, c->n_runs, o->round_steps, (long long)c->n_runs * o->round_steps);
    return CAMP_ROUNDS_REFUSED;
  }
  if (camp_rounds_read_ledger(o->workdir, c, rep)) return -1;
  int recorded = rep->n_rounds;
  if (recorded == 0) rep->n_rounds = 1;
  for (int i = 0; i < c->n_runs; i++) /* round 1: every run (one added since: now) */
    if (rep->step[0][i] <= 0) rep->step[0][i] = o->round_steps;
  for (int r = 1; r < rep->n_rounds; r++)
    for (int i = 0; i < c->n_runs; i++)
      if (rep->step[r][i] < rep->step[r - 1][i]) rep->step[r][i] = rep->step[r - 1][i];
  if (write_ledger(o->workdir, c, rep)) return -1;
  printf("stopping on the error of k: target %g; round 1: every run for %lld steps; budget %lld "
         "steps%s\n",
         o->target_error_k, rep->step[0][0], budget,
         recorded ? " (the recorded rounds replayed first: runs already there are reused)" : "");
  fflush(stdout);
  axis_state ax[3];
  for (int r = 0;; r++) {
    if (execute_round(o, c, rep, r)) return -1;
    long long spent = 0;
    for (int i = 0; i < c->n_runs; i++) spent += rep->step[r][i];
    int open = 0;
    for (int d = 0; d < 3; d++) {
      evaluate(o, c, d, &ax[d]);
      rep->k_rel_err[r][d] = ax[d].rel_err;
      if (!ax[d].has_runs) continue;
      rep->met[d] = ax[d].rel_err <= o->target_error_k;
      if (rep->met[d])
        snprintf(rep->stop_why[d], sizeof rep->stop_why[d],
                 "target met: relative error of k %.3g%% <= %g%% after %d round(s)",
                 100 * ax[d].rel_err, 100 * o->target_error_k, r + 1);
      else
        open = 1;
      char err[64] = "none (no Darcy range)";
      if (isfinite(ax[d].rel_err)) snprintf(err, sizeof err, "%.3g%%", 100 * ax[d].rel_err);
      printf("round %d: k_%c%c relative error %s%s (%lld steps of %lld)\n", r + 1, 'x' + d, 'x' + d,
             err, rep->met[d] ? ", target met" : "", spent, budget);
    }
    fflush(stdout);
    if (r + 1 < recorded) continue; /* replaying: the next round is recorded */
    if (!open) break;
    long long left = budget - spent;
    int advanced = 0;
    if (r + 1 < CAMP_MAX_ROUNDS) advanced = plan(o, c, rep, r, ax, &left);
    if (!advanced) {
      for (int d = 0; d < 3; d++)
        if (ax[d].has_runs && !rep->met[d])
          snprintf(rep->stop_why[d], sizeof rep->stop_why[d],
                   "target NOT met: relative error of k %.3g%% above %g%%: %s", 100 * ax[d].rel_err,
                   100 * o->target_error_k,
                   r + 1 >= CAMP_MAX_ROUNDS ? "the most rounds were run"
                   : left < o->flux_every   ? "the step budget is spent (--budget-steps)"
                   : !isfinite(ax[d].rel_err)
                       ? "no run can be continued within --max-steps to give a Darcy range"
                       : "no run can be continued");
      break;
    }
    rep->n_rounds = r + 2;
    if (write_ledger(o->workdir, c, rep)) return -1;
    printf("round %d: %d run(s) continued\n", r + 2, advanced);
  }
  shares(c, ax, rep);
  print_report(c, rep);
  write_rounds_json(o->workdir, c);
  return 0;
}
