/* A continuum flow problem on a structured grid of rock blocks (cells): geometry, one flow law per
 * block, boundary conditions and sources. Block arrays are global (every rank holds them): block
 * grids for upscaling and coupling have thousands of blocks, not billions. Index of block (i,j,k):
 * i + nx (j + ny k), x fastest. A 2D problem is nz = 1 with unit depth. */
#ifndef MDPORE_UPSCALE_DARCY_PROBLEM_H
#define MDPORE_UPSCALE_DARCY_PROBLEM_H

#include "law/flow_law.h"

enum { FACE_XM = 0, FACE_XP, FACE_YM, FACE_YP, FACE_ZM, FACE_ZP };

typedef struct {
  int dim;     /* 2 or 3 */
  int n[3];    /* cells per axis (n[2] = 1 in 2D) */
  double h[3]; /* cell size per axis (h[2] = 1, unit depth, in 2D) */
  fluid_props fluid;
  flow_law *laws; /* one per block: its law along x, and along every axis a whose laws_axis[a] is
                     NULL (a scalar law: the same for the faces of every direction) */
  double *k_lin;  /* per block: permeability of the law linearised at the characteristic gradient */
  /* A diagonal permeability per block: laws_axis[a] (a = 1, 2; laws_axis[0] stays NULL, x is
   * `laws`) is the law of every block along axis a, used for the faces normal to a; k_lin_axis[a]
   * is its linearised permeability. NULL (the default): every direction uses `laws`. */
  flow_law *laws_axis[3];
  double *k_lin_axis[3];
  int fixed[6];    /* 1: fixed pressure on that face, 0: no flow */
  double *bc_p[6]; /* fixed pressures, one per boundary cell of the face (NULL when not fixed);
                      x faces indexed j + ny k, y faces i + nx k, z faces i + nx j */
  double *source;  /* volumetric rate into each block (negative: sink), or NULL */
  double g_lin;    /* power laws are linear below this gradient (flow_law_q) */
  double eq_scale; /* residual scale 1/C_ref (C_ref a typical face conductance): equations then read
                      in pressure units and the Jacobian is O(1), whatever the unit system */
  double p_scale;  /* characteristic pressure difference (for absolute tolerances) */
  double rtol;     /* solver relative tolerance */
  int max_it;      /* Newton iterations */
  /* Periodic problem (upscaling, darcy_upscale.h): every axis of the grid wraps, no face is fixed,
   * and the pressure is p = p~ - drive . x with p~ periodic: the unknowns are p~, every face along
   * an axis adds drive[axis] h[axis] to the drop p~_a - p~_b, and block (0,0,0) is tied to p~ = 0
   * through one typical conductance (exact: no flow through that tie at the solution). */
  int periodic;
  double drive[3]; /* mean driving gradient -grad p of a periodic problem */
} darcy_problem;

static inline long darcy_index(const darcy_problem *p, int i, int j, int k) {
  return i + (long)p->n[0] * (j + (long)p->n[1] * k);
}
/* Whether the neighbour across `face` of block c[3] is a block (wrapping on a periodic problem). */
static inline int darcy_has_neighbour(const darcy_problem *p, const int c[3], int face) {
  int axis = face / 2, m = c[axis] + (face % 2 ? 1 : -1);
  return p->periodic ? axis < p->dim : (m >= 0 && m < p->n[axis]);
}
static inline long darcy_nblocks(const darcy_problem *p) {
  return (long)p->n[0] * p->n[1] * p->n[2];
}
/* The law of block b along axis a (the faces normal to a). */
static inline const flow_law *darcy_law(const darcy_problem *p, long b, int a) {
  return p->laws_axis[a] ? &p->laws_axis[a][b] : &p->laws[b];
}
/* The linearised permeability of block b along axis a. */
static inline double darcy_k_lin(const darcy_problem *p, long b, int a) {
  return p->k_lin_axis[a] ? p->k_lin_axis[a][b] : p->k_lin[b];
}
/* Whether any block has a law along some axis other than its x law (a diagonal permeability). */
static inline int darcy_is_diagonal(const darcy_problem *p) {
  return p->laws_axis[1] || p->laws_axis[2];
}
/* Index into bc_p[face] of the boundary cell (i,j,k). */
static inline long darcy_face_index(const darcy_problem *p, int face, int i, int j, int k) {
  int axis = face / 2;
  if (axis == 0) return j + (long)p->n[1] * k;
  if (axis == 1) return i + (long)p->n[0] * k;
  return i + (long)p->n[0] * j;
}
static inline long darcy_face_count(const darcy_problem *p, int face) {
  int axis = face / 2;
  return (long)p->n[(axis + 1) % 3] * p->n[(axis + 2) % 3];
}

/* Gives the problem per-axis laws (laws_axis[1..dim-1] and their k_lin_axis), each a copy of
 * `laws` until set; nothing when already there. 0, or -1 when out of memory. */
int darcy_problem_make_diagonal(darcy_problem *p);

/* Fills k_lin (and k_lin_axis), g_lin (from the characteristic gradient = largest fixed-pressure difference over the
 * domain length), p_scale and eq_scale. Call after laws, boundary values and sizes are set. */
void darcy_problem_linearise(darcy_problem *p, double g_lin_fraction);
void darcy_problem_free(darcy_problem *p);

#endif
