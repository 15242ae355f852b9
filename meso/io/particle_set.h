/* A flat set of particles (all of them, or one rank's), independent of the engine: what the readers
 * (LAMMPS data, snapshots) produce and what the writers (snapshots, dumps, LAMMPS data) consume.
 * Vectors are interleaved: x[3 i + d]. */
#ifndef MESO_IO_PARTICLE_SET_H
#define MESO_IO_PARTICLE_SET_H

#include <stdint.h>

typedef struct {
  long n, capacity;
  int64_t *id;
  int32_t *species;
  double *x, *v;
  double *f;   /* NULL unless requested */
  double *rho; /* NULL unless present   */
  int has_v;   /* velocities were given (readers) */
} particle_set_t;

/* Allocate room for n particles (f and rho only when asked). 0 or -1. */
int particle_set_alloc(particle_set_t *s, long n, int with_f, int with_rho);
/* Bytes per particle of a set: what a reader checks against the memory limit (common/size_check.h)
 * before particle_set_alloc, from the count its file declares. */
static inline double particle_set_bytes(int with_f, int with_rho) {
  return (double)(sizeof(int64_t) + sizeof(int32_t) + 6 * sizeof(double)) +
         (with_f ? 3.0 * sizeof(double) : 0.0) + (with_rho ? (double)sizeof(double) : 0.0);
}
void particle_set_free(particle_set_t *s);
/* Reorder by increasing id (outputs are sorted so files compare line by line). 0, or -1 when its
 * work arrays cannot be allocated (the set unchanged). */
int particle_set_sort_by_id(particle_set_t *s);

#endif
