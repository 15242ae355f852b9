/* np = 1 vs np = N: a 3D heterogeneous nonlinear problem (Darcy, Forchheimer, power-law and
 * threshold blocks mixed, an injector) solved on all ranks of PETSC_COMM_WORLD and again on rank 0
 * alone must give the same pressures to within the solver tolerance. Run under mpiexec -n 2. */
#include <math.h>
#include <petscsys.h>
#include <stdio.h>

#include "darcy_solve.h"
#include "darcy_test_problem.h"
#include "synthetic_rng.h"

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  darcy_problem p = test_problem(3, 14, 9, 6, 1.4, 0.9, 0.6, 1.0);
  uint64_t seed = 42; /* identical on every rank */
  for (long b = 0; b < darcy_nblocks(&p); b++) {
    double k = 1e-15 * exp(2.0 * gaussian(&seed));
    switch (b % 4) {
    case 0:
      p.laws[b] = (flow_law){.kind = LAW_DARCY, .k = k};
      break;
    case 1:
      p.laws[b] = (flow_law){.kind = LAW_FORCHHEIMER, .k = k, .beta = 1e9};
      break;
    case 2:
      p.laws[b] = (flow_law){.kind = LAW_POWER, .K = k / 1e-3 * pow(1e6, -0.2), .n = 1.2};
      break;
    default:
      p.laws[b] = (flow_law){.kind = LAW_THRESHOLD, .k = k, .g0 = 2e5};
      break;
    }
  }
  test_fix_face(&p, FACE_XM, 2.0e6);
  test_fix_face(&p, FACE_XP, 1.0e6);
  p.source = calloc(darcy_nblocks(&p), sizeof(double));
  p.source[darcy_index(&p, 7, 4, 3)] = 1e-9;
  darcy_problem_linearise(&p, 1e-6);
  double *par = NULL, *ser = NULL;
  darcy_stats sp, ss = {0};
  int bad = darcy_solve(PETSC_COMM_WORLD, &p, &par, &sp) || !sp.converged;
  if (rank == 0) bad |= darcy_solve(PETSC_COMM_SELF, &p, &ser, &ss) || !ss.converged;
  int failed = bad;
  if (rank == 0 && !bad) {
    double maxdiff = 0;
    for (long b = 0; b < darcy_nblocks(&p); b++) maxdiff = fmax(maxdiff, fabs(par[b] - ser[b]));
    double rel = maxdiff / 1.0e6;
    printf("np=%d vs np=1: max |dp| = %.3e Pa (%.2e of the applied drop); Newton its %d vs %d\n",
           (int)size, maxdiff, rel, sp.newton_its, ss.newton_its);
    failed = !(rel < 1e-9) || size < 2;
    if (size < 2) printf("run this test with at least 2 ranks\n");
  }
  MPI_Bcast(&failed, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  free(par);
  free(ser);
  darcy_problem_free(&p);
  PetscCall(PetscFinalize());
  return failed;
}
