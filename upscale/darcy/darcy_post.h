/* Quantities derived from a solved pressure field (rank 0, serial): face fluxes and face pressures,
 * each block's pressure drop and mean gradient along each axis (what the coupling loop hands to the
 * next pore-scale runs), effective permeability of the domain and the mass balance. */
#ifndef MDPORE_UPSCALE_DARCY_POST_H
#define MDPORE_UPSCALE_DARCY_POST_H

#include "darcy_problem.h"

typedef struct {
  double *flux[3];    /* volumetric rate through each face along +axis; flux[0] is (nx+1) x ny x nz
                         (index i + (nx+1)(j + ny k)), likewise for y and z */
  double *face_p[3];  /* pressure on each face, same layout */
  double *block_dp;   /* per block and axis: p(minus face) - p(plus face), index 3 b + axis */
  double *block_grad; /* per block and axis: mean gradient G = -dp/dx = block_dp / h */
  int keff_defined[3];
  double
      keff[3]; /* effective permeability along axes with both end faces at uniform fixed pressure */
  double q_in[3],
      q_out[3]; /* volumetric inflow through the minus face, outflow through the plus face */
  double net_boundary_outflow, total_source, mass_balance_rel;
  double pmin, pmax;
} darcy_post;

long darcy_post_face_count(const darcy_problem *p, int axis);
/* 0, or -1 when its arrays cannot be allocated (out freed: nothing to free). */
int darcy_post_compute(const darcy_problem *p, const double *pressure, darcy_post *out);
void darcy_post_free(darcy_post *out);

#endif
