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

/* Densities of static frozen particles computed once (plan.density_cache; density_pass.c). A
 * static frozen particle (frozen, not moving) never moves, so the part of its density from other
 * static frozen particles never changes: it is kept in a table keyed by the particle id (so it
 * survives the sort and needs no care at migration: static particles never change rank) and each
 * step only the mobile and moving neighbours' part is added. The lists of static frozen particles
 * then hold only those neighbours within rd (the force pass and the wall field never read a frozen
 * particle's list), and a bin row without any is not even scanned: a wall particle with no mobile
 * neighbour within its rows costs 9 subtractions. */
typedef struct {
  int valid;           /* this step: every owned static frozen particle was found in the table */
  int64_t *key;        /* open-addressing table: id + 1 (0 = empty) */
  double *value;       /* the static-static part of that particle's density */
  size_t table_cap;    /* power of 2 */
  double *rho_static;  /* [n_local]: the table's value for owned static frozen particle i */
  int *dynamic_prefix; /* [nslots + 1]: non-static (mobile or moving) slots before slot t */
  int cap_n, cap_slots;
  long rebuilds; /* times the table was (re)built */
} density_cache_t;

/* Before the list build of a step (after the cell list): the prefix of non-static slots and each
 * owned static particle's cached part; valid = 1 when every one was found (else this step's pass
 * rebuilds the table). Off (valid = 0, nothing allocated) without plan.density_cache. 0 or -1. */
int cpu_density_cache_prepare(density_cache_t *dc, const plan_t *plan, const particles_t *p,
                              const cell_list_t *cl);
void cpu_density_cache_free(density_cache_t *dc);

/* Build the lists of all owned particles of p. 0 or -1 (out of memory). With a valid density
 * cache (else NULL) a static frozen particle's list holds only its non-static partners within rd. */
int cpu_neighbours_build(nlist_t *nl, const plan_t *plan, const particles_t *p,
                         const cell_list_t *cl, const density_cache_t *dc);
void cpu_neighbours_free(nlist_t *nl);

/* rho_i = sum_{j != i, r < rd} w_rho(r) for owned i (physics.md section 1; self term excluded).
 * With the density cache (dc non-NULL under plan.density_cache): a static frozen particle's rho is
 * its cached static part plus the sum over its (non-static) list; on a step whose cache is not
 * valid both parts are summed over the full lists and the table is rebuilt. 0 or -1 (memory). */
int cpu_density_pass(const plan_t *plan, particles_t *p, const cell_list_t *cl, const nlist_t *nl,
                     density_cache_t *dc);

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
