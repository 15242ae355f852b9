/* CPU (OpenMP) pair passes over owned particles with full neighbour traversal: each pair is
 * evaluated from both sides, each owned particle's sum is done by one thread in bin order
 * (deterministic, independent of the thread count). */
#ifndef MESO_BACKEND_CPU_PASSES_H
#define MESO_BACKEND_CPU_PASSES_H

#include "engine/cell_list.h"
#include "engine/particles.h"
#include "engine/plan.h"

#include <stdint.h>

/* rho_i = sum_{j != i, r < rd} w_rho(r) for owned i (physics.md section 1; self term excluded). */
void cpu_density_pass(const plan_t *plan, particles_t *p, const cell_list_t *cl);

typedef struct {
  uint64_t seed;
  uint64_t step; /* step index of this force evaluation (keys the random numbers) */
  double dt;
  int per_particle_virial; /* fill p->virial */
  double
      virial[6]; /* out: 1/2 sum_{owned i} sum_j r_ij,a F_ij,b (xx yy zz xy xz yz), pair forces */
} force_pass_args_t;

/* f_i = sum_j F_ij for owned i, F_ij from the pair terms of the plan (meso/physics/pair_forces.h).
 * Overwrites p->f of owned particles. */
void cpu_force_pass(const plan_t *plan, particles_t *p, const cell_list_t *cl,
                    force_pass_args_t *args);

#endif
