/* Particle arrays: allocation, growth, copies. */
#include "particle_store.h"

#include <stdlib.h>
#include <string.h>

static int grow(void **ptr, size_t elem, int n) {
  void *q = realloc(*ptr, elem * (size_t)n);
  if (!q) return -1;
  *ptr = q;
  return 0;
}

int pstore_reserve(particles_t *p, int n) {
  if (n <= p->capacity) return 0;
  int cap = p->capacity > 0 ? p->capacity : 64;
  while (cap < n) cap *= 2;
  int rc = grow((void **)&p->id, sizeof *p->id, cap) |
           grow((void **)&p->species, sizeof *p->species, cap);
  for (int d = 0; d < 3; d++) {
    rc |= grow((void **)&p->x[d], sizeof(double), cap) |
          grow((void **)&p->v[d], sizeof(double), cap) |
          grow((void **)&p->f[d], sizeof(double), cap);
    if (p->vpred[d]) rc |= grow((void **)&p->vpred[d], sizeof(double), cap);
  }
  if (p->rho) rc |= grow((void **)&p->rho, sizeof(double), cap);
  if (p->virial) rc |= grow((void **)&p->virial, 6 * sizeof(double), cap);
  if (rc) return -1;
  p->capacity = cap;
  return 0;
}

int pstore_init(particles_t *p, int with_rho, int with_vpred) {
  memset(p, 0, sizeof *p);
  const int cap = 64;
  if (with_rho && !(p->rho = malloc(cap * sizeof(double)))) return -1;
  for (int d = 0; d < 3 && with_vpred; d++)
    if (!(p->vpred[d] = malloc(cap * sizeof(double)))) return -1;
  int rc = grow((void **)&p->id, sizeof *p->id, cap) |
           grow((void **)&p->species, sizeof *p->species, cap);
  for (int d = 0; d < 3; d++)
    rc |= grow((void **)&p->x[d], sizeof(double), cap) |
          grow((void **)&p->v[d], sizeof(double), cap) |
          grow((void **)&p->f[d], sizeof(double), cap);
  if (rc) return -1;
  p->capacity = cap;
  return 0;
}

void pstore_free(particles_t *p) {
  free(p->id);
  free(p->species);
  for (int d = 0; d < 3; d++) {
    free(p->x[d]);
    free(p->v[d]);
    free(p->f[d]);
    free(p->vpred[d]);
  }
  free(p->rho);
  free(p->virial);
  memset(p, 0, sizeof *p);
}

int pstore_set_virial(particles_t *p, int on) {
  if (!on) {
    free(p->virial);
    p->virial = NULL;
    return 0;
  }
  if (p->virial) return 0;
  p->virial = calloc((size_t)(p->capacity > 0 ? p->capacity : 1) * 6, sizeof(double));
  return p->virial ? 0 : -1;
}

void pstore_copy(particles_t *p, int dst, int src) {
  p->id[dst] = p->id[src];
  p->species[dst] = p->species[src];
  for (int d = 0; d < 3; d++) {
    p->x[d][dst] = p->x[d][src];
    p->v[d][dst] = p->v[d][src];
    p->f[d][dst] = p->f[d][src];
  }
}
