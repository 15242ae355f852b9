/* migrate_records (the CUDA backend's migration with one axis cut: leavers as records) against
 * migrate_particles (the CPU path) on the same leavers: the same particles in the same order with
 * bitwise equal fields on every rank, the same losses, every result inside its subdomain, and no
 * particle gained or lost. Leavers: out below and above along the cut axis x (across the periodic
 * box faces too), out only along the uncut y (wrapped back: they stay), out along both, and one
 * non-finite position (noted as lost, kept, by both). Run under mpiexec -n 2 and -n 3. */
#include "common/mpi_singleton.h"
#include "domain/decomp.h"
#include "domain/migrate.h"
#include "domain/particle_store.h"
#include "test_engine_common.h"

#define N_LEAVERS 400

static void make_leaver(const decomp_t *dc, uint64_t *rng, int k, migrant_t *r) {
  memset(r, 0, sizeof *r);
  r->id = (int64_t)(1000000 * dc->rank + k);
  r->species = k % 2;
  for (int d = 0; d < 3; d++) {
    r->x[d] = dc->lo[d] + (dc->hi[d] - dc->lo[d]) * test_rng_uniform(rng);
    r->v[d] = test_rng_uniform(rng) - 0.5;
    r->f[d] = 10.0 * (test_rng_uniform(rng) - 0.5);
  }
  const double step = 0.4 * test_rng_uniform(rng);
  switch (k % 4) {
  case 0: /* below along x */
    r->x[0] = dc->lo[0] - step - 1e-9;
    break;
  case 1: /* above along x */
    r->x[0] = dc->hi[0] + step;
    break;
  case 2: /* only along y: wrapped back, stays */
    r->x[1] = k % 8 < 4 ? dc->box_lo[1] - step - 1e-9 : dc->box_hi[1] + step;
    break;
  default: /* along x and z */
    r->x[0] = k % 8 < 4 ? dc->lo[0] - step - 1e-9 : dc->hi[0] + step;
    r->x[2] = dc->box_hi[2] + step;
    break;
  }
}

static int same_record(const migrant_t *a, const particles_t *p, int i) {
  if (a->id != p->id[i] || a->species != p->species[i]) return 0;
  for (int d = 0; d < 3; d++)
    if (memcmp(&a->x[d], &p->x[d][i], 8) || memcmp(&a->v[d], &p->v[d][i], 8) ||
        memcmp(&a->f[d], &p->f[d][i], 8))
      return 0;
  return 1;
}

int main(int argc, char **argv) {
  (void)argc;
  (void)argv;
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  int nranks = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  scene_t *s = malloc(sizeof *s);
  test_scene_mdpd(s, 6.0 * nranks, 5.0, 4.0);
  s->procs[0] = nranks;
  s->procs[1] = s->procs[2] = 1;
  decomp_t dc;
  char err[256];
  CHECK(!decomp_create(&dc, s, MPI_COMM_WORLD, 1.0, err, sizeof err), "decomp: %s", err);
  CHECK(nranks < 2 || dc.dims[0] == nranks, "expected the cut along x");

  uint64_t rng = 77 + (uint64_t)rank;
  migrant_t *leavers = malloc((N_LEAVERS + 1) * sizeof *leavers);
  particles_t p;
  CHECK(!pstore_init(&p, 0, 0) && !pstore_reserve(&p, N_LEAVERS + 1), "particle store");
  const int m = rank == 0 ? N_LEAVERS + 1 : N_LEAVERS;
  for (int k = 0; k < N_LEAVERS; k++) make_leaver(&dc, &rng, k, &leavers[k]);
  if (rank == 0) { /* not finite: both paths note it as lost and keep it */
    make_leaver(&dc, &rng, 3, &leavers[N_LEAVERS]);
    leavers[N_LEAVERS].id = 999999;
    leavers[N_LEAVERS].x[0] = NAN;
  }
  for (int k = 0; k < m; k++) migrant_unpack(&p, k, &leavers[k]);
  p.n_local = m;
  p.n_ghost = 0;

  xbuf_t sbuf = {0}, rbuf = {0}, out = {0};
  migrate_report_t rep_cpu = {0}, rep_rec = {0};
  migrate_particles(&dc, &p, &sbuf, &rbuf, &rep_cpu);
  const int n = migrate_records(&dc, 0, leavers, m, &sbuf, &rbuf, &out, &rep_rec);

  CHECK(n == p.n_local, "rank %d: %d records vs %d particles from migrate_particles", rank, n,
        p.n_local);
  const migrant_t *r = (const migrant_t *)out.data;
  int inside = 0;
  for (int i = 0; i < n; i++) {
    CHECK(same_record(&r[i], &p, i), "rank %d: record %d (id %lld) differs from the CPU path's",
          rank, i, (long long)r[i].id);
    inside += r[i].id == 999999 || decomp_owns(&dc, r[i].x);
  }
  CHECK(inside == n, "rank %d: %d of %d results outside the subdomain", rank, n - inside, n);
  CHECK(rep_rec.n_lost == rep_cpu.n_lost && !rep_rec.out_of_memory,
        "rank %d: lost %ld vs %ld (CPU path)", rank, rep_rec.n_lost, rep_cpu.n_lost);
  long counts[3] = {m, n, rep_rec.n_lost}, sums[3];
  MPI_Allreduce(counts, sums, 3, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  CHECK(sums[0] == sums[1], "%ld particles in, %ld out", sums[0], sums[1]);
  CHECK(sums[2] == 1, "%ld lost in all (expected the one non-finite)", sums[2]);
  if (rank == 0)
    printf("migrate_records: %ld leavers on %d ranks, the CPU path's result bitwise, 1 loss "
           "noted\n",
           sums[0], nranks);
  xbuf_free(&sbuf);
  xbuf_free(&rbuf);
  xbuf_free(&out);
  pstore_free(&p);
  decomp_free(&dc);
  free(leavers);
  free(s);
  MPI_Finalize();
  return 0;
}
