/* Initial configurations: a random fill has round(rho V) particles with ids 1..N inside its region,
 * zero total momentum and a temperature near the requested one; the configuration generated on the
 * parallel decomposition is bitwise the same as on one rank (keyed on ids, not on ranks). Frozen
 * species are at rest; a lattice fill realises the density within 5%. Run on 2 ranks. */
#include "common/mpi_singleton.h"
#include "effects/scene_load.h"
#include "engine/sim.h"
#include "io/gather.h"
#include "populate/init_config.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_io_check.h"

static const char *text =
    "box: {lo: [0, 0, 0], hi: [9, 6, 6]}\n"
    "species: [{name: liquid}, {name: wall, frozen: true, mass: 2}]\n"
    "pairs: {default: {A: -40, B: 25, gamma: 4.5, rc: 1, rd: 0.75}}\n"
    "effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}}\n"
    "initial:\n"
    "  fill:\n"
    "    - {species: liquid, lo: [0, 0, 0], hi: [6, 6, 6], density: 6.2}\n"
    "    - {species: wall, lo: [6, 0, 0], hi: [9, 6, 6], density: 8, mode: lattice}\n"
    "  temperature: 1.5\n"
    "run: {dt: 0.01, steps: 0, seed: 4}\n";

static int build(const scene_t *s, MPI_Comm comm, particle_set_t *out) {
  sim_t *sim = sim_create(s, comm);
  if (!sim || init_configuration(sim, s)) return -1;
  int rc = gather_particles(sim, 0, 0, out, NULL);
  sim_destroy(sim);
  return rc;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0) {
    FILE *f = fopen("init_test.yaml", "w");
    fputs(text, f);
    fclose(f);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  scene_t s;
  if (scene_load("init_test.yaml", &s)) return 1;
  particle_set_t all, one;
  CHECK(build(&s, MPI_COMM_WORLD, &all) == 0);
  CHECK(build(&s, MPI_COMM_SELF, &one) == 0);
  if (rank == 0) {
    particle_set_sort_by_id(&all);
    particle_set_sort_by_id(&one);
    const long n_liq = lround(6.2 * 216), n_wall = init_fill_count(&s, 1);
    CHECK(all.n == n_liq + n_wall && one.n == all.n);
    CHECK(fabs(n_wall / (8.0 * 108) - 1) < 0.05);
    double p[3] = {0, 0, 0}, ke = 0;
    long n_mob = 0, bad_pos = 0, bad_id = 0, frozen_moving = 0;
    for (long i = 0; i < all.n; i++) {
      bad_id += all.id[i] != i + 1;
      const int sp = all.species[i];
      const double xmax = sp == 0 ? 6 : 9, xmin = sp == 0 ? 0 : 6;
      bad_pos += all.x[3 * i] < xmin || all.x[3 * i] > xmax;
      const double *v = all.v + 3 * i;
      if (s.species[sp].frozen) {
        frozen_moving += v[0] != 0 || v[1] != 0 || v[2] != 0;
        continue;
      }
      n_mob++;
      for (int d = 0; d < 3; d++) p[d] += v[d];
      ke += 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    const double T = 2 * ke / (3.0 * (n_mob - 1));
    printf("init: %ld particles, T = %.4f (want 1.5), momentum = %.2e %.2e %.2e\n", all.n, T, p[0],
           p[1], p[2]);
    CHECK(bad_id == 0 && bad_pos == 0 && frozen_moving == 0);
    CHECK(fabs(p[0]) + fabs(p[1]) + fabs(p[2]) < 1e-9);
    CHECK(fabs(T - 1.5) < 5 * 1.5 * sqrt(2.0 / (3 * n_mob))); /* 5 sigma of the sampling spread */
    int identical = one.n == all.n;
    for (long i = 0; identical && i < all.n; i++)
      identical = all.id[i] == one.id[i] &&
                  !memcmp(all.x + 3 * i, one.x + 3 * i, 3 * sizeof(double)) &&
                  !memcmp(all.v + 3 * i, one.v + 3 * i, 3 * sizeof(double));
    CHECK(identical);
    remove("init_test.yaml");
  }
  particle_set_free(&all);
  particle_set_free(&one);
  MPI_Bcast(&failures, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Finalize();
  return failures ? 1 : 0;
}
