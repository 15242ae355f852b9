/* Incompressible water/oil displacement by IMPES (docs/twophase-darcy.md): at each step the
 * pressure equation  div(k lambda_t(S) grad p) = -q_t  is solved implicitly with the single-phase
 * assembly (darcy_fv.c, darcy_solve.c), every block's permeability scaled by its total mobility
 * lambda_t = krw/mu_w + kro/mu_o; then the water saturation is advanced explicitly,
 *   phi V dS/dt = - sum_faces f_w(S_upstream) F_face + sources,
 * with single-point upstream weighting and a CFL time step. No capillary pressure, no gravity. */
#ifndef MDPORE_UPSCALE_TWOPHASE_IMPES_H
#define MDPORE_UPSCALE_TWOPHASE_IMPES_H

#include <mpi.h>

#include "darcy_config.h"

typedef struct {
  long steps;
  double pv_injected, oil_recovery, water_cut;
  double breakthrough_pvi; /* pore volumes injected when the water cut first exceeds f_w(s_init)
                             by 1e-6 (water breakthrough); -1: not reached */
  double oil_balance_rel;  /* |oil in place + produced - initial| / initial oil in place */
  double max_dfw;          /* largest df_w/dS over the saturation range (CFL) */
  int linear_its;          /* pressure solves: total CG iterations */
} twophase_summary;

/* Collective on comm; rank 0 writes the files and fills *sum. Returns 0, or non-zero after a
 * message (a pressure solve that fails or does not converge, a file that cannot be written). */
int twophase_run(MPI_Comm comm, darcy_config *c, twophase_summary *sum);

#endif
