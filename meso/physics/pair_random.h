/* Counter-based, pairwise-symmetric random numbers for the DPD random force (physics.md section 1).
 * xi_ij = xi_ji is a pure function of (seed, step, min id, max id): every rank and every backend
 * draws the same number for the same pair and step, so runs do not depend on the decomposition.
 * Three generators, chosen per run by the dpd_thermostat option `rng` (enum pair_rng); all are
 * Philox (Salmon, Moraes, Dror, Shaw, "Parallel random numbers: as easy as 1, 2, 3", SC'11) from
 * Random123, which compiles for host and CUDA device code:
 *  - philox (default): Philox4x32-10, counter = the two 64-bit ids, key = (seed, step);
 *  - philox2x32: Philox2x32-10, counter = the two ids as 32-bit words (ids < 2^32), half the
 *    multiplies (this was the build option MDPORE_PAIR_RNG=philox2x32; the same numbers);
 *  - fast: Philox2x32-7, the same counter, a 32-bit key hashed from (seed, step): 7 multiplies of
 *    32 x 32 -> 64 bits per draw instead of 20 (pair_random_bits_fast below says why it is sound).
 * Each maps its counter through a keyed bijection, so for one (seed, step) distinct pairs never
 * share a counter and their outputs are distinct 64-bit blocks (xi uses 32 bits of it). */
#ifndef MESO_PHYSICS_PAIR_RANDOM_H
#define MESO_PHYSICS_PAIR_RANDOM_H

#include "hd.h"
#include <Random123/philox.h>
#include <stdint.h>

/* The generators (dpd_thermostat's option rng; plan.pair_rng; the CUDA kernel's template
 * parameter). PAIR_RNG_PHILOX is 0: a scene without the option hashes and runs as before. */
enum pair_rng { PAIR_RNG_PHILOX = 0, PAIR_RNG_PHILOX2X32 = 1, PAIR_RNG_FAST = 2, PAIR_RNG_COUNT };

/* The scene word of each generator (rng: philox | philox2x32 | fast). */
MESO_HD const char *pair_rng_word(int rng) {
  return rng == PAIR_RNG_FAST ? "fast" : rng == PAIR_RNG_PHILOX2X32 ? "philox2x32" : "philox";
}
/* Its construction, for --explain and the benchmarks. */
MESO_HD const char *pair_rng_construction(int rng) {
  return rng == PAIR_RNG_FAST         ? "Philox2x32-7, hashed (seed, step) key"
         : rng == PAIR_RNG_PHILOX2X32 ? "Philox2x32-10"
                                      : "Philox4x32-10";
}
/* The largest particle id the generator keys on without aliasing (checked when particles are
 * added): the 2x32 counters hold each id in one 32-bit word. */
MESO_HD int64_t pair_random_max_id(int rng) {
  return rng == PAIR_RNG_PHILOX ? INT64_MAX : (int64_t)4294967295LL;
}

/* 32 random bits -> sqrt(3) U(-1, 1): zero mean, unit variance; U at the centres of 2^32 bins
 * (never exactly +-1). */
MESO_HD meso_real pair_random_from_bits(uint32_t bits) {
  const meso_real u =
      ((meso_real)bits + MESO_R(0.5)) * (meso_real)(2.0 / 4294967296.0) - MESO_R(1.0);
  return (meso_real)1.7320508075688772 * u;
}

/* The seed folded to 32 bits (the Philox generators' key word). */
MESO_HD uint32_t pair_random_seed32(uint64_t seed) {
  return (uint32_t)(seed ^ (seed >> 32));
}

/* Philox2x32-10's key: the folded seed plus the step times an odd constant (a bijection of the step
 * for one seed). */
MESO_HD uint32_t pair_random_philox2x32_key(uint64_t seed, uint64_t step) {
  return pair_random_seed32(seed) + (uint32_t)step * 0x9E3779B9u;
}

/* Philox4x32-10 (the default): counter = (min id, max id) as four 32-bit words, key = the seed
 * folded to 32 bits and the step (runs shorter than 2^32 steps). */
MESO_HD uint32_t pair_random_bits_philox(uint64_t seed, uint64_t step, int64_t id_i, int64_t id_j) {
  const uint64_t lo = (uint64_t)(id_i < id_j ? id_i : id_j);
  const uint64_t hi = (uint64_t)(id_i < id_j ? id_j : id_i);
  philox4x32_ctr_t ctr = {{(uint32_t)lo, (uint32_t)(lo >> 32), (uint32_t)hi, (uint32_t)(hi >> 32)}};
  philox4x32_key_t key = {{pair_random_seed32(seed), (uint32_t)step}};
  return philox4x32(ctr, key).v[0];
}

/* Philox2x32-10 (half the multiplies of Philox4x32-10): counter = (min id, max id) as 32-bit words
 * (ids < 2^32, checked at setup), key pair_random_philox2x32_key. Kept bitwise as the former build
 * option. */
MESO_HD uint32_t pair_random_bits_philox2x32(uint64_t seed, uint64_t step, int64_t id_i,
                                             int64_t id_j) {
  const uint32_t lo = (uint32_t)(id_i < id_j ? id_i : id_j);
  const uint32_t hi = (uint32_t)(id_i < id_j ? id_j : id_i);
  philox2x32_ctr_t ctr = {{lo, hi}};
  philox2x32_key_t key = {{pair_random_philox2x32_key(seed, step)}};
  return philox2x32(ctr, key).v[0];
}

/* The per-step key of the fast generator: a bijection of the step (mod 2^32) for each seed, with
 * nonlinear differences between consecutive steps.
 *  - The seed enters through the SplitMix64 output function (Steele, Lea, Flood, "Fast splittable
 *    pseudorandom number generators", OOPSLA 2014; Stafford's "Mix13" constants), upper 32 bits:
 *    neighbouring seeds (1, 2, 3, ...) get unrelated words.
 *  - word + step * 0x9E3779B9 (odd: a bijection of the step) goes through the MurmurHash3 32-bit
 *    finaliser (Appleby; xorshift-multiply, also a bijection). The finaliser keeps consecutive
 *    keys from differing by a constant: with key(step) = key(0) + step W, and W Philox2x32's own
 *    key increment 0x9E3779B9 as in the philox2x32 generator, step s + 1 runs the rounds of step s
 *    shifted by one (a slide relation between rounds); hashed keys have no such structure.
 * Loop-invariant in a force pass (seed and step are): compilers hoist it out of the pair loop. */
MESO_HD uint32_t pair_random_fast_key(uint64_t seed, uint64_t step) {
  uint64_t z = seed + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  uint32_t k = (uint32_t)(z >> 32) + (uint32_t)step * 0x9E3779B9u;
  k = (k ^ (k >> 16)) * 0x85EBCA6Bu;
  k = (k ^ (k >> 13)) * 0xC2B2AE35u;
  return k ^ (k >> 16);
}

/* The fast generator: Philox2x32 with 7 rounds on counter (min id, max id), key
 * pair_random_fast_key(seed, step); output word 0 (it holds the last round's mulhi).
 * Why 7 rounds: the SC'11 authors' documentation of Philox2x32 in Random123 (philox.h) says they
 * know of no statistical flaws with 6 rounds or more; their default 10 is "a considerable safety
 * margin over the minimum number of rounds". 7 keeps one round of margin over that minimum at 7 of
 * Philox4x32-10's 20 multiplies (each round: one 32 x 32 -> 64 multiply, two xors; the round keys
 * depend on (seed, step) only and are hoisted out of the pair loop).
 * Why distinct (pair, step) inputs do not collide systematically: for one (seed, step) Philox is a
 * bijection of the 64-bit counter, and the counter (min id, max id) is injective for ids < 2^32
 * (pair_random_max_id; checked at setup), so no two pairs of a step share an output block. Across
 * steps the key is a bijection of step mod 2^32 (pair_random_fast_key): no two steps of a run
 * shorter than 2^32 steps share a key. Equal xi between different (pair, step) then happen only as
 * for independent 32-bit draws. tests/engine/test_pair_rng_stats.c measures mean, variance,
 * symmetry, uniformity and the correlations between steps, neighbouring pairs and seeds. */
MESO_HD uint32_t pair_random_bits_fast(uint64_t seed, uint64_t step, int64_t id_i, int64_t id_j) {
  const uint32_t lo = (uint32_t)(id_i < id_j ? id_i : id_j);
  const uint32_t hi = (uint32_t)(id_i < id_j ? id_j : id_i);
  philox2x32_ctr_t ctr = {{lo, hi}};
  philox2x32_key_t key = {{pair_random_fast_key(seed, step)}};
  return philox2x32_R(7, ctr, key).v[0];
}

/* The bits of generator rng (a compile-time constant where the callers specialise on it). */
MESO_HD uint32_t pair_random_bits(int rng, uint64_t seed, uint64_t step, int64_t id_i,
                                  int64_t id_j) {
  if (rng == PAIR_RNG_FAST) return pair_random_bits_fast(seed, step, id_i, id_j);
  if (rng == PAIR_RNG_PHILOX2X32) return pair_random_bits_philox2x32(seed, step, id_i, id_j);
  return pair_random_bits_philox(seed, step, id_i, id_j);
}

/* The same bits with the key schedule done once per (seed, step) instead of once per pair: the
 * round keys of Random123's Philox (the key plus r W in round r, PHILOX_W32_0 and _1) are computed
 * by pair_random_keys, and pair_random_bits_keyed runs the rounds with them. The result equals
 * pair_random_bits bit for bit (tests/engine/test_physics_random.c checks it for every generator).
 * The CUDA force pass uses it: its round keys are kernel parameters, so no pair recomputes them,
 * and each round's 32 x 32 -> 64 multiply is one wide multiply (Random123's 64-bit product left an
 * add of zero after each on the device: bench/RESULTS.md, 2026-11-27 87113e1). */
#define PAIR_RNG_MAX_ROUNDS 10
struct pair_rng_keys {
  uint32_t k0[PAIR_RNG_MAX_ROUNDS], k1[PAIR_RNG_MAX_ROUNDS];
};

MESO_HD struct pair_rng_keys pair_random_keys(int rng, uint64_t seed, uint64_t step) {
  struct pair_rng_keys k;
  uint32_t k0 = rng == PAIR_RNG_FAST         ? pair_random_fast_key(seed, step)
                : rng == PAIR_RNG_PHILOX2X32 ? pair_random_philox2x32_key(seed, step)
                                             : pair_random_seed32(seed);
  uint32_t k1 = (uint32_t)step; /* (Philox4x32's second key word) */
  for (int r = 0; r < PAIR_RNG_MAX_ROUNDS; r++) {
    k.k0[r] = k0;
    k.k1[r] = k1;
    k0 += PHILOX_W32_0;
    k1 += PHILOX_W32_1;
  }
  return k;
}

/* a b as (hi, lo) 32-bit words: one wide multiply on the device */
MESO_HD uint32_t pair_mulhilo32(uint32_t a, uint32_t b, uint32_t *hi) {
#ifdef __CUDA_ARCH__
  uint32_t lo, h;
  asm("{\n\t.reg .u64 p;\n\tmul.wide.u32 p, %2, %3;\n\tmov.b64 {%0, %1}, p;\n\t}"
      : "=r"(lo), "=r"(h)
      : "r"(a), "r"(b));
  *hi = h;
  return lo;
#else
  const uint64_t p = (uint64_t)a * b;
  *hi = (uint32_t)(p >> 32);
  return (uint32_t)p;
#endif
}

MESO_HD uint32_t pair_random_bits_keyed(int rng, struct pair_rng_keys k, int64_t id_i,
                                        int64_t id_j) {
  if (rng == PAIR_RNG_PHILOX) { /* Philox4x32-10, counter (min id, max id) as four words */
    const uint64_t lo = (uint64_t)(id_i < id_j ? id_i : id_j);
    const uint64_t hi = (uint64_t)(id_i < id_j ? id_j : id_i);
    uint32_t c0 = (uint32_t)lo, c1 = (uint32_t)(lo >> 32), c2 = (uint32_t)hi,
             c3 = (uint32_t)(hi >> 32);
#ifdef __CUDA_ARCH__
#pragma unroll
#endif
    for (int r = 0; r < 10; r++) {
      uint32_t hi0, hi1;
      const uint32_t lo0 = pair_mulhilo32(PHILOX_M4x32_0, c0, &hi0);
      const uint32_t lo1 = pair_mulhilo32(PHILOX_M4x32_1, c2, &hi1);
      c0 = hi1 ^ c1 ^ k.k0[r];
      c1 = lo1;
      c2 = hi0 ^ c3 ^ k.k1[r];
      c3 = lo0;
    }
    return c0;
  }
  /* Philox2x32, counter (min id, max id) as two words: 7 rounds (fast) or 10 */
  uint32_t c0 = (uint32_t)(id_i < id_j ? id_i : id_j), c1 = (uint32_t)(id_i < id_j ? id_j : id_i);
  const int rounds = rng == PAIR_RNG_FAST ? 7 : 10;
#ifdef __CUDA_ARCH__
#pragma unroll
#endif
  for (int r = 0; r < 10; r++) {
    if (r >= rounds) break;
    uint32_t hi0;
    const uint32_t lo0 = pair_mulhilo32(PHILOX_M2x32_0, c0, &hi0);
    c0 = hi0 ^ k.k0[r] ^ c1;
    c1 = lo0;
  }
  return c0;
}

/* xi_ij of generator rng: uniform with zero mean and unit variance, sqrt(3) U(-1, 1). */
MESO_HD meso_real pair_random_xi_rng(int rng, uint64_t seed, uint64_t step, int64_t id_i,
                                     int64_t id_j) {
  return pair_random_from_bits(pair_random_bits(rng, seed, step, id_i, id_j));
}

/* xi_ij of the default generator (Philox4x32-10). */
MESO_HD meso_real pair_random_xi(uint64_t seed, uint64_t step, int64_t id_i, int64_t id_j) {
  return pair_random_from_bits(pair_random_bits_philox(seed, step, id_i, id_j));
}

#endif
