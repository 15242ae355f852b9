/* Results do not depend on the decomposition: the same scene on this communicator (1, 2 or 4 ranks)
 * and on MPI_COMM_SELF (one rank) gives the same first-step forces and densities to 1e-12 relative,
 * and the same positions after a few steps. The random forces are keyed on (seed, step, ids), so
 * they are included. Scenes: mDPD (attraction + repulsion + thermostat) with a frozen species, with
 * lambda = 0.5 and lambda = 0.65. Run under mpiexec -n 1, 2, 4. */
#include "common/mpi_singleton.h"
#include "test_engine_common.h"

typedef struct {
  double id, f[3], rho, x[3];
} rec_t;

/* Gather (id, f, rho, x) of all particles to rank 0, ordered by id. Returns the count on rank 0. */
static int gather_by_id(sim_t *sim, MPI_Comm comm, rec_t **out) {
  particles_t *p = sim_particles(sim);
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  rec_t *mine = malloc((size_t)(p->n_local + 1) * sizeof(rec_t));
  for (int i = 0; i < p->n_local; i++) {
    mine[i].id = (double)p->id[i];
    for (int d = 0; d < 3; d++) mine[i].f[d] = p->f[d][i], mine[i].x[d] = p->x[d][i];
    mine[i].rho = p->rho ? p->rho[i] : 0.0;
  }
  const int nd = (int)(sizeof(rec_t) / sizeof(double));
  int cnt = p->n_local * nd, *counts = malloc(size * sizeof(int)),
      *displs = malloc(size * sizeof(int));
  MPI_Gather(&cnt, 1, MPI_INT, counts, 1, MPI_INT, 0, comm);
  int total = 0;
  if (rank == 0)
    for (int r = 0; r < size; r++) displs[r] = total, total += counts[r];
  rec_t *all = rank == 0 ? malloc((size_t)(total / nd + 1) * sizeof(rec_t)) : NULL;
  MPI_Gatherv(mine, cnt, MPI_DOUBLE, all, counts, displs, MPI_DOUBLE, 0, comm);
  free(mine);
  free(counts);
  free(displs);
  if (rank != 0) return 0;
  rec_t *sorted = calloc((size_t)(total / nd + 1), sizeof(rec_t));
  for (int k = 0; k < total / nd; k++) sorted[(int)all[k].id] = all[k];
  free(all);
  *out = sorted;
  return total / nd;
}

static double max_rel_diff(const rec_t *a, const rec_t *b, int n, int what) {
  double dmax = 0, scale = 0;
  for (int i = 0; i < n; i++)
    for (int d = 0; d < (what == 1 ? 1 : 3); d++) {
      const double va = what == 0 ? a[i].f[d] : what == 1 ? a[i].rho : a[i].x[d];
      const double vb = what == 0 ? b[i].f[d] : what == 1 ? b[i].rho : b[i].x[d];
      if (fabs(va - vb) > dmax) dmax = fabs(va - vb);
      if (fabs(vb) > scale) scale = fabs(vb);
    }
  return dmax / scale;
}

static sim_t *build(const scene_t *s, MPI_Comm comm, int n) {
  sim_t *sim = sim_create(s, comm);
  if (!sim) return NULL;
  if (test_fill_random(sim, s, n, 0.25, 777) || sim_setup(sim)) {
    sim_destroy(sim);
    return NULL;
  }
  return sim;
}

static int compare_scene(const scene_t *s, int n, int steps, const char *label) {
  int rank, size;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  sim_t *par = build(s, MPI_COMM_WORLD, n);
  CHECK(par, "%s: building on %d ranks failed", label, size);
  rec_t *pf = NULL, *sf = NULL, *px = NULL, *sx = NULL;
  int np = gather_by_id(par, MPI_COMM_WORLD, &pf);
  for (int k = 0; k < steps; k++)
    CHECK(sim_step(par) == 0, "%s: step failed on %d ranks", label, size);
  gather_by_id(par, MPI_COMM_WORLD, &px);
  sim_destroy(par);
  int fail = 0;
  if (rank == 0) {
    sim_t *ser = build(s, MPI_COMM_SELF, n);
    CHECK(ser, "%s: building on 1 rank failed", label);
    int ns = gather_by_id(ser, MPI_COMM_SELF, &sf);
    for (int k = 0; k < steps; k++) CHECK(sim_step(ser) == 0, "%s: serial step failed", label);
    gather_by_id(ser, MPI_COMM_SELF, &sx);
    sim_destroy(ser);
    CHECK(np == n && ns == n, "%s: particle counts %d (parallel) %d (serial), expected %d", label,
          np, ns, n);
    const double df = max_rel_diff(pf, sf, n, 0), dr = max_rel_diff(pf, sf, n, 1);
    const double dx = max_rel_diff(px, sx, n, 2);
    printf("%s, %d ranks vs 1: first-step force max rel diff %.3e, rho %.3e; positions after %d "
           "steps %.3e\n",
           label, size, df, dr, steps, dx);
    fail = !(df < 1e-12 && dr < 1e-12 && dx < 1e-10);
    free(pf), free(sf), free(px), free(sx);
  }
  MPI_Bcast(&fail, 1, MPI_INT, 0, MPI_COMM_WORLD);
  CHECK(!fail, "%s: results depend on the number of ranks", label);
  return 0;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  scene_t s;
  /* 7.4 x 6.2 x 5 box at density ~5: subdomains stay >= rc on up to 4 ranks (2 x 2 x 1); their
   * bins do not line up with the single-rank bins, so neighbour sums run in different orders. */
  test_scene_mdpd(&s, 7.4, 6.2, 5.0);
  s.n_species = 2;
  snprintf(s.species[1].name, SCENE_NAME_LEN, "wall");
  s.species[1].mass = 1.0;
  s.species[1].frozen = 1;
  s.pair[0][1].A = s.pair[1][0].A = -30;
  effect_name_in_scene(&s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(&s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(&s, EFFECT_DPD_THERMOSTAT);
  const int n = 1200;
  int rc = compare_scene(&s, n, 10, "mDPD + thermostat + frozen, lambda 0.5");
  s.vv_lambda = 0.65;
  effect_name_in_scene(&s, EFFECT_BODY_FORCE);
  SCENE_EFFECT_OPTIONS(&s, EFFECT_BODY_FORCE, body_force_params_t)->g[0][0] = 0.3;
  if (!rc) rc = compare_scene(&s, n, 10, "mDPD + thermostat + frozen + body force, lambda 0.65");
  MPI_Finalize();
  return rc;
}
