/* Counter-based, pairwise-symmetric random numbers for the DPD random force (physics.md section 1).
 * xi_ij = xi_ji is a pure function of (seed, step, min id, max id): every rank and every backend
 * draws the same number for the same pair and step, so runs do not depend on the decomposition.
 * Philox4x32-10 from Random123 (Salmon et al., SC'11) is the generator; it compiles for host and
 * CUDA device code. */
#ifndef MESO_PHYSICS_PAIR_RANDOM_H
#define MESO_PHYSICS_PAIR_RANDOM_H

#include "hd.h"
#include <Random123/philox.h>
#include <stdint.h>

/* 32 random bits -> sqrt(3) U(-1, 1): zero mean, unit variance; U at the centres of 2^32 bins
 * (never exactly +-1). */
MESO_HD meso_real pair_random_from_bits(uint32_t bits) {
  const meso_real u =
      ((meso_real)bits + MESO_R(0.5)) * (meso_real)(2.0 / 4294967296.0) - MESO_R(1.0);
  return (meso_real)1.7320508075688772 * u;
}

#ifdef MDPORE_PAIR_RNG_PHILOX2X32
/* Philox2x32-10 (half the multiplies of Philox4x32-10, also Crush-resistant per Salmon et al.):
 * counter = (min id, max id) as 32-bit words (ids < 2^32, checked at setup), key = the seed folded
 * to 32 bits plus the step times an odd constant (a bijection of the step for one seed). */
MESO_HD meso_real pair_random_xi(uint64_t seed, uint64_t step, int64_t id_i, int64_t id_j) {
  const uint32_t lo = (uint32_t)(id_i < id_j ? id_i : id_j);
  const uint32_t hi = (uint32_t)(id_i < id_j ? id_j : id_i);
  philox2x32_ctr_t ctr = {{lo, hi}};
  philox2x32_key_t key = {{(uint32_t)(seed ^ (seed >> 32)) + (uint32_t)step * 0x9E3779B9u}};
  return pair_random_from_bits(philox2x32(ctr, key).v[0]);
}
#define PAIR_RANDOM_MAX_ID 4294967295LL
#else
/* Uniform number with zero mean and unit variance: sqrt(3) * U(-1, 1). */
MESO_HD meso_real pair_random_xi(uint64_t seed, uint64_t step, int64_t id_i, int64_t id_j) {
  const uint64_t lo = (uint64_t)(id_i < id_j ? id_i : id_j);
  const uint64_t hi = (uint64_t)(id_i < id_j ? id_j : id_i);
  philox4x32_ctr_t ctr = {{(uint32_t)lo, (uint32_t)(lo >> 32), (uint32_t)hi, (uint32_t)(hi >> 32)}};
  /* Key: the seed folded to 32 bits and the step (runs shorter than 2^32 steps). */
  philox4x32_key_t key = {{(uint32_t)(seed ^ (seed >> 32)), (uint32_t)step}};
  return pair_random_from_bits(philox4x32(ctr, key).v[0]);
}
#define PAIR_RANDOM_MAX_ID INT64_MAX
#endif

#endif
