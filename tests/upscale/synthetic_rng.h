/* Seeded Gaussian noise for the synthetic-data tests (splitmix64 + Box-Muller): reproducible on
 * every machine, independent of libc's rand(). */
#ifndef MDPORE_TESTS_SYNTHETIC_RNG_H
#define MDPORE_TESTS_SYNTHETIC_RNG_H

#include <math.h>
#include <stdint.h>

static inline uint64_t splitmix64(uint64_t *s) {
  uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

static inline double uniform01(uint64_t *s) {
  return ((splitmix64(s) >> 11) + 0.5) * 0x1.0p-53;
}

static inline double gaussian(uint64_t *s) {
  double u = uniform01(s), v = uniform01(s);
  return sqrt(-2.0 * log(u)) * cos(2.0 * M_PI * v);
}

#endif
