/* The permeability tensor of darcy_upscale.h, three boundary-condition families:
 *  - layers along z (and, with 2 blocks, along x): fixed and periodic diagonals are the arithmetic
 *    (along the layers) and harmonic (across) means exactly; linear conditions give the arithmetic
 *    mean along the layers exactly (the uniform gradient is the solution there);
 *  - a random field: the periodic tensor is symmetric; swapping the x and y axes of the field
 *    (and of the grid) swaps the rows and columns of every family's tensor;
 *  - a uniform 2D medium: K = k I for every family.
 * Run on 1 rank, or under mpiexec -n 2 (the solves are then distributed). */
#include <math.h>
#include <petscsys.h>
#include <stdio.h>
#include <string.h>

#include "darcy_test_problem.h"
#include "darcy_upscale.h"
#include "synthetic_rng.h"

static int failures = 0, rank = 0;

static void check(const char *what, double got, double want, double tol) {
  double rel = fabs(got - want) / fabs(want);
  if (rank == 0)
    printf("%-58s got %.12g want %.12g rel %.2e %s\n", what, got, want, rel,
           rel <= tol ? "ok" : "FAIL");
  if (!(rel <= tol)) failures++;
}

static void check_small(const char *what, double got, double bound) {
  if (rank == 0)
    printf("%-58s got %.3e bound %.1e %s\n", what, got, bound, fabs(got) <= bound ? "ok" : "FAIL");
  if (!(fabs(got) <= bound)) failures++;
}

static void upscale(darcy_problem *p, darcy_upscale_result *r) {
  const int all = (1 << UPSCALE_COUNT) - 1;
  char why[256];
  darcy_problem_linearise(p, 1e-6);
  if (darcy_upscale_check(p, all, why, sizeof why)) {
    if (rank == 0) printf("upscale check refused a valid problem: %s\n", why);
    failures++;
  }
  if (darcy_upscale(PETSC_COMM_WORLD, p, all, r)) failures++;
  for (int f = 0; f < UPSCALE_COUNT; f++)
    if (!r->done[f] || !r->converged[f]) {
      if (rank == 0) printf("family %s not solved or not converged\n", darcy_upscale_names[f]);
      failures++;
    }
}

/* layers of permeability kl[] along `axis` (one block per layer) */
static void layered(int nx, int ny, int nz, int axis, const double *kl, double *arith,
                    double *harm) {
  darcy_problem p = test_problem(3, nx, ny, nz, 0.3 * nx, 0.2 * ny, 0.1 * nz, 1.0);
  int n[3] = {nx, ny, nz};
  *arith = *harm = 0.0;
  for (int l = 0; l < n[axis]; l++) {
    *arith += kl[l] / n[axis];
    *harm += 1.0 / kl[l] / n[axis];
  }
  *harm = 1.0 / *harm;
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++) {
        int c[3] = {i, j, k};
        p.laws[darcy_index(&p, i, j, k)].k = kl[c[axis]];
      }
  darcy_upscale_result r;
  upscale(&p, &r);
  char name[96];
  for (int f = 0; f < UPSCALE_COUNT; f++)
    for (int a = 0; a < 3; a++) {
      if (f == UPSCALE_LINEAR && a == axis) continue; /* not a mean across layers */
      snprintf(name, sizeof name, "layers along %c, %s: K_%c%c = %s mean", "xyz"[axis],
               darcy_upscale_names[f], "xyz"[a], "xyz"[a], a == axis ? "harmonic" : "arithmetic");
      check(name, r.k[f][a][a], a == axis ? *harm : *arith, 1e-9);
    }
  darcy_problem_free(&p);
}

/* random lognormal field on nx x ny x nz; swap: the same field with x and y exchanged */
static void random_field(int swap, darcy_upscale_result *r) {
  const int n0[3] = {5, 7, 4};
  const double L0[3] = {1.0, 1.4, 0.6};
  int n[3] = {n0[0], n0[1], n0[2]};
  double L[3] = {L0[0], L0[1], L0[2]};
  if (swap) n[0] = n0[1], n[1] = n0[0], L[0] = L0[1], L[1] = L0[0];
  darcy_problem p = test_problem(3, n[0], n[1], n[2], L[0], L[1], L[2], 1.0);
  uint64_t seed = 2024;
  for (int k = 0; k < n0[2]; k++)
    for (int j = 0; j < n0[1]; j++)
      for (int i = 0; i < n0[0]; i++) {
        double v = 1e-15 * exp(1.5 * gaussian(&seed));
        long b = swap ? darcy_index(&p, j, i, k) : darcy_index(&p, i, j, k);
        p.laws[b].k = v;
      }
  upscale(&p, r);
  darcy_problem_free(&p);
}

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  const double kl[8] = {1e-15, 3e-17, 2e-16, 5e-14, 7e-16, 1e-16, 4e-15, 9e-17};
  double ar, hm;
  layered(6, 5, 8, 2, kl, &ar, &hm);
  layered(2, 3, 4, 0, kl + 2, &ar, &hm); /* periodic with 2 blocks along the layered axis */

  darcy_upscale_result a, b;
  random_field(0, &a);
  random_field(1, &b);
  check_small("random field, periodic tensor asymmetry", a.asymmetry[UPSCALE_PERIODIC], 1e-8);
  if (!(a.asymmetry[UPSCALE_LINEAR] > 1e-6)) { /* linear conditions: not symmetric in general */
    if (rank == 0) printf("random field, linear tensor unexpectedly symmetric: FAIL\n");
    failures++;
  }
  const int perm[3] = {1, 0, 2};
  double worst = 0.0;
  for (int f = 0; f < UPSCALE_COUNT; f++)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        if (a.defined[f][i][j] != b.defined[f][perm[i]][perm[j]]) failures++;
        if (!a.defined[f][i][j]) continue;
        worst = fmax(worst, fabs(a.k[f][i][j] - b.k[f][perm[i]][perm[j]]) / a.k[f][i][i]);
      }
  check_small("x <-> y swapped field: tensors swapped (max rel diff)", worst, 1e-8);
  if (rank == 0)
    printf("random field K_xx fixed / linear / periodic: %.6g / %.6g / %.6g\n",
           a.k[UPSCALE_FIXED][0][0], a.k[UPSCALE_LINEAR][0][0], a.k[UPSCALE_PERIODIC][0][0]);

  { /* uniform 2D medium: K = k I */
    darcy_problem p = test_problem(2, 7, 4, 1, 0.7, 0.3, 1.0, 3e-16);
    darcy_upscale_result r;
    upscale(&p, &r);
    for (int f = 0; f < UPSCALE_COUNT; f++) {
      char name[96];
      snprintf(name, sizeof name, "uniform 2D, %s: K_xx, K_yy = k", darcy_upscale_names[f]);
      check(name, 0.5 * (r.k[f][0][0] + r.k[f][1][1]), 3e-16, 1e-9);
      check_small(name, r.k[f][0][0] / r.k[f][1][1] - 1.0, 1e-9);
      if (f != UPSCALE_FIXED) {
        snprintf(name, sizeof name, "uniform 2D, %s: K_xy / k", darcy_upscale_names[f]);
        check_small(name, r.k[f][0][1] / 3e-16, 1e-9);
      }
    }
    darcy_problem_free(&p);
  }
  { /* refused: a non-Darcy block */
    darcy_problem p = test_problem(3, 3, 3, 3, 1, 1, 1, 1e-15);
    p.laws[13] = (flow_law){.kind = LAW_FORCHHEIMER, .k = 1e-15, .beta = 1e6};
    char why[256] = "";
    int refused = darcy_upscale_check(&p, 7, why, sizeof why) != 0 && strstr(why, "(1, 1, 1)");
    if (rank == 0) printf("non-Darcy block refused: %s (%s)\n", refused ? "ok" : "FAIL", why);
    failures += !refused;
    darcy_problem_free(&p);
  }
  PetscCall(PetscFinalize());
  if (rank == 0) printf("%s\n", failures ? "FAILED" : "all upscaling tensor checks passed");
  return failures ? 1 : 0;
}
