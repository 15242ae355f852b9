/* The DPD random numbers and the thermostat's pair forces (physics.md section 1):
 *  - xi(seed, step, i, j) == xi(seed, step, j, i) for every pair (one number per pair per step);
 *  - mean ~ 0 and variance ~ 1 over many draws (uniform sqrt(3) U(-1, 1); 5-sigma bounds);
 *  - different steps give uncorrelated numbers;
 *  - with only dpd_thermostat, the total force on a random periodic configuration is zero to
 * rounding (F_ij = -F_ji, random and dissipative parts included), with each generator of
 * dpd_thermostat's option rng (tests/engine/test_pair_rng_stats.c has their statistics), and the
 * generators give different forces;
 *  - the 2x32 generators (philox2x32, fast) refuse particle ids of 2^32 and above;
 *  - the keyed form the CUDA force pass draws with (round keys once per step,
 * pair_random_bits_keyed) gives every generator's bits exactly, over random seeds, steps and ids
 * (the full 64-bit range for philox, below 2^32 for the 2x32 generators). */
#include "common/mpi_singleton.h"
#include "effects/dpd_thermostat.h"
#include "physics/pair_random.h"
#include "test_engine_common.h"

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  const long n = 2000000;
  double sum = 0, sum2 = 0, corr = 0;
  uint64_t st = 99;
  for (long k = 0; k < n; k++) {
    const int64_t i = (int64_t)(test_rng_next(&st) >> 20), j = (int64_t)(test_rng_next(&st) >> 20);
    const uint64_t step = k % 1000;
    const double a = pair_random_xi(42, step, i, j), b = pair_random_xi(42, step, j, i);
    CHECK(a == b, "xi(%lld, %lld) = %.17g != xi(%lld, %lld) = %.17g", (long long)i, (long long)j, a,
          (long long)j, (long long)i, b);
    sum += a;
    sum2 += a * a;
    corr += a * pair_random_xi(42, step + 1, i, j);
  }
  const double mean = sum / n, var = sum2 / n - mean * mean, c = corr / n;
  /* sd of the mean 1/sqrt(n); of the variance sqrt((9/5 - 1)/n) for sqrt(3) U(-1, 1) */
  printf("xi: mean %.2e (bound %.1e), variance %.5f, lag-1-step correlation %.2e\n", mean,
         5 / sqrt((double)n), var, c);
  CHECK(fabs(mean) < 5 / sqrt((double)n), "mean %.3e", mean);
  CHECK(fabs(var - 1) < 5 * sqrt(0.8 / n), "variance %.5f", var);
  CHECK(fabs(c) < 5 / sqrt((double)n), "correlation between steps %.3e", c);

  for (int rng = 0; rng < PAIR_RNG_COUNT; rng++) {
    long differ = 0;
    for (long k = 0; k < 200000; k++) {
      const uint64_t seed = test_rng_next(&st) >> (k % 2 ? 0 : 40), step = test_rng_next(&st) >> 30;
      int64_t i = (int64_t)(test_rng_next(&st) >> 1), j = (int64_t)(test_rng_next(&st) >> 1);
      if (rng != PAIR_RNG_PHILOX || k % 3 == 0) { /* ids < 2^32 (and small ones for philox) */
        i &= 0xffffffffLL;
        j &= 0xffffffffLL;
      }
      const struct pair_rng_keys keys = pair_random_keys(rng, seed, step);
      differ += pair_random_bits_keyed(rng, keys, i, j) != pair_random_bits(rng, seed, step, i, j);
    }
    printf("rng %s: keyed bits differ from Random123's in %ld of 200000 draws\n",
           pair_rng_word(rng), differ);
    CHECK(differ == 0, "rng %s: keyed bits differ in %ld draws", pair_rng_word(rng), differ);
  }

  double fx0[3] = {0, 0, 0};
  for (int rng = 0; rng < PAIR_RNG_COUNT; rng++) {
    scene_t s;
    test_scene_mdpd(&s, 5.0, 5.0, 5.0);
    effect_name_in_scene(&s, EFFECT_DPD_THERMOSTAT);
    SCENE_EFFECT_OPTIONS(&s, EFFECT_DPD_THERMOSTAT, dpd_thermostat_options_t)->rng = rng;
    sim_t *sim = sim_create(&s, MPI_COMM_SELF);
    CHECK(sim, "sim_create");
    CHECK(test_fill_random(sim, &s, 500, 0.0, 5) == 0, "fill");
    CHECK(sim_setup(sim) == 0, "setup");
    particles_t *p = sim_particles(sim);
    double total[3] = {0, 0, 0}, abs_sum = 0;
    for (int i = 0; i < p->n_local; i++)
      for (int d = 0; d < 3; d++) total[d] += p->f[d][i], abs_sum += fabs(p->f[d][i]);
    const double tmax = fmax(fabs(total[0]), fmax(fabs(total[1]), fabs(total[2])));
    printf("thermostat only, rng %s: |sum F| = %.3e, sum |F| = %.3e, f(particle 0) = (%.6f, "
           "%.6f, %.6f)\n",
           pair_rng_word(rng), tmax, abs_sum, p->f[0][0], p->f[1][0], p->f[2][0]);
    CHECK(abs_sum > 100, "forces suspiciously small: %.3e", abs_sum);
    CHECK(tmax < 1e-12 * abs_sum, "total force %.3e not zero", tmax);
    if (rng == PAIR_RNG_PHILOX)
      for (int d = 0; d < 3; d++) fx0[d] = p->f[d][0];
    else
      CHECK(fx0[0] != p->f[0][0] || fx0[1] != p->f[1][0], "rng %s gave philox's forces",
            pair_rng_word(rng));
    /* ids: the 2x32 counters hold one id per 32-bit word */
    const double x[3] = {1, 1, 1}, v[3] = {0, 0, 0};
    const int64_t big = 4294967296LL;
    const int added = sim_add_particle(sim, big, 0, x, v);
    CHECK((added < 0) == (rng != PAIR_RNG_PHILOX), "rng %s: id 2^32 %s", pair_rng_word(rng),
          added < 0 ? "refused" : "accepted");
    sim_destroy(sim);
  }
  MPI_Finalize();
  return 0;
}
