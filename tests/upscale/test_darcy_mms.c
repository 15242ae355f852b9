/* Manufactured solution: heterogeneous permeability k = exp(x + y/2) on the unit square (and cube),
 * pressure p = sin(2x) cos(y) + x (+ z^2/2 in 3D), source S = -div(k grad p)/mu put in each block
 * as S(centre) * volume, boundary pressures = p at the face centres. The two-point-flux scheme with
 * harmonic face permeabilities must converge at second order in the discrete L2 norm. */
#include <math.h>
#include <petscsys.h>
#include <stdio.h>

#include "darcy_solve.h"
#include "darcy_test_problem.h"

static double kfun(double x, double y) {
  return exp(x + 0.5 * y);
}
static double pfun(int dim, double x, double y, double z) {
  return sin(2 * x) * cos(y) + x + (dim == 3 ? 0.5 * z * z : 0.0);
}
/* S = -div(k grad p) with k_x = k, k_y = k/2, k_z = 0 (mu = 1) */
static double sfun(int dim, double x, double y) {
  double k = kfun(x, y);
  double px = 2 * cos(2 * x) * cos(y) + 1, pxx = -4 * sin(2 * x) * cos(y);
  double py = -sin(2 * x) * sin(y), pyy = -sin(2 * x) * cos(y), pzz = dim == 3 ? 1.0 : 0.0;
  return -(k * px + k * pxx + 0.5 * k * py + k * pyy + k * pzz);
}

static double l2_error(int dim, int n) {
  darcy_problem p = test_problem(dim, n, n, n, 1, 1, 1, 1.0);
  p.fluid.mu = 1.0;
  long nb = darcy_nblocks(&p);
  p.source = malloc(nb * sizeof(double));
  double vol = p.h[0] * p.h[1] * p.h[2];
  for (int k = 0; k < p.n[2]; k++)
    for (int j = 0; j < p.n[1]; j++)
      for (int i = 0; i < p.n[0]; i++) {
        double x = (i + 0.5) * p.h[0], y = (j + 0.5) * p.h[1];
        long b = darcy_index(&p, i, j, k);
        p.laws[b].k = kfun(x, y);
        p.source[b] = sfun(dim, x, y) * vol;
      }
  for (int f = 0; f < 2 * dim; f++) {
    p.fixed[f] = 1;
    p.bc_p[f] = malloc(darcy_face_count(&p, f) * sizeof(double));
    for (int k = 0; k < p.n[2]; k++)
      for (int j = 0; j < p.n[1]; j++)
        for (int i = 0; i < p.n[0]; i++) {
          int c[3] = {i, j, k}, axis = f / 2;
          if (c[axis] != (f % 2 ? p.n[axis] - 1 : 0)) continue;
          double xyz[3] = {(i + 0.5) * p.h[0], (j + 0.5) * p.h[1], (k + 0.5) * p.h[2]};
          xyz[axis] = f % 2 ? 1.0 : 0.0;
          p.bc_p[f][darcy_face_index(&p, f, i, j, k)] = pfun(dim, xyz[0], xyz[1], xyz[2]);
        }
  }
  darcy_problem_linearise(&p, 1e-6);
  double *pr = NULL, err = 0;
  darcy_stats st;
  if (darcy_solve(PETSC_COMM_SELF, &p, &pr, &st) || !st.converged) return NAN;
  for (int k = 0; k < p.n[2]; k++)
    for (int j = 0; j < p.n[1]; j++)
      for (int i = 0; i < p.n[0]; i++) {
        double e = pr[darcy_index(&p, i, j, k)] -
                   pfun(dim, (i + 0.5) * p.h[0], (j + 0.5) * p.h[1], (k + 0.5) * p.h[2]);
        err += e * e * vol;
      }
  free(pr);
  darcy_problem_free(&p);
  return sqrt(err);
}

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  int failed = 0;
  const int sizes[2][3] = {{16, 32, 64}, {8, 16, 32}};
  for (int dim = 2; dim <= 3; dim++) {
    double e[3];
    for (int r = 0; r < 3; r++) e[r] = l2_error(dim, sizes[dim - 2][r]);
    double o1 = log2(e[0] / e[1]), o2 = log2(e[1] / e[2]);
    printf(
        "%dD manufactured solution: L2 errors %.3e %.3e %.3e (n = %d, %d, %d), orders %.3f %.3f\n",
        dim, e[0], e[1], e[2], sizes[dim - 2][0], sizes[dim - 2][1], sizes[dim - 2][2], o1, o2);
    if (!(o2 > 1.9 && o2 < 2.2)) failed = 1;
  }
  PetscCall(PetscFinalize());
  printf("%s\n", failed ? "FAILED: not second order" : "second-order convergence");
  return failed;
}
