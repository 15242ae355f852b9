/* 3D Cartesian domain decomposition: one box-aligned subdomain per rank (MPI_Cart_create). The
 * cuts along each axis are uniform at creation; decomp_set_cuts moves them (load balancing,
 * domain/balance.h): the grid stays a tensor product of per-axis cuts, so every rank keeps its six
 * face neighbours. */
#ifndef MESO_ENGINE_DECOMP_H
#define MESO_ENGINE_DECOMP_H

#include "scene/scene.h"

#include <mpi.h>
#include <stddef.h>

typedef struct {
  MPI_Comm cart;
  int rank, nranks;
  int dims[3], coords[3], periodic[3];
  int nbr[3]
         [2]; /* neighbour rank below (0) and above (1) along each axis; MPI_PROC_NULL at walls */
  double box_lo[3], box_hi[3], L[3];
  double lo[3], hi[3]; /* this rank's subdomain [lo, hi) */
  double *cut[3]; /* dims[d] + 1 bounds along axis d: cut[d][0] = box_lo, cut[d][dims] = box_hi */
  double rcut;    /* the ghost cutoff: no subdomain thinner than it                           */
} decomp_t;

/* Grid dims for nranks: scene.procs, zeros filled by MPI_Dims_create. 0, or -1 with a message. */
int decomp_dims(const scene_t *s, int nranks, int dims[3], char *err, size_t errlen);
/* Build the decomposition on comm (collective). Every subdomain must be at least rcut wide (ghosts
 * come from the nearest neighbours only). 0, or -1 with a message. */
int decomp_create(decomp_t *dc, const scene_t *s, MPI_Comm comm, double rcut, char *err,
                  size_t errlen);
void decomp_free(decomp_t *dc);
/* Lower bound of subdomain c (c = dims gives box_hi) along axis d. */
double decomp_bound(const decomp_t *dc, int d, int c);
/* Replace the cuts along axis d by cuts[0..dims[d]] (cuts[0] and cuts[dims] must be the box bounds,
 * increasing, every slab at least rcut wide) and update this rank's [lo, hi). Particles are not
 * moved (domain/redistribute.h does that). 0, or -1 with a message. */
int decomp_set_cuts(decomp_t *dc, int d, const double *cuts, char *err, size_t errlen);
/* The Cartesian coordinate along axis d of the subdomain holding coordinate x (x inside the box). */
int decomp_coord_of(const decomp_t *dc, int d, double x);
/* Wrap a position into the box along the periodic axes. */
void decomp_wrap(const decomp_t *dc, double x[3]);
/* 1 when x lies in this rank's subdomain. */
int decomp_owns(const decomp_t *dc, const double x[3]);

#endif
