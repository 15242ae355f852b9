/* Counter-based random numbers for initial configurations (Philox4x32-10, Random123): a pure
 * function of (seed, stream, index), so every rank generates the same global configuration without
 * communication and the result does not depend on the decomposition. */
#ifndef MESO_IO_INIT_RANDOM_H
#define MESO_IO_INIT_RANDOM_H

#include <Random123/philox.h>
#include <math.h>
#include <stdint.h>

enum { INIT_STREAM_POSITION = 1, INIT_STREAM_VELOCITY = 2 };

/* Four uniform numbers in (0, 1) for (seed, stream, index). */
static inline void init_uniform4(uint64_t seed, uint32_t stream, uint64_t index, double u[4]) {
  philox4x32_ctr_t ctr = {{(uint32_t)index, (uint32_t)(index >> 32), stream, 0x6d64706fu}};
  philox4x32_key_t key = {{(uint32_t)seed, (uint32_t)(seed >> 32)}};
  philox4x32_ctr_t r = philox4x32(ctr, key);
  for (int k = 0; k < 4; k++) u[k] = ((double)r.v[k] + 0.5) * (1.0 / 4294967296.0);
}

/* Three standard normal numbers for (seed, stream, index) (Box-Muller). */
static inline void init_normal3(uint64_t seed, uint32_t stream, uint64_t index, double g[3]) {
  double u[4];
  init_uniform4(seed, stream, index, u);
  const double two_pi = 6.283185307179586;
  g[0] = sqrt(-2.0 * log(u[0])) * cos(two_pi * u[1]);
  g[1] = sqrt(-2.0 * log(u[0])) * sin(two_pi * u[1]);
  g[2] = sqrt(-2.0 * log(u[2])) * cos(two_pi * u[3]);
}

#endif
