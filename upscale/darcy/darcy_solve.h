/* Solves a darcy_problem on a PETSc DMDA: one KSP solve (conjugate gradients) when every block
 * follows Darcy's law, else Newton (SNES) with the analytic Jacobian, started from the linearised
 * problem's solution. PETSc options: prefix -darcy_ (e.g. -darcy_snes_monitor, -darcy_ksp_type). */
#ifndef MDPORE_UPSCALE_DARCY_SOLVE_H
#define MDPORE_UPSCALE_DARCY_SOLVE_H

#include <mpi.h>

#include "darcy_problem.h"

typedef struct {
  int linear;       /* 1: all-Darcy, solved with KSP only */
  int converged;    /* 1 if the solver met its tolerance */
  int newton_its;   /* SNES iterations (0 for linear) */
  int linear_its;   /* total KSP iterations */
  double residual;  /* final residual norm (volumetric flux units: the net outflow imbalance) */
  double residual0; /* residual norm of the initial guess */
  char reason[64];
} darcy_stats;

/* Collective on comm. On success the pressure of every block (natural order, x fastest) is returned
 * in a malloc'd array on rank 0 (*pressure is NULL on other ranks). Returns 0, or non-zero on a
 * PETSc error. */
int darcy_solve(MPI_Comm comm, darcy_problem *p, double **pressure, darcy_stats *st);

#endif
