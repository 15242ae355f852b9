/* Load balancing of a simulation (sim_balance.h). */
#include "engine/sim_balance.h"
#include "domain/balance.h"
#include "domain/redistribute.h"
#include "engine/sim_internal.h"

#include <stdlib.h>
#include <string.h>

static void report(const sim_state_t *st, const char *msg) {
  if (st->dc.rank == 0) fprintf(stderr, "mdpore: load balancing: %s\n", msg);
}

/* This rank's mobile and frozen particle counts. */
static void local_counts(const sim_state_t *st, double *mobile, double *frozen) {
  long m = 0;
  for (int i = 0; i < st->p.n_local; i++) m += st->plan.mobile[st->p.species[i]] != 0;
  *mobile = (double)m;
  *frozen = (double)(st->p.n_local - m);
}

/* This rank's particle weight (1 per mobile particle, st->frozen_weight per frozen one). */
static double local_weight(const sim_state_t *st) {
  double m, f;
  local_counts(st, &m, &f);
  return m + st->frozen_weight * f;
}

/* The cost model busy_r = a mobile_r + b frozen_r fitted over the ranks by least squares; the
 * frozen weight b / a (clamped to [0, 10], b < 0 taken as 0). 0, or -1 when the ranks' compositions
 * do not tell a from b (all alike) or a <= 0. */
static int fit_frozen_weight(sim_state_t *st, double *weight) {
  double mine[3], *all = malloc((size_t)st->dc.nranks * 3 * sizeof(double));
  local_counts(st, &mine[0], &mine[1]);
  mine[2] = st->busy_seconds;
  int ok = all != NULL;
  MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, st->dc.cart);
  if (!ok) {
    free(all);
    return -1;
  }
  MPI_Allgather(mine, 3, MPI_DOUBLE, all, 3, MPI_DOUBLE, st->dc.cart);
  /* The normal equations' sums accumulate over every measured period of the run (one point per
   * rank and period, busy seconds per step): the timing noise of single periods averages out. */
  double *sum = st->cost_fit; /* smm, smf, sff, smb, sfb */
  const double steps = st->step - st->busy_since > 0 ? (double)(st->step - st->busy_since) : 1.0;
  for (int r = 0; r < st->dc.nranks; r++) {
    const double m = all[3 * r], f = all[3 * r + 1], b = all[3 * r + 2] / steps;
    sum[0] += m * m;
    sum[1] += m * f;
    sum[2] += f * f;
    sum[3] += m * b;
    sum[4] += f * b;
  }
  free(all);
  const double smm = sum[0], smf = sum[1], sff = sum[2], smb = sum[3], sfb = sum[4];
  const double det = smm * sff - smf * smf;
  if (!(det > 1e-6 * smm * sff)) return -1; /* compositions proportional: no fit */
  double a = (sff * smb - smf * sfb) / det, b = (smm * sfb - smf * smb) / det;
  if (b < 0) { /* frozen particles cost nothing measurable: the mobile-only fit */
    b = 0;
    a = smb / smm;
  }
  if (!(a > 0)) return -1;
  *weight = b / a > 10 ? 10 : b / a;
  return 0;
}

/* max / mean of v over the ranks. */
static double max_over_mean(MPI_Comm comm, int nranks, double v) {
  double mx = v, sum = v;
  MPI_Allreduce(MPI_IN_PLACE, &mx, 1, MPI_DOUBLE, MPI_MAX, comm);
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, comm);
  return sum > 0 ? mx / (sum / nranks) : 1.0;
}

/* The backend on the current subdomains: rebuilt, and set up again when it was (forces kept). */
static int rebuild_backend(sim_t *sim) {
  sim_state_t *st = &sim->st;
  if (sim->ops->destroy && st->impl) sim->ops->destroy(st);
  st->impl = NULL;
  int bad = sim->ops->create(st) != 0;
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, st->dc.cart);
  if (bad) {
    report(st, st->err[0] ? st->err : "the backend could not be rebuilt on the new subdomains");
    return -1;
  }
  if (!sim->is_setup) return 0;
  const int loaded = st->forces_loaded;
  st->forces_loaded = 1; /* the forces travelled with the particles */
  const long step = st->step;
  const int rc = sim_setup(sim);
  st->forces_loaded = loaded;
  st->step = step;
  return rc;
}

/* Particles to their owners under the current cuts, then the backend. */
static int settle(sim_t *sim) {
  sim_state_t *st = &sim->st;
  if (redistribute_particles(&st->dc, &st->p, st->err, sizeof st->err)) {
    report(st, st->err);
    return -1;
  }
  return rebuild_backend(sim);
}

int sim_balance(sim_t *sim, int measured, sim_balance_report_t *rep) {
  sim_state_t *st = &sim->st;
  const double t0 = MPI_Wtime();
  memset(rep, 0, sizeof *rep);
  if (sim->is_setup && sim->ops->sync_host) sim->ops->sync_host(st);
  /* Measured: the frozen weight from the fitted cost model; when the ranks cannot tell it, each
   * particle's weight scaled by its rank's seconds per unit weight. */
  double scale = 1.0;
  if (measured && sim_busy_measured(sim)) {
    double fitted;
    if (fit_frozen_weight(st, &fitted) == 0) {
      st->frozen_weight = fitted;
      rep->fitted = 1;
    } else {
      const double w = local_weight(st), busy = st->busy_seconds;
      double wsum = w, bsum = busy;
      MPI_Allreduce(MPI_IN_PLACE, &wsum, 1, MPI_DOUBLE, MPI_SUM, st->dc.cart);
      MPI_Allreduce(MPI_IN_PLACE, &bsum, 1, MPI_DOUBLE, MPI_SUM, st->dc.cart);
      const double mean_rate = wsum > 0 ? bsum / wsum : 0;
      scale = mean_rate > 0 ? (w > 0 && busy > 0 ? busy / w : mean_rate) / mean_rate : 1.0;
    }
  }
  rep->frozen_weight = st->frozen_weight;
  const double w = local_weight(st);
  rep->weight_before = max_over_mean(st->dc.cart, st->dc.nranks, w);
  rep->cost_before = max_over_mean(st->dc.cart, st->dc.nranks, w * scale);
  int frozen[SCENE_MAX_SPECIES];
  for (int s = 0; s < SCENE_MAX_SPECIES; s++)
    frozen[s] = s < st->plan.n_species && !st->plan.mobile[s];
  double *hist[3] = {NULL, NULL, NULL}, *cuts[3] = {NULL, NULL, NULL};
  int bad = 0;
  for (int d = 0; d < 3; d++) {
    hist[d] = calloc((size_t)balance_nbins(&st->dc, d), sizeof(double));
    cuts[d] = malloc((size_t)(st->dc.dims[d] + 1) * sizeof(double));
    bad |= !hist[d] || !cuts[d];
  }
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, st->dc.cart);
  if (bad) {
    report(st, "out of memory for the cost histograms");
    goto out;
  }
  balance_histogram_add(&st->dc, &st->p, frozen, st->frozen_weight, scale, hist);
  for (int d = 0; d < 3; d++) {
    const int nb = balance_nbins(&st->dc, d), m = st->dc.dims[d];
    MPI_Allreduce(MPI_IN_PLACE, hist[d], nb, MPI_DOUBLE, MPI_SUM, st->dc.cart);
    if (m == 1) {
      memcpy(cuts[d], st->dc.cut[d], 2 * sizeof(double));
      continue;
    }
    /* Every rank computes the same cuts from the same reduced histogram. */
    if (balance_cuts_1d(hist[d], nb, st->dc.box_lo[d], st->dc.box_hi[d], m,
                        st->dc.rcut * (1 + 1e-9), cuts[d])) {
      snprintf(st->err, sizeof st->err,
               "%d slabs of at least rcut = %g do not fit along %c (box %g): use fewer ranks "
               "along it (box.procs)",
               m, st->dc.rcut, "xyz"[d], st -> dc.L[d]);
      bad = 1;
      break;
    }
    cuts[d][0] = st->dc.box_lo[d];
    cuts[d][m] = st->dc.box_hi[d];
    for (int c = 0; c <= m && !rep->moved; c++) rep->moved = cuts[d][c] != st->dc.cut[d][c];
  }
  if (bad) {
    report(st, st->err);
    goto out;
  }
  bad = sim_set_cuts(sim, cuts);
  if (!bad) {
    const double w_after = local_weight(st);
    rep->weight_after = max_over_mean(st->dc.cart, st->dc.nranks, w_after);
    rep->cost_after = rep->weight_after; /* the measured rates belong to the old subdomains */
  }
out:
  for (int d = 0; d < 3; d++) {
    free(hist[d]);
    free(cuts[d]);
  }
  sim_busy_reset(sim);
  rep->seconds = MPI_Wtime() - t0;
  MPI_Allreduce(MPI_IN_PLACE, &rep->seconds, 1, MPI_DOUBLE, MPI_MAX, st->dc.cart);
  return bad ? -1 : 0;
}

int sim_set_cuts(sim_t *sim, double *const cuts[3]) {
  sim_state_t *st = &sim->st;
  int bad = 0;
  for (int d = 0; d < 3 && !bad; d++)
    bad = decomp_set_cuts(&st->dc, d, cuts[d], st->err, sizeof st->err) != 0;
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, st->dc.cart);
  if (bad) {
    report(st, st->err[0] ? st->err : "the cuts were refused on another rank");
    return -1;
  }
  if (sim->is_setup && sim->ops->sync_host) sim->ops->sync_host(st);
  return settle(sim);
}

void sim_cuts(const sim_t *sim, const double *cuts[3], int dims[3]) {
  for (int d = 0; d < 3; d++) {
    cuts[d] = sim->st.dc.cut[d];
    dims[d] = sim->st.dc.dims[d];
  }
}

const double *sim_phase_seconds(const sim_t *sim) {
  return sim->st.phase_seconds;
}
void sim_phase_seconds_reset(sim_t *sim) {
  memset(sim->st.phase_seconds, 0, sizeof sim->st.phase_seconds);
}
double sim_busy_seconds(const sim_t *sim) {
  return sim->st.busy_seconds;
}
double sim_frozen_weight(const sim_t *sim) {
  return sim->st.frozen_weight;
}
void sim_busy_reset(sim_t *sim) {
  sim->st.busy_seconds = 0;
  sim->st.busy_since = sim->st.step;
}
int sim_busy_measured(const sim_t *sim) {
  return sim->ops->sync_host == NULL; /* a host backend: its phases end when their work does */
}

void sim_imbalance(sim_t *sim, double *busy, double *busy_run, double *weight) {
  sim_state_t *st = &sim->st;
  *weight = max_over_mean(st->dc.cart, st->dc.nranks, local_weight(st));
  const int on = sim_busy_measured(sim);
  *busy = on ? max_over_mean(st->dc.cart, st->dc.nranks, st->busy_seconds) : 0;
  *busy_run = on ? max_over_mean(st->dc.cart, st->dc.nranks, st->busy_total) : 0;
}

void sim_busy_per_rank(sim_t *sim, double *since_move, double *run) {
  sim_state_t *st = &sim->st;
  MPI_Gather(&st->busy_seconds, 1, MPI_DOUBLE, since_move, 1, MPI_DOUBLE, 0, st->dc.cart);
  MPI_Gather(&st->busy_total, 1, MPI_DOUBLE, run, 1, MPI_DOUBLE, 0, st->dc.cart);
}

double sim_busy_mean(sim_t *sim) {
  sim_state_t *st = &sim->st;
  double sum = sim_busy_measured(sim) ? st->busy_total : 0;
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, st->dc.cart);
  return sum / st->dc.nranks;
}
