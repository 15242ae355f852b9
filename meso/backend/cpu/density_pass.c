/* Density pass of many-body DPD (Warren 2003): rho_i = sum_{j != i, r < rd} w_rho(r; rd), with the
 * Warren or the Lucy kernel (meso/physics/density_kernels.h). Self term excluded (physics.md 1).
 * With plan.density_cache the densities of static frozen particles are split in two (cpu_passes.h:
 * density_cache_t): rho_i = rho_i^static + sum over the mobile and moving j, the first part summed
 * once and kept per particle id. */
#include "cpu_passes.h"
#include "neighbour_bins.h"
#include "physics/density_kernels.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The kernel sum of owned particle i (slot q in bin order) over its first m list entries whose
 * partner's static flag equals `want_static` (-1: every partner); kernel is a compile-time
 * constant after inlining. Only the near part of the neighbour list (within the row's largest rd)
 * is passed in. */
static inline __attribute__((always_inline)) double
density_sum(const plan_t *plan, const particles_t *p, const cell_list_t *cl, int q, int i,
            const nlist_t *nl, int m, const int kernel, const int want_static) {
  const double xi = cl->px[q], yi = cl->py[q], zi = cl->pz[q];
  const pair_coef_t *row = plan->coef[p->species[i]];
  const int *cand = nl->slot + (size_t)i * (size_t)nl->stride;
  double sum = 0.0;
  for (int k = 0; k < m; k++) {
    const int t = cand[k], j = cl->idx[t];
    if (want_static >= 0 && plan->static_frozen[p->species[j]] != want_static) continue;
    const double dx = xi - cl->px[t], dy = yi - cl->py[t], dz = zi - cl->pz[t];
    const double r2 = dx * dx + dy * dy + dz * dz;
    const pair_coef_t *c = &row[p->species[j]];
    if (r2 >= c->rd2) continue; /* species-dependent rd only */
    const double r = sqrt(r2);
    sum += kernel == MESO_KERNEL_LUCY ? w_rho_lucy_inv(r, c->inv_rd, c->wnorm)
                                      : w_rho_warren_inv(r, c->inv_rd, c->wnorm);
  }
  return sum;
}

/* The static part of a static frozen particle's density, summed in fixed point (units of 2^-44,
 * about 6e-14: each term rounded once, sums of up to ~2^19 kernel maxima fit in 63 bits), so that
 * it does not depend on the order of the list: a restart from a checkpoint (particles in another
 * order) rebuilds bitwise the value an uninterrupted run keeps. */
#define STATIC_FIXED_SCALE 17592186044416.0 /* 2^44 */
static inline __attribute__((always_inline)) double
density_static_part(const plan_t *plan, const particles_t *p, const cell_list_t *cl, int q, int i,
                    const nlist_t *nl, int m, const int kernel) {
  const double xi = cl->px[q], yi = cl->py[q], zi = cl->pz[q];
  const pair_coef_t *row = plan->coef[p->species[i]];
  const int *cand = nl->slot + (size_t)i * (size_t)nl->stride;
  int64_t sum = 0;
  for (int k = 0; k < m; k++) {
    const int t = cand[k], j = cl->idx[t];
    if (!plan->static_frozen[p->species[j]]) continue;
    const double dx = xi - cl->px[t], dy = yi - cl->py[t], dz = zi - cl->pz[t];
    const double r2 = dx * dx + dy * dy + dz * dz;
    const pair_coef_t *c = &row[p->species[j]];
    if (r2 >= c->rd2) continue;
    const double r = sqrt(r2);
    const double w = kernel == MESO_KERNEL_LUCY ? w_rho_lucy_inv(r, c->inv_rd, c->wnorm)
                                                : w_rho_warren_inv(r, c->inv_rd, c->wnorm);
    sum += (int64_t)llround(w * STATIC_FIXED_SCALE);
  }
  return (double)sum / STATIC_FIXED_SCALE;
}

/* rho of owned particle i. cache: 0 off; 1 valid (i static: cached part + its dynamic list);
 * 2 rebuilding (i static: both parts over the full list, the static one kept in rho_static). */
static inline __attribute__((always_inline)) double
density_of(const plan_t *plan, const particles_t *p, const cell_list_t *cl, int q, int i,
           const nlist_t *nl, density_cache_t *dc, const int kernel, const int cache) {
  const int m = nl->count_near[i];
  if (!cache || !plan->static_frozen[p->species[i]])
    return density_sum(plan, p, cl, q, i, nl, m, kernel, -1);
  if (cache == 1) return dc->rho_static[i] + density_sum(plan, p, cl, q, i, nl, m, kernel, 0);
  const double part_static = density_static_part(plan, p, cl, q, i, nl, m, kernel);
  dc->rho_static[i] = part_static;
  return part_static + density_sum(plan, p, cl, q, i, nl, m, kernel, 0);
}

#define DENSITY_LOOP(KERNEL, CACHE)                                                                \
  _Pragma("omp parallel for schedule(static)") for (int q = 0; q < nslots; q++) {                  \
    const int i = cl->idx[q];                                                                      \
    if (i < p->n_local) p->rho[i] = density_of(plan, p, cl, q, i, nl, dc, KERNEL, CACHE);          \
  }

#define DENSITY_KERNEL(CACHE)                                                                      \
  if (plan->density_kernel == MESO_KERNEL_LUCY)                                                    \
    DENSITY_LOOP(MESO_KERNEL_LUCY, CACHE)                                                          \
  else                                                                                             \
    DENSITY_LOOP(MESO_KERNEL_WARREN, CACHE)

/* splitmix64's finaliser: ids are dense integers, the table wants them spread. */
static inline size_t hash_id(int64_t id, size_t mask) {
  uint64_t z = (uint64_t)id + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return (size_t)(z ^ (z >> 31)) & mask;
}

static int table_rebuild(density_cache_t *dc, const plan_t *plan, const particles_t *p) {
  size_t n_static = 0;
  for (int i = 0; i < p->n_local; i++) n_static += plan->static_frozen[p->species[i]] != 0;
  size_t cap = 16;
  while (cap < 2 * n_static) cap *= 2;
  if (cap != dc->table_cap) {
    free(dc->key);
    free(dc->value);
    dc->key = malloc(cap * sizeof *dc->key);
    dc->value = malloc(cap * sizeof *dc->value);
    dc->table_cap = dc->key && dc->value ? cap : 0;
    if (!dc->table_cap) return -1;
  }
  memset(dc->key, 0, cap * sizeof *dc->key);
  const size_t mask = cap - 1;
  for (int i = 0; i < p->n_local; i++) {
    if (!plan->static_frozen[p->species[i]]) continue;
    size_t h = hash_id(p->id[i], mask);
    while (dc->key[h] != 0) h = (h + 1) & mask;
    dc->key[h] = p->id[i] + 1;
    dc->value[h] = dc->rho_static[i];
  }
  dc->rebuilds++;
  return 0;
}

int cpu_density_pass(const plan_t *plan, particles_t *p, const cell_list_t *cl, const nlist_t *nl,
                     density_cache_t *dc) {
  const int nslots = p->n_local + p->n_ghost;
  if (!plan->density_cache || !dc) {
    DENSITY_KERNEL(0)
    return 0;
  }
  if (dc->valid) {
    DENSITY_KERNEL(1)
    return 0;
  }
  DENSITY_KERNEL(2)
  return table_rebuild(dc, plan, p);
}

static int grow(void **a, int *cap, int n, size_t size) {
  if (n <= *cap) return 0;
  void *q = realloc(*a, (size_t)n * size);
  if (!q) return -1;
  *a = q;
  *cap = n;
  return 0;
}

int cpu_density_cache_prepare(density_cache_t *dc, const plan_t *plan, const particles_t *p,
                              const cell_list_t *cl) {
  dc->valid = 0;
  if (!plan->density_cache) return 0;
  const int nslots = p->n_local + p->n_ghost;
  int cap_n = dc->cap_n;
  if (grow((void **)&dc->rho_static, &cap_n, p->n_local + 1, sizeof(double)) ||
      grow((void **)&dc->dynamic_prefix, &dc->cap_slots, nslots + 1, sizeof(int)))
    return -1;
  dc->cap_n = cap_n;
  int run = 0;
  for (int t = 0; t < nslots; t++) {
    dc->dynamic_prefix[t] = run;
    run += !plan->static_frozen[p->species[cl->idx[t]]];
  }
  dc->dynamic_prefix[nslots] = run;
  if (!dc->table_cap) return 0; /* never built: this step's pass builds it */
  const size_t mask = dc->table_cap - 1;
  long misses = 0;
#pragma omp parallel for schedule(static) reduction(+ : misses)
  for (int i = 0; i < p->n_local; i++) {
    if (!plan->static_frozen[p->species[i]]) continue;
    size_t h = hash_id(p->id[i], mask);
    while (dc->key[h] != 0 && dc->key[h] != p->id[i] + 1) h = (h + 1) & mask;
    if (dc->key[h] == 0)
      misses++;
    else
      dc->rho_static[i] = dc->value[h];
  }
  dc->valid = misses == 0;
  return 0;
}

void cpu_density_cache_free(density_cache_t *dc) {
  free(dc->key);
  free(dc->value);
  free(dc->rho_static);
  free(dc->dynamic_prefix);
  memset(dc, 0, sizeof *dc);
}
