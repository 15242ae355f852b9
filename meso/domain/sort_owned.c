/* Counting sort of the owned particles by bin (see sort_owned.h). */
#include "sort_owned.h"

#include <stdlib.h>
#include <string.h>

void sort_scratch_free(sort_scratch_t *s) {
  free(s->key);
  free(s->count);
  free(s->perm);
  free(s->tmp);
  memset(s, 0, sizeof *s);
}

static int reserve(sort_scratch_t *s, int n, int ncell) {
  if (n > s->cap) {
    const int cap = n + n / 4 + 64;
    int *k = realloc(s->key, (size_t)cap * sizeof(int));
    if (k) s->key = k;
    int *q = realloc(s->perm, (size_t)cap * sizeof(int));
    if (q) s->perm = q;
    void *t = realloc(s->tmp, (size_t)cap * sizeof(double));
    if (t) s->tmp = t;
    if (!k || !q || !t) return -1;
    s->cap = cap;
  }
  if (ncell + 1 > s->cap_cells) {
    int *c = realloc(s->count, (size_t)(ncell + 1) * sizeof(int));
    if (!c) return -1;
    s->count = c;
    s->cap_cells = ncell + 1;
  }
  return 0;
}

static void permute_double(double *a, const int *perm, int n, double *tmp) {
  for (int k = 0; k < n; k++) tmp[k] = a[perm[k]];
  memcpy(a, tmp, (size_t)n * sizeof(double));
}

int sort_owned_by_bin(particles_t *p, const double lo[3], const double hi[3], double rcut,
                      sort_scratch_t *s) {
  const int n = p->n_local;
  if (n < 2 || !(rcut > 0)) return 0;
  int nb[3];
  double inv[3];
  for (int d = 0; d < 3; d++) {
    const double extent = hi[d] - lo[d];
    nb[d] = (int)(extent / rcut);
    if (nb[d] < 1) nb[d] = 1;
    inv[d] = nb[d] / extent;
  }
  const int ncell = nb[0] * nb[1] * nb[2];
  if (reserve(s, n, ncell)) return -1;
  memset(s->count, 0, (size_t)(ncell + 1) * sizeof(int));
  for (int i = 0; i < n; i++) {
    int b[3];
    for (int d = 0; d < 3; d++) {
      const double u = (p->x[d][i] - lo[d]) * inv[d];
      b[d] = u > 0 ? (int)u : 0; /* NaN and rounding go to the edge bins */
      if (b[d] >= nb[d]) b[d] = nb[d] - 1;
    }
    s->key[i] = b[0] + nb[0] * (b[1] + nb[1] * b[2]);
    s->count[s->key[i] + 1]++;
  }
  for (int c = 0; c < ncell; c++) s->count[c + 1] += s->count[c];
  for (int i = 0; i < n; i++) s->perm[s->count[s->key[i]]++] = i; /* stable */
  double *tmp = s->tmp;
  for (int d = 0; d < 3; d++) {
    permute_double(p->x[d], s->perm, n, tmp);
    permute_double(p->v[d], s->perm, n, tmp);
    permute_double(p->f[d], s->perm, n, tmp);
  }
  int64_t *ti = (int64_t *)tmp; /* int64 fits the double-sized scratch */
  for (int k = 0; k < n; k++) ti[k] = p->id[s->perm[k]];
  memcpy(p->id, ti, (size_t)n * sizeof(int64_t));
  int32_t *ts = (int32_t *)tmp;
  for (int k = 0; k < n; k++) ts[k] = p->species[s->perm[k]];
  memcpy(p->species, ts, (size_t)n * sizeof(int32_t));
  return 0;
}
