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

/* This rank's particle weight (balance.frozen_weight for frozen species, 1 otherwise). */
static double local_weight(const sim_state_t *st) {
  double w = 0;
  for (int i = 0; i < st->p.n_local; i++)
    w += st->plan.mobile[st->p.species[i]] ? 1.0 : st->scene.balance.frozen_weight;
  return w;
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
  const double w = local_weight(st);
  double scale = 1.0; /* seconds per unit weight on this rank */
  if (measured && sim_busy_measured(sim)) {
    double busy = st->busy_seconds, wsum = w, bsum = busy;
    MPI_Allreduce(MPI_IN_PLACE, &wsum, 1, MPI_DOUBLE, MPI_SUM, st->dc.cart);
    MPI_Allreduce(MPI_IN_PLACE, &bsum, 1, MPI_DOUBLE, MPI_SUM, st->dc.cart);
    const double mean_rate = wsum > 0 ? bsum / wsum : 0;
    scale = w > 0 && busy > 0 ? busy / w : mean_rate;
    if (mean_rate > 0)
      scale /= mean_rate; /* about 1: keeps the histogram's numbers readable */
    else
      scale = 1.0;
  }
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
  balance_histogram_add(&st->dc, &st->p, frozen, st->scene.balance.frozen_weight, scale, hist);
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

double sim_busy_seconds(const sim_t *sim) {
  return sim->st.busy_seconds;
}
void sim_busy_reset(sim_t *sim) {
  sim->st.busy_seconds = 0;
}
int sim_busy_measured(const sim_t *sim) {
  return sim->ops->sync_host == NULL; /* a host backend: its phases end when their work does */
}

void sim_imbalance(sim_t *sim, double *busy, double *weight) {
  sim_state_t *st = &sim->st;
  *weight = max_over_mean(st->dc.cart, st->dc.nranks, local_weight(st));
  *busy = sim_busy_measured(sim) ? max_over_mean(st->dc.cart, st->dc.nranks, st->busy_seconds) : 0;
}
