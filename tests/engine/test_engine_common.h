/* Shared helpers of the engine tests: scenes filled in C (no parser), a deterministic generator,
 * and building a simulation by offering every particle on every rank. */
#ifndef TEST_ENGINE_COMMON_H
#define TEST_ENGINE_COMMON_H

#include "effects/effect.h"
#include "engine/sim.h"
#include "scene/scene.h"

#include <math.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CHECK(cond, ...)                                                                           \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);                                         \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fprintf(stderr, "\n");                                                                       \
      return 1;                                                                                    \
    }                                                                                              \
  } while (0)

/* splitmix64: a small deterministic generator for test configurations. */
static inline uint64_t test_rng_next(uint64_t *s) {
  uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
static inline double test_rng_uniform(uint64_t *s) {
  return (test_rng_next(s) >> 11) * 0x1.0p-53;
}

/* A periodic mDPD scene (Warren 2003 parameters: A = -40, B = 25, rd = 0.75, gamma = 4.5, kT = 1)
 * with one species "liquid", box [0, L). Effects: none named; callers set scene->effect[...]. */
static inline void test_scene_mdpd(scene_t *s, double lx, double ly, double lz) {
  memset(s, 0, sizeof *s);
  s->neighbour_skin = -1.0; /* the backend's default, as scene_load sets it */
  snprintf(s->file, sizeof s->file, "(test scene)");
  snprintf(s->name, sizeof s->name, "test");
  const double L[3] = {lx, ly, lz};
  for (int d = 0; d < 3; d++) {
    s->box_lo[d] = 0.0;
    s->box_hi[d] = L[d];
    s->periodic[d] = 1;
  }
  s->n_species = 1;
  snprintf(s->species[0].name, SCENE_NAME_LEN, "liquid");
  s->species[0].mass = 1.0;
  for (int a = 0; a < SCENE_MAX_SPECIES; a++)
    for (int b = 0; b < SCENE_MAX_SPECIES; b++)
      s->pair[a][b] = (scene_pair_t){.A = -40, .B = 25, .gamma = 4.5, .rc = 1.0, .rd = 0.75};
  s->density_kernel = 0;
  s->kT = 1.0;
  s->vv_lambda = 0.5;
  s->dt = 0.01;
  s->seed = 12345;
}

/* Offer n particles at uniformly random positions (species by the given fraction of species 1) with
 * random velocities of unit variance, identically on every rank. Returns 0 or -1. */
static inline int test_fill_random(sim_t *sim, const scene_t *s, int n, double frac_species1,
                                   uint64_t seed) {
  uint64_t st = seed;
  for (int i = 0; i < n; i++) {
    double x[3], v[3];
    for (int d = 0; d < 3; d++)
      x[d] = s->box_lo[d] + (s->box_hi[d] - s->box_lo[d]) * test_rng_uniform(&st);
    for (int d = 0; d < 3; d++) v[d] = sqrt(3.0) * (2.0 * test_rng_uniform(&st) - 1.0);
    const int species = test_rng_uniform(&st) < frac_species1 ? 1 : 0;
    if (sim_add_particle(sim, i, species, x, v) < 0) return -1;
  }
  return 0;
}

#endif
