/* The mDPD water scene the benchmarks build in code (not a test): A = -40 for every pair, B = 25,
 * rc = 1, rd = 0.75, gamma = 4.5, kT = 1, vv_lambda = 0.5, dt = 0.01, seed 7, periodic box
 * [0, L), mdpd_attraction + mdpd_repulsion + dpd_thermostat; species 0 "fluid" (mass 1) and, with
 * n_species 2, a frozen species 1 "wall". The caller adds the rest (body force, generator, ...). */
#ifndef MDPORE_BENCH_SCENE_H
#define MDPORE_BENCH_SCENE_H

#include "effects/effect.h"
#include "scene/scene.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* U[0, 1) from a SplitMix64 stream (Steele, Lea & Flood 2014) advanced in *state: the benchmarks'
 * random start configurations (not the physics' random numbers). */
static inline double bench_uniform(uint64_t *state) {
  uint64_t z = (*state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return (double)((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

static inline void bench_scene_mdpd(scene_t *s, const char *name, const double L[3],
                                    int n_species) {
  memset(s, 0, sizeof *s);
  snprintf(s->file, sizeof s->file, "(%s)", name);
  snprintf(s->name, sizeof s->name, "%s", name);
  s->neighbour_skin = -1.0;
  for (int d = 0; d < 3; d++) {
    s->box_hi[d] = L[d];
    s->periodic[d] = 1;
  }
  s->n_species = n_species;
  snprintf(s->species[0].name, SCENE_NAME_LEN, "fluid");
  snprintf(s->species[1].name, SCENE_NAME_LEN, "wall");
  s->species[0].mass = s->species[1].mass = 1.0;
  s->species[1].frozen = 1;
  for (int a = 0; a < SCENE_MAX_SPECIES; a++)
    for (int b = 0; b < SCENE_MAX_SPECIES; b++)
      s->pair[a][b] = (scene_pair_t){.A = -40, .B = 25, .gamma = 4.5, .rc = 1.0, .rd = 0.75};
  s->kT = 1.0;
  s->vv_lambda = 0.5;
  s->dt = 0.01;
  s->seed = 7;
  effect_name_in_scene(s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(s, EFFECT_DPD_THERMOSTAT);
}

#endif
