/* Cell-centred two-point-flux finite volumes on a DMDA (physics.md section 6): the residual of each
 * block is its net outflow minus its source, F_c = (sum_faces A q_out - S_c) eq_scale, and its
 * analytic Jacobian. */
#ifndef MDPORE_UPSCALE_DARCY_FV_H
#define MDPORE_UPSCALE_DARCY_FV_H

#include <petscdmda.h>

#include "darcy_problem.h"
#include "law/face_flux.h"

/* Flux out of block (i,j,k) through one of its faces (FACE_XM..FACE_ZP) for pressure p_c in the
 * block and p_nb in the neighbour (ignored at a domain face). Returns the Darcy velocity result; at
 * a no-flow face q = dq_dp = 0. *area gets the face area. */
face_flux_result darcy_face(const darcy_problem *p, int i, int j, int k, int face, double p_c,
                            double p_nb, double *area);

PetscErrorCode darcy_residual_local(DMDALocalInfo *info, PetscScalar ***pr, PetscScalar ***f,
                                    void *ctx);
PetscErrorCode darcy_jacobian_local(DMDALocalInfo *info, PetscScalar ***pr, Mat J, Mat Jpre,
                                    void *ctx);

#endif
