/* Exact layered-media and Forchheimer-column checks of the two-point-flux solver:
 *  - layers in series (across the flow): k_eff is the thickness-weighted harmonic mean, exactly;
 *  - layers in parallel (along the flow): k_eff is the thickness-weighted arithmetic mean, exactly;
 *  - 1D Forchheimer column, two materials in series: the flux q solves
 *      sum_i L_i (mu/k_i q + beta_i rho q^2) = dp   (analytic, solved here by bisection)
 *    and each block's pressure drop is its own share h (mu/k q + beta rho q^2);
 *  - a power-law column: q = K (dp/L)^n;
 *  - anisotropic layers (a diagonal law per block, k_x, k_y, k_z per layer), layers stacked along
 *    x: across them (flow along x) k_eff is the harmonic mean of the layers' k_x, along them (flow
 *    along y or z) the arithmetic mean of their k_y or k_z, exactly; with power laws along y
 *    (q = K_l G^n in layer l) the mean flux along y is sum_l t_l K_l G^n / L. */
#include <math.h>
#include <petscsys.h>
#include <stdio.h>

#include "darcy_post.h"
#include "darcy_solve.h"
#include "darcy_test_problem.h"

static int failures = 0;

static void check(const char *what, double got, double want, double tol) {
  double rel = fabs(got - want) / fabs(want);
  printf("%-48s got %.12g want %.12g rel %.2e %s\n", what, got, want, rel,
         rel <= tol ? "ok" : "FAIL");
  if (!(rel <= tol)) failures++;
}

static double solve_keff(darcy_problem *p, int axis, darcy_post *post) {
  double *pr = NULL;
  darcy_stats st;
  darcy_problem_linearise(p, 1e-6);
  if (darcy_solve(PETSC_COMM_SELF, p, &pr, &st) || !st.converged) {
    printf("solver failed (%s)\n", st.reason);
    failures++;
  }
  darcy_post_compute(p, pr, post);
  free(pr);
  return post->keff[axis];
}

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  const double k[4] = {1e-15, 3e-17, 2e-16, 5e-14}; /* four layers, 3 decades of contrast */
  const int cells[4] = {3, 5, 2, 6};                /* layer thicknesses in cells */
  darcy_post post;
  for (int dim = 2; dim <= 3; dim++) {
    /* series: layers stacked along x, flow along x */
    darcy_problem p = test_problem(dim, 16, 4, 3, 1.6, 0.4, 0.3, 1.0);
    double inv = 0, arith = 0;
    for (int l = 0, i0 = 0; l < 4; i0 += cells[l++]) {
      inv += cells[l] / 16.0 / k[l];
      arith += cells[l] / 16.0 * k[l];
      for (long b = 0; b < darcy_nblocks(&p); b++)
        if (b % 16 >= i0 && b % 16 < i0 + cells[l]) p.laws[b].k = k[l];
    }
    test_fix_face(&p, FACE_XM, 2.0e6);
    test_fix_face(&p, FACE_XP, 1.0e6);
    char name[64];
    snprintf(name, sizeof name, "%dD series k_eff = harmonic mean", dim);
    check(name, solve_keff(&p, 0, &post), 1.0 / inv, 1e-10);
    snprintf(name, sizeof name, "%dD series mass balance (|rel| < 1e-10)", dim);
    check(name, 1.0 + post.mass_balance_rel, 1.0, 1e-10);
    darcy_post_free(&post);
    /* parallel: the same layers, flow along y */
    for (int f = 0; f < 6; f++) {
      free(p.bc_p[f]);
      p.bc_p[f] = NULL;
      p.fixed[f] = 0;
    }
    test_fix_face(&p, FACE_YM, 2.0e6);
    test_fix_face(&p, FACE_YP, 1.0e6);
    snprintf(name, sizeof name, "%dD parallel k_eff = arithmetic mean", dim);
    check(name, solve_keff(&p, 1, &post), arith, 1e-10);
    darcy_post_free(&post);
    darcy_problem_free(&p);
  }
  { /* Forchheimer column: two materials in series, 1D along x (2D grid one cell high) */
    const int nx = 20;
    const double L = 0.2, dp = 5.0e5, kk[2] = {1e-12, 4e-13}, beta[2] = {2e7, 8e7};
    darcy_problem p = test_problem(2, nx, 1, 1, L, 0.01, 1, 1.0);
    for (int i = 0; i < nx; i++)
      p.laws[i] =
          (flow_law){.kind = LAW_FORCHHEIMER, .k = kk[i >= nx / 2], .beta = beta[i >= nx / 2]};
    test_fix_face(&p, FACE_XM, dp);
    test_fix_face(&p, FACE_XP, 0.0);
    double lo = 0, hi = dp * kk[0] / (p.fluid.mu * L) * 10; /* bisection on the analytic relation */
    for (int it = 0; it < 200; it++) {
      double q = 0.5 * (lo + hi), s = 0;
      for (int m = 0; m < 2; m++)
        s += 0.5 * L * (p.fluid.mu / kk[m] * q + beta[m] * p.fluid.rho * q * q);
      if (s > dp)
        hi = q;
      else
        lo = q;
    }
    double q = 0.5 * (lo + hi), A = p.h[1] * p.h[2];
    solve_keff(&p, 0, &post);
    check("Forchheimer column flux (analytic)", post.q_out[0] / A, q, 1e-9);
    double h = p.h[0], want0 = h * (p.fluid.mu / kk[0] * q + beta[0] * p.fluid.rho * q * q);
    double want1 = h * (p.fluid.mu / kk[1] * q + beta[1] * p.fluid.rho * q * q);
    check("Forchheimer block pressure drop, material 1", post.block_dp[3 * 2 + 0], want0, 1e-9);
    check("Forchheimer block pressure drop, material 2", post.block_dp[3 * (nx - 3) + 0], want1,
          1e-9);
    darcy_post_free(&post);
    darcy_problem_free(&p);
  }
  { /* power-law column: uniform gradient, q = K (dp/L)^n */
    darcy_problem p = test_problem(3, 12, 2, 2, 0.12, 0.02, 0.02, 1.0);
    for (long b = 0; b < darcy_nblocks(&p); b++)
      p.laws[b] = (flow_law){.kind = LAW_POWER, .K = 2e-12, .n = 1.3};
    test_fix_face(&p, FACE_XM, 3.0e5);
    test_fix_face(&p, FACE_XP, 1.0e5);
    solve_keff(&p, 0, &post);
    double A = 0.02 * 0.02, q = 2e-12 * pow(2.0e5 / 0.12, 1.3);
    check("power-law column flux q = K G^n", post.q_out[0] / A, q, 1e-9);
    darcy_post_free(&post);
    darcy_problem_free(&p);
  }
  { /* smoothed threshold column: uniform gradient G, q = (k/mu)[G - G0(1 - exp(-G/G0))] */
    darcy_problem p = test_problem(2, 10, 3, 1, 0.1, 0.03, 1, 1.0);
    for (long b = 0; b < darcy_nblocks(&p); b++)
      p.laws[b] = (flow_law){.kind = LAW_THRESHOLD, .k = 1e-15, .g0 = 4.0e5};
    test_fix_face(&p, FACE_XM, 1.0e5);
    test_fix_face(&p, FACE_XP, 0.0);
    solve_keff(&p, 0, &post);
    double G = 1.0e5 / 0.1, q = 1e-15 / 1e-3 * (G - 4.0e5 * (1 - exp(-G / 4.0e5)));
    check("threshold (Swartzendruber) column flux", post.q_out[0] / (0.03 * 1.0), q, 1e-9);
    darcy_post_free(&post);
    darcy_problem_free(&p);
  }
  { /* anisotropic layers: a diagonal law per block, layers stacked along x (cells[l] thick) */
    const double kd[4][3] = {
        {1e-15, 4e-15, 2e-16}, {3e-17, 1e-15, 6e-17}, {2e-16, 2e-16, 5e-15}, {5e-14, 7e-16, 1e-14}};
    const int order[3][2] = {{FACE_XM, FACE_XP}, {FACE_YM, FACE_YP}, {FACE_ZM, FACE_ZP}};
    double want[3] = {0, 0, 0}, scalar_along[3] = {0, 0, 0};
    for (int l = 0; l < 4; l++) {
      want[0] += cells[l] / 16.0 / kd[l][0];
      for (int a = 1; a < 3; a++) {
        want[a] += cells[l] / 16.0 * kd[l][a];
        scalar_along[a] += cells[l] / 16.0 * kd[l][0]; /* what one scalar law (k_x) would give */
      }
    }
    want[0] = 1.0 / want[0];
    for (int flow = 0; flow < 3; flow++) {
      darcy_problem p = test_problem(3, 16, 4, 3, 1.6, 0.4, 0.3, 1.0);
      if (darcy_problem_make_diagonal(&p)) failures++;
      for (long b = 0; b < darcy_nblocks(&p); b++)
        for (int l = 0, i0 = 0; l < 4; i0 += cells[l++])
          if (b % 16 >= i0 && b % 16 < i0 + cells[l]) {
            p.laws[b].k = kd[l][0];
            p.laws_axis[1][b].k = kd[l][1];
            p.laws_axis[2][b].k = kd[l][2];
          }
      test_fix_face(&p, order[flow][0], 2.0e6);
      test_fix_face(&p, order[flow][1], 1.0e6);
      char name[80];
      snprintf(name, sizeof name, "diagonal layers, flow along %c: %s mean of k_%c", 'x' + flow,
               flow ? "arithmetic" : "harmonic", 'x' + flow);
      const double got = solve_keff(&p, flow, &post);
      check(name, got, want[flow], 1e-10);
      if (flow) { /* the diagonal is what the answer reads: one scalar k_x law would be far off */
        const double off = fabs(got / scalar_along[flow] - 1);
        printf("  scalar k_x law would give %.6g (%.0f%% off)%s\n", scalar_along[flow], 100 * off,
               off > 0.5 ? "" : " FAIL: the test does not tell the diagonal from the scalar law");
        if (!(off > 0.5)) failures++;
      }
      darcy_post_free(&post);
      darcy_problem_free(&p);
    }
    /* power laws along y only (Darcy along x and z): the nonlinear solve with a diagonal law */
    darcy_problem p = test_problem(3, 16, 4, 3, 1.6, 0.4, 0.3, 1.0);
    if (darcy_problem_make_diagonal(&p)) failures++;
    const double Kl[4] = {2e-12, 5e-13, 8e-12, 1e-12}, n = 1.3, G = 1.0e6 / 0.4;
    double q_mean = 0;
    for (int l = 0; l < 4; l++) q_mean += cells[l] / 16.0 * Kl[l] * pow(G, n);
    for (long b = 0; b < darcy_nblocks(&p); b++)
      for (int l = 0, i0 = 0; l < 4; i0 += cells[l++])
        if (b % 16 >= i0 && b % 16 < i0 + cells[l]) {
          p.laws[b].k = kd[l][0];
          p.laws_axis[1][b] = (flow_law){.kind = LAW_POWER, .K = Kl[l], .n = n};
          p.laws_axis[2][b].k = kd[l][2];
        }
    test_fix_face(&p, FACE_YM, 2.0e6);
    test_fix_face(&p, FACE_YP, 1.0e6);
    solve_keff(&p, 1, &post);
    check("diagonal layers, power laws along y: mean flux", post.q_out[1] / (1.6 * 0.3), q_mean,
          1e-8);
    darcy_post_free(&post);
    darcy_problem_free(&p);
  }
  PetscCall(PetscFinalize());
  printf("%s\n", failures ? "FAILED" : "all layered/column checks passed");
  return failures ? 1 : 0;
}
