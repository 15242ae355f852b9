/* DMDA + KSP/SNES driver (see darcy_solve.h). */
#include "darcy_solve.h"

#include <petscdmda.h>
#include <petscsnes.h>
#include <stdlib.h>
#include <string.h>

#include "darcy_fv.h"

static int all_darcy(const darcy_problem *p) {
  for (int a = 0; a < 3; a++)
    for (long b = 0; b < darcy_nblocks(p); b++)
      if (darcy_law(p, b, a)->kind != LAW_DARCY) return 0;
  return 1;
}

/* One linear solve J x = -F(0) for a problem whose residual is affine in p (all-Darcy laws). */
static PetscErrorCode linear_solve(SNES snes, Vec x, double rtol, darcy_stats *st) {
  Vec F;
  Mat J;
  KSP ksp;
  DM da;
  PetscFunctionBeginUser;
  PetscCall(SNESGetDM(snes, &da));
  PetscCall(VecDuplicate(x, &F));
  PetscCall(DMCreateMatrix(da, &J));
  PetscCall(VecSet(x, 0.0));
  PetscCall(SNESComputeFunction(snes, x, F));
  PetscCall(SNESComputeJacobian(snes, x, J, J));
  PetscCall(VecScale(F, -1.0));
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)da), &ksp));
  PetscCall(KSPSetOperators(ksp, J, J));
  PetscCall(KSPSetType(ksp, KSPCG)); /* the two-point-flux matrix is symmetric positive definite */
  PetscCall(KSPSetTolerances(ksp, rtol, 1e-300, PETSC_DEFAULT, 10000));
  PetscCall(KSPSetOptionsPrefix(ksp, "darcy_"));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(KSPSolve(ksp, F, x));
  KSPConvergedReason why;
  PetscInt its;
  PetscCall(KSPGetConvergedReason(ksp, &why));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  st->linear_its += (int)its;
  st->converged = why > 0;
  snprintf(st->reason, sizeof st->reason, "%s", KSPConvergedReasons[why]);
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&F));
  PetscFunctionReturn(0);
}

static PetscErrorCode residual_norm(SNES snes, Vec x, double *norm) {
  Vec F;
  PetscReal nr;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(x, &F));
  PetscCall(SNESComputeFunction(snes, x, F));
  PetscCall(VecNorm(F, NORM_2, &nr));
  *norm = nr;
  {
    const darcy_problem *p;
    DM da;
    PetscCall(SNESGetDM(snes, &da));
    PetscCall(DMGetApplicationContext(da, &p));
    if (p) *norm /= p->eq_scale; /* back to volumetric flux units */
  }
  PetscCall(VecDestroy(&F));
  PetscFunctionReturn(0);
}

/* Copies the distributed solution into a natural-ordered array on rank 0. */
static PetscErrorCode gather(DM da, Vec x, double **out) {
  Vec nat, seq;
  VecScatter sc;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)da), &rank));
  PetscCall(DMDACreateNaturalVector(da, &nat));
  PetscCall(DMDAGlobalToNaturalBegin(da, x, INSERT_VALUES, nat));
  PetscCall(DMDAGlobalToNaturalEnd(da, x, INSERT_VALUES, nat));
  PetscCall(VecScatterCreateToZero(nat, &sc, &seq));
  PetscCall(VecScatterBegin(sc, nat, seq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, nat, seq, INSERT_VALUES, SCATTER_FORWARD));
  *out = NULL;
  if (rank == 0) {
    PetscInt n;
    const PetscScalar *a;
    PetscCall(VecGetSize(seq, &n));
    *out = malloc((n ? (size_t)n : 1) * sizeof(double));
    PetscCall(VecGetArrayRead(seq, &a));
    if (*out) memcpy(*out, a, (size_t)n * sizeof(double));
    PetscCall(VecRestoreArrayRead(seq, &a));
  }
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&seq));
  PetscCall(VecDestroy(&nat));
  /* every rank fails together when rank 0 has no room for the field */
  int oom = rank == 0 && !*out;
  PetscCallMPI(MPI_Bcast(&oom, 1, MPI_INT, 0, PetscObjectComm((PetscObject)da)));
  PetscCheck(!oom, PetscObjectComm((PetscObject)da), PETSC_ERR_MEM,
             "out of memory for the pressure field on rank 0");
  PetscFunctionReturn(0);
}

static PetscErrorCode solve(MPI_Comm comm, darcy_problem *p, double **pressure, darcy_stats *st) {
  DM da;
  SNES snes;
  Vec x;
  PetscFunctionBeginUser;
  memset(st, 0, sizeof *st);
  DMBoundaryType bt[3];
  for (int a = 0; a < 3; a++)
    bt[a] = p->periodic && a < p->dim ? DM_BOUNDARY_PERIODIC : DM_BOUNDARY_NONE;
  PetscCall(DMDACreate3d(comm, bt[0], bt[1], bt[2], DMDA_STENCIL_STAR, p->n[0], p->n[1], p->n[2],
                         PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE, 1, 1, NULL, NULL, NULL, &da));
  PetscCall(DMSetUp(da));
  PetscCall(DMSetApplicationContext(da, p));
  PetscCall(DMCreateGlobalVector(da, &x));
  PetscCall(SNESCreate(comm, &snes));
  PetscCall(SNESSetDM(snes, da));
  PetscCall(DMDASNESSetFunctionLocal(
      da, INSERT_VALUES,
      (PetscErrorCode(*)(DMDALocalInfo *, void *, void *, void *))darcy_residual_local, p));
  PetscCall(DMDASNESSetJacobianLocal(
      da, (PetscErrorCode(*)(DMDALocalInfo *, void *, Mat, Mat, void *))darcy_jacobian_local, p));
  st->linear = all_darcy(p);
  if (st->linear) {
    PetscCall(linear_solve(snes, x, p->rtol, st));
    PetscCall(residual_norm(snes, x, &st->residual));
  } else {
    /* initial guess: the problem with every law replaced by Darcy with its linearised permeability
     */
    long nb = darcy_nblocks(p);
    flow_law *nonlinear[3] = {p->laws, p->laws_axis[1], p->laws_axis[2]}, *lin[3] = {0};
    int oom = 0;
    for (int a = 0; a < 3; a++) {
      if (!nonlinear[a]) continue;
      lin[a] = malloc(nb * sizeof(flow_law));
      if (!lin[a]) {
        oom = 1;
        continue;
      }
      for (long b = 0; b < nb; b++)
        lin[a][b] = (flow_law){.kind = LAW_DARCY, .k = darcy_k_lin(p, b, a)};
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &oom, 1, MPI_INT, MPI_MAX, comm));
    if (oom)
      for (int a = 0; a < 3; a++) free(lin[a]);
    PetscCheck(!oom, comm, PETSC_ERR_MEM, "out of memory for the initial guess's %ld laws", nb);
    p->laws = lin[0];
    p->laws_axis[1] = lin[1];
    p->laws_axis[2] = lin[2];
    darcy_stats lst = {0};
    PetscCall(linear_solve(snes, x, 1e-8, &lst));
    p->laws = nonlinear[0];
    p->laws_axis[1] = nonlinear[1];
    p->laws_axis[2] = nonlinear[2];
    for (int a = 0; a < 3; a++) free(lin[a]);
    PetscCall(residual_norm(snes, x, &st->residual0));
    KSP ksp;
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPSetType(ksp, KSPCG));
    PetscCall(KSPSetTolerances(ksp, 1e-12, 1e-300, PETSC_DEFAULT, 10000));
    /* absolute floor: roundoff of the (pressure-unit) residual; the initial guess may already be
     * exact */
    PetscCall(SNESSetTolerances(snes, 1e-13 * p->p_scale, p->rtol, 1e-300, p->max_it, 100000));
    PetscCall(SNESSetOptionsPrefix(snes, "darcy_"));
    PetscCall(SNESSetFromOptions(snes));
    PetscCall(SNESSolve(snes, NULL, x));
    SNESConvergedReason why;
    PetscInt its, lits;
    PetscCall(SNESGetConvergedReason(snes, &why));
    PetscCall(SNESGetIterationNumber(snes, &its));
    PetscCall(SNESGetLinearSolveIterations(snes, &lits));
    st->converged = why > 0;
    st->newton_its = (int)its;
    st->linear_its = lst.linear_its + (int)lits;
    snprintf(st->reason, sizeof st->reason, "%s", SNESConvergedReasons[why]);
    PetscCall(residual_norm(snes, x, &st->residual));
  }
  PetscCall(gather(da, x, pressure));
  PetscCall(VecDestroy(&x));
  PetscCall(SNESDestroy(&snes));
  PetscCall(DMDestroy(&da));
  PetscFunctionReturn(0);
}

int darcy_solve(MPI_Comm comm, darcy_problem *p, double **pressure, darcy_stats *st) {
  return (int)solve(comm, p, pressure, st);
}
