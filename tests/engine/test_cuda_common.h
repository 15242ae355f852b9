/* Helpers of the CUDA tests: skip (exit 77, ctest "skipped") when no GPU is visible, and copy a
 * simulation's owned particles into arrays indexed by particle id. */
#ifndef TEST_CUDA_COMMON_H
#define TEST_CUDA_COMMON_H

#include "test_engine_common.h"

/* Exits 77 with "skipped: no GPU (...)" when the CUDA backend cannot run here. */
static inline void test_cuda_require_gpu(void) {
  int backend = 0;
  char err[512];
  if (sim_backend_choose("cuda", 1, &backend, err, sizeof err)) {
    const char *why = strstr(err, "available: ");
    printf("skipped: no GPU (%s)\n", why ? why + 11 : err);
    MPI_Finalize();
    exit(77);
  }
}

/* Per-id copies of x, v, f (3 n each) and rho (n; 0 without a density pass). */
typedef struct {
  double *x, *v, *f, *rho;
} test_state_t;

static inline int test_state_get(sim_t *sim, int n, test_state_t *st) {
  st->x = calloc(3 * (size_t)n, sizeof(double));
  st->v = calloc(3 * (size_t)n, sizeof(double));
  st->f = calloc(3 * (size_t)n, sizeof(double));
  st->rho = calloc((size_t)n, sizeof(double));
  if (!st->x || !st->v || !st->f || !st->rho) return -1;
  particles_t *p = sim_particles(sim);
  for (int i = 0; i < p->n_local; i++) {
    const int64_t id = p->id[i];
    if (id < 0 || id >= n) return -1;
    for (int d = 0; d < 3; d++) {
      st->x[3 * id + d] = p->x[d][i];
      st->v[3 * id + d] = p->v[d][i];
      st->f[3 * id + d] = p->f[d][i];
    }
    st->rho[id] = p->rho ? p->rho[i] : 0.0;
  }
  return 0;
}

static inline void test_state_free(test_state_t *st) {
  free(st->x);
  free(st->v);
  free(st->f);
  free(st->rho);
}

#endif
