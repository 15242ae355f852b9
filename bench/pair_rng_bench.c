/* The cost of the pair random numbers on this CPU (not a test), for each generator of
 * dpd_thermostat's option rng (physics/pair_random.h), with the ratio to the default (philox) from
 * the same run:
 *  1. ns per xi draw: xi(seed, step, i, j) for one i against consecutive partners j at a fixed
 *     step, as a force loop draws them (the key depends on (seed, step) only), summed so that no
 *     draw is optimised away; the best of 5 repetitions of 2^24 draws;
 *  2. the CPU pair-force pass alone (mdpd_attraction + mdpd_repulsion + dpd_thermostat, rho = 6.2,
 *     random positions in a periodic box of side L, 1 rank): ms per pass and ns per particle, the
 *     best of `passes` calls of the backend's pair-force phase on the same configuration.
 * usage: pair_rng_bench [L (12)] [passes (20)]   (OMP_NUM_THREADS sets the force pass's threads) */
#include "common/mpi_singleton.h"
#include "backend/backend.h"
#include "bench_scene.h"
#include "effects/dpd_thermostat.h"
#include "effects/effect.h"
#include "engine/sim.h"
#include "engine/sim_internal.h"
#include "physics/pair_random.h"

#include <math.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The draw loop of one generator: rng is a constant in each call site below (inlined copies). */
static inline __attribute__((always_inline)) double draws(int rng, uint64_t seed, uint64_t step,
                                                          long n) {
  double s = 0;
  for (long k = 0; k < n; k++) {
    const int64_t i = k >> 6, j = i + 1 + (k & 63); /* 64 partners per particle */
    s += pair_random_xi_rng(rng, seed, step, i, j);
  }
  return s;
}
static __attribute__((noinline)) double draws_philox(uint64_t seed, uint64_t step, long n) {
  return draws(PAIR_RNG_PHILOX, seed, step, n);
}
static __attribute__((noinline)) double draws_philox2x32(uint64_t seed, uint64_t step, long n) {
  return draws(PAIR_RNG_PHILOX2X32, seed, step, n);
}
static __attribute__((noinline)) double draws_fast(uint64_t seed, uint64_t step, long n) {
  return draws(PAIR_RNG_FAST, seed, step, n);
}

static uint64_t state = 99;
static double uniform(void) {
  return bench_uniform(&state);
}

/* Best ms of `passes` pair-force passes with generator rng; -1 on failure. */
static double force_pass_ms(int rng, double L, int passes, long *n_out) {
  scene_t *s = calloc(1, sizeof *s);
  if (!s) return -1;
  const double box[3] = {L, L, L};
  bench_scene_mdpd(s, "pair_rng_bench", box, 1);
  SCENE_EFFECT_OPTIONS(s, EFFECT_DPD_THERMOSTAT, dpd_thermostat_options_t)->rng = rng;
  sim_t *sim = sim_create(s, MPI_COMM_SELF);
  const long n = lround(6.2 * L * L * L);
  state = 99; /* the same configuration for every generator */
  for (long k = 0; sim && k < n; k++) {
    const double x[3] = {L * uniform(), L * uniform(), L * uniform()};
    const double v[3] = {sqrt(3.0) * (2 * uniform() - 1), sqrt(3.0) * (2 * uniform() - 1),
                         sqrt(3.0) * (2 * uniform() - 1)};
    if (sim_add_particle(sim, k, 0, x, v) < 0) return -1;
  }
  if (!sim || sim_setup(sim)) return -1;
  sim_state_t *st = sim_state(sim);
  double best = 1e30;
  for (int r = 0; r < passes; r++) {
    const double t0 = now();
    if (backend_cpu_ops.phase[PHASE_PAIR_FORCES](st)) return -1;
    const double t = now() - t0;
    if (t < best) best = t;
  }
  sim_destroy(sim);
  free(s);
  *n_out = n;
  return 1e3 * best;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  const double L = argc > 1 ? atof(argv[1]) : 12.0;
  const int passes = argc > 2 ? atoi(argv[2]) : 20;
  const long n = 1L << 24;
  double (*const fn[PAIR_RNG_COUNT])(uint64_t, uint64_t,
                                     long) = {[PAIR_RNG_PHILOX] = draws_philox,
                                              [PAIR_RNG_PHILOX2X32] = draws_philox2x32,
                                              [PAIR_RNG_FAST] = draws_fast};
  double ns[PAIR_RNG_COUNT], sum = 0;
  for (int rng = 0; rng < PAIR_RNG_COUNT; rng++) {
    double best = 1e30;
    for (int rep = 0; rep < 5; rep++) {
      const double t0 = now();
      sum += fn[rng](7, 1000 + (uint64_t)rep, n);
      const double t = now() - t0;
      if (t < best) best = t;
    }
    ns[rng] = 1e9 * best / (double)n;
  }
  printf("xi draws (one particle against 64 consecutive partners, 2^24 draws, best of 5; checksum "
         "%.3g):\n",
         sum);
  printf("%-11s %-40s %10s %16s\n", "rng", "generator", "ns/draw", "ratio to philox");
  for (int rng = 0; rng < PAIR_RNG_COUNT; rng++)
    printf("%-11s %-40s %10.3f %16.3f\n", pair_rng_word(rng), pair_rng_construction(rng), ns[rng],
           ns[rng] / ns[PAIR_RNG_PHILOX]);
  double ms[PAIR_RNG_COUNT];
  long np = 0;
  for (int rng = 0; rng < PAIR_RNG_COUNT; rng++)
    if ((ms[rng] = force_pass_ms(rng, L, passes, &np)) < 0) {
      fprintf(stderr, "pair_rng_bench: the force pass failed\n");
      return 1;
    }
  printf("CPU pair-force pass (mDPD + thermostat, rho 6.2, L = %g, %ld particles, 1 rank, best of "
         "%d):\n",
         L, np, passes);
  printf("%-11s %10s %18s %16s\n", "rng", "ms/pass", "ns/particle", "ratio to philox");
  for (int rng = 0; rng < PAIR_RNG_COUNT; rng++)
    printf("%-11s %10.3f %18.2f %16.3f\n", pair_rng_word(rng), ms[rng], 1e6 * ms[rng] / (double)np,
           ms[rng] / ms[PAIR_RNG_PHILOX]);
  MPI_Finalize();
  return 0;
}
