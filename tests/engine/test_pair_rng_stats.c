/* Statistics of the pair random numbers of every generator (physics/pair_random.h):
 * philox (Philox4x32-10, the default), philox2x32 (Philox2x32-10) and fast (Philox2x32-7 with a
 * hashed (seed, step) key). For each, over 2^20 draws per statistic:
 *  - symmetry: xi(seed, step, i, j) == xi(seed, step, j, i) bitwise, for every draw below;
 *  - mean 0 and variance 1 of xi = sqrt(3) U(-1, 1) (sd of the mean 1/sqrt(n), of the variance
 *    sqrt(0.8/n): E xi^4 = 9/5);
 *  - uniformity of U: chi-square over 64 equal bins from the top 6 of the 32 bits, and over the 64
 *    values of the low 6 bits (63 degrees of freedom; Wilson-Hilferty z); the frequency of each of
 *    the 32 bits (binomial z);
 *  - correlations, each the mean product of two unit-variance draws (sd 1/sqrt(n)): the same pair
 *    at steps s and s + 1, s + 2 (random pairs and steps; and 256 pairs x 4096 consecutive steps,
 *    lags 1 to 3), neighbouring pairs (i, j)-(i, j + 1) and (i, j)-(i + 1, j) at one step, seeds
 *    s and s + 1 at the same pair and step, and the generator against the default one.
 * Pairs: ids uniform below 2^31 ("random"), and "near" pairs j = i + 1..64, i < 2^20 (a lattice
 * fill numbers neighbours nearly in order); steps uniform below 2^24. Bounds: |z| < 5 for every
 * statistic (each would fail an independent generator with probability ~6e-7; the inputs are fixed,
 * so the outcome is reproducible). Prints one table row per statistic and generator. */
#include "physics/pair_random.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>

#define N_DRAWS (1L << 20)
#define Z_MAX 5.0

static int failures = 0;

/* splitmix64 (Steele et al. 2014): the test's inputs, independent of the generators under test */
static uint64_t next(uint64_t *s) {
  uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

typedef struct {
  int64_t i, j;
  uint64_t step;
} draw_t;

/* kind 0: ids uniform below 2^31; kind 1: near pairs j = i + 1..64 with i < 2^20 */
static draw_t input(uint64_t *s, int kind) {
  draw_t d;
  const uint64_t r = next(s), q = next(s);
  if (kind == 0) {
    d.i = (int64_t)(r & 0x7fffffff);
    d.j = (int64_t)((r >> 32) & 0x7fffffff);
  } else {
    d.i = (int64_t)(r & 0xfffff);
    d.j = d.i + 1 + (int64_t)((r >> 32) & 63);
  }
  if (q & 1) { /* either order: the generator orders the pair itself */
    const int64_t t = d.i;
    d.i = d.j;
    d.j = t;
  }
  d.step = (q >> 8) & 0xffffff;
  return d;
}

static double xi(int rng, uint64_t seed, uint64_t step, int64_t i, int64_t j) {
  return pair_random_xi_rng(rng, seed, step, i, j);
}

static void report(int rng, const char *what, double value, double z) {
  const int ok = fabs(z) < Z_MAX;
  printf("%-10s %-44s %12.5g   z = %+6.2f  %s\n", pair_rng_word(rng), what, value, z,
         ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

/* Wilson-Hilferty: chi-square with k degrees of freedom -> approximately standard normal */
static double chi2_z(double x, double k) {
  const double c = 2.0 / (9.0 * k);
  return (cbrt(x / k) - (1.0 - c)) / sqrt(c);
}

static void one_point(int rng, uint64_t seed, int kind) {
  uint64_t st = 1000 + (uint64_t)kind;
  double sum = 0, sum2 = 0;
  long top[64] = {0}, low[64] = {0}, ones[32] = {0};
  long asym = 0;
  for (long k = 0; k < N_DRAWS; k++) {
    const draw_t d = input(&st, kind);
    const uint32_t b = pair_random_bits(rng, seed, d.step, d.i, d.j);
    if (b != pair_random_bits(rng, seed, d.step, d.j, d.i)) asym++;
    const double x = pair_random_from_bits(b);
    sum += x;
    sum2 += x * x;
    top[b >> 26]++;
    low[b & 63]++;
    for (int bit = 0; bit < 32; bit++) ones[bit] += (b >> bit) & 1;
  }
  const double n = (double)N_DRAWS, mean = sum / n, var = sum2 / n - mean * mean;
  const char *tag = kind ? "near pairs" : "random pairs";
  char what[96];
  if (asym) {
    printf("%-10s %s: %ld of %ld draws differ between (i, j) and (j, i)  FAIL\n",
           pair_rng_word(rng), tag, asym, N_DRAWS);
    failures++;
  }
  snprintf(what, sizeof what, "mean, %s", tag);
  report(rng, what, mean, mean * sqrt(n));
  snprintf(what, sizeof what, "variance, %s", tag);
  report(rng, what, var, (var - 1.0) / sqrt(0.8 / n));
  double c_top = 0, c_low = 0;
  const double e = n / 64.0;
  for (int k = 0; k < 64; k++) {
    c_top += (top[k] - e) * (top[k] - e) / e;
    c_low += (low[k] - e) * (low[k] - e) / e;
  }
  snprintf(what, sizeof what, "chi2 (63 dof), 64 bins of U, %s", tag);
  report(rng, what, c_top, chi2_z(c_top, 63));
  snprintf(what, sizeof what, "chi2 (63 dof), low 6 bits, %s", tag);
  report(rng, what, c_low, chi2_z(c_low, 63));
  double zmax = 0;
  int worst = 0;
  for (int bit = 0; bit < 32; bit++) {
    const double z = (ones[bit] - 0.5 * n) / (0.5 * sqrt(n));
    if (fabs(z) > fabs(zmax)) zmax = z, worst = bit;
  }
  snprintf(what, sizeof what, "worst of 32 bit frequencies (bit %d), %s", worst, tag);
  report(rng, what, ones[worst] / n, zmax);
}

/* Mean product of pairs of draws; f fills the two numbers of draw k. */
typedef void (*pair_fn)(int rng, uint64_t seed, const draw_t *d, double *a, double *b);

static void lag1(int rng, uint64_t seed, const draw_t *d, double *a, double *b) {
  *a = xi(rng, seed, d->step, d->i, d->j);
  *b = xi(rng, seed, d->step + 1, d->i, d->j);
}
static void lag2(int rng, uint64_t seed, const draw_t *d, double *a, double *b) {
  *a = xi(rng, seed, d->step, d->i, d->j);
  *b = xi(rng, seed, d->step + 2, d->i, d->j);
}
static void next_j(int rng, uint64_t seed, const draw_t *d, double *a, double *b) {
  const int64_t lo = d->i < d->j ? d->i : d->j, hi = d->i < d->j ? d->j : d->i;
  *a = xi(rng, seed, d->step, lo, hi);
  *b = xi(rng, seed, d->step, lo, hi + 1);
}
static void next_i(int rng, uint64_t seed, const draw_t *d, double *a, double *b) {
  const int64_t lo = d->i < d->j ? d->i : d->j, hi = d->i < d->j ? d->j : d->i;
  *a = xi(rng, seed, d->step, lo, hi);
  *b = xi(rng, seed, d->step, lo + 1, hi); /* (hi, hi) when lo + 1 == hi: a valid counter */
}
static void next_seed(int rng, uint64_t seed, const draw_t *d, double *a, double *b) {
  *a = xi(rng, seed, d->step, d->i, d->j);
  *b = xi(rng, seed + 1, d->step, d->i, d->j);
}
static void vs_default(int rng, uint64_t seed, const draw_t *d, double *a, double *b) {
  *a = xi(rng, seed, d->step, d->i, d->j);
  *b = xi(PAIR_RNG_PHILOX, seed, d->step, d->i, d->j);
}

static void correlation(int rng, uint64_t seed, int kind, pair_fn f, const char *name) {
  uint64_t st = 2000 + (uint64_t)kind;
  double s = 0;
  for (long k = 0; k < N_DRAWS; k++) {
    const draw_t d = input(&st, kind);
    double a, b;
    f(rng, seed, &d, &a, &b);
    s += a * b;
  }
  const double c = s / (double)N_DRAWS;
  char what[96];
  snprintf(what, sizeof what, "corr. %s, %s", name, kind ? "near pairs" : "random pairs");
  report(rng, what, c, c * sqrt((double)N_DRAWS));
}

/* 256 pairs, each over 4096 consecutive steps from a random start: autocorrelation at lags 1-3. */
static void series(int rng, uint64_t seed) {
  enum { PAIRS = 256, STEPS = 4096, LAGS = 3 };
  uint64_t st = 3000;
  double c[LAGS + 1] = {0};
  long n[LAGS + 1] = {0};
  for (int p = 0; p < PAIRS; p++) {
    const draw_t d = input(&st, p & 1);
    double h[LAGS + 1] = {0};
    for (int t = 0; t < STEPS; t++) {
      for (int l = LAGS; l > 0; l--) h[l] = h[l - 1];
      h[0] = xi(rng, seed, d.step + (uint64_t)t, d.i, d.j);
      for (int l = 1; l <= LAGS && l <= t; l++) c[l] += h[0] * h[l], n[l]++;
    }
  }
  for (int l = 1; l <= LAGS; l++) {
    char what[96];
    snprintf(what, sizeof what, "autocorr. lag %d, 256 pairs x 4096 steps", l);
    report(rng, what, c[l] / n[l], c[l] / n[l] * sqrt((double)n[l]));
  }
}

int main(void) {
  const uint64_t seed = 12345;
  for (int rng = 0; rng < PAIR_RNG_COUNT; rng++) {
    printf("--- %s: %s ---\n", pair_rng_word(rng), pair_rng_construction(rng));
    for (int kind = 0; kind < 2; kind++) one_point(rng, seed, kind);
    for (int kind = 0; kind < 2; kind++) {
      correlation(rng, seed, kind, lag1, "steps s, s+1");
      correlation(rng, seed, kind, lag2, "steps s, s+2");
      correlation(rng, seed, kind, next_j, "pairs (i,j), (i,j+1)");
      correlation(rng, seed, kind, next_i, "pairs (i,j), (i+1,j)");
      correlation(rng, seed, kind, next_seed, "seeds s, s+1");
      if (rng != PAIR_RNG_PHILOX) correlation(rng, seed, kind, vs_default, "against philox");
    }
    series(rng, seed);
  }
  /* The generators are different streams, and the fast one is not the philox2x32 one. */
  int same = 0;
  for (int64_t j = 1; j < 1000; j++)
    same += pair_random_bits(PAIR_RNG_FAST, seed, 7, 0, j) ==
            pair_random_bits(PAIR_RNG_PHILOX2X32, seed, 7, 0, j);
  if (same > 2) {
    printf("fast and philox2x32 agree on %d of 999 draws  FAIL\n", same);
    failures++;
  }
  if (failures) fprintf(stderr, "%d statistics out of bounds\n", failures);
  return failures ? 1 : 0;
}
