/* CPU (OpenMP) pair passes over owned particles with full neighbour traversal: each pair is
 * evaluated from both sides, each owned particle's sum is done by one thread in bin order
 * (deterministic, independent of the thread count). */
#ifndef MESO_BACKEND_CPU_PASSES_H
#define MESO_BACKEND_CPU_PASSES_H

#include "domain/cell_list.h"
#include "domain/particles.h"
#include "effects/plan.h"
#include "physics/wall_boundary.h"

#include <stdint.h>

/* Neighbour lists of the owned particles for one step: the bin slots (other than the particle's
 * own) within the largest cutoff of the particle's species row, built once and used by the density
 * and the force pass. Each list holds first the neighbours within the row's largest rd (count_near
 * of them), then the others, each part in bin order, so the density pass and the many-body term
 * loop without unpredictable branches. */
typedef struct {
  int stride;      /* room per particle; grown when a particle has more neighbours */
  int *count;      /* [n_local] */
  int *count_near; /* [n_local] */
  int *slot;       /* [n_local * stride] */
  size_t cap;      /* allocated slots */
  int cap_n;       /* allocated counts */
} nlist_t;

/* Build the lists of all owned particles of p. 0 or -1 (out of memory). */
int cpu_neighbours_build(nlist_t *nl, const plan_t *plan, const particles_t *p,
                         const cell_list_t *cl);
void cpu_neighbours_free(nlist_t *nl);

/* rho_i = sum_{j != i, r < rd} w_rho(r) for owned i (physics.md section 1; self term excluded). */
void cpu_density_pass(const plan_t *plan, particles_t *p, const cell_list_t *cl, const nlist_t *nl);

/* wall_boundary: phi_i and grad phi_i of every owned particle into field[i] (0 for frozen ones). */
void cpu_wall_field_pass(const plan_t *plan, const particles_t *p, const cell_list_t *cl,
                         const nlist_t *nl, wall_field_t *field);

typedef struct {
  uint64_t seed;
  uint64_t step;           /* step index of this force evaluation (keys the random numbers) */
  double inv_sqrt_dt;      /* 1 / sqrt(dt) of the random force (plan.inv_sqrt_dt) */
  int per_particle_virial; /* fill p->virial */
  double
      virial[6]; /* out: 1/2 sum_{owned i} sum_j r_ij,a F_ij,b (xx yy zz xy xz yz), pair forces */
} force_pass_args_t;

/* f_i = sum_j F_ij for owned i, F_ij from the pair terms of the plan (meso/physics/pair_forces.h).
 * Overwrites p->f of owned particles. */
void cpu_force_pass(const plan_t *plan, particles_t *p, const cell_list_t *cl, const nlist_t *nl,
                    force_pass_args_t *args);

#endif
