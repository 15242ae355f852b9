/* Flat particle sets: allocation and sorting by id. */
#include "io/particle_set.h"

#include <stdlib.h>
#include <string.h>

int particle_set_alloc(particle_set_t *s, long n, int with_f, int with_rho) {
  memset(s, 0, sizeof *s);
  const size_t m = (size_t)(n > 0 ? n : 1);
  s->id = malloc(m * sizeof *s->id);
  s->species = malloc(m * sizeof *s->species);
  s->x = malloc(3 * m * sizeof *s->x);
  s->v = calloc(3 * m, sizeof *s->v);
  if (with_f) s->f = calloc(3 * m, sizeof *s->f);
  if (with_rho) s->rho = calloc(m, sizeof *s->rho);
  s->n = n;
  s->capacity = (long)m;
  if (!s->id || !s->species || !s->x || !s->v || (with_f && !s->f) || (with_rho && !s->rho)) {
    particle_set_free(s);
    return -1;
  }
  return 0;
}

void particle_set_free(particle_set_t *s) {
  free(s->id);
  free(s->species);
  free(s->x);
  free(s->v);
  free(s->f);
  free(s->rho);
  memset(s, 0, sizeof *s);
}

/* qsort's comparator context: one per thread (the replicas of mdpore run --replicas sort at once) */
static _Thread_local const int64_t *sort_ids;
static int by_id(const void *a, const void *b) {
  const int64_t x = sort_ids[*(const long *)a], y = sort_ids[*(const long *)b];
  return (x > y) - (x < y);
}

/* arr reordered by perm through tmp (n * elem bytes). */
static void permute(void *arr, size_t elem, const long *perm, long n, char *tmp) {
  if (!arr) return;
  char *src = arr;
  for (long i = 0; i < n; i++) memcpy(tmp + (size_t)i * elem, src + (size_t)perm[i] * elem, elem);
  memcpy(src, tmp, (size_t)n * elem);
}

int particle_set_sort_by_id(particle_set_t *s) {
  if (s->n < 2) return 0;
  /* both work arrays first: a failure leaves the set as it was */
  long *perm = malloc((size_t)s->n * sizeof *perm);
  char *tmp = malloc((size_t)s->n * 3 * sizeof(double)); /* the largest element: x, v, f */
  if (!perm || !tmp) {
    free(perm), free(tmp);
    return -1;
  }
  for (long i = 0; i < s->n; i++) perm[i] = i;
  sort_ids = s->id;
  qsort(perm, (size_t)s->n, sizeof *perm, by_id);
  permute(s->id, sizeof *s->id, perm, s->n, tmp);
  permute(s->species, sizeof *s->species, perm, s->n, tmp);
  permute(s->x, 3 * sizeof *s->x, perm, s->n, tmp);
  permute(s->v, 3 * sizeof *s->v, perm, s->n, tmp);
  permute(s->f, 3 * sizeof *s->f, perm, s->n, tmp);
  permute(s->rho, sizeof *s->rho, perm, s->n, tmp);
  free(perm), free(tmp);
  return 0;
}
