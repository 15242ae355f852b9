/* Builds darcy_problem instances in code for the solver tests (the CLI builds them from YAML). */
#ifndef MDPORE_TESTS_DARCY_TEST_PROBLEM_H
#define MDPORE_TESTS_DARCY_TEST_PROBLEM_H

#include <stdlib.h>

#include "darcy_problem.h"

/* Uniform Darcy medium of permeability k, no-flow everywhere, n cells per axis over lengths L. */
static inline darcy_problem test_problem(int dim, int nx, int ny, int nz, double Lx, double Ly,
                                         double Lz, double k) {
  darcy_problem p = {0};
  p.dim = dim;
  p.n[0] = nx;
  p.n[1] = ny;
  p.n[2] = dim == 3 ? nz : 1;
  p.h[0] = Lx / nx;
  p.h[1] = Ly / ny;
  p.h[2] = dim == 3 ? Lz / nz : 1.0;
  p.fluid = (fluid_props){1.0e-3, 1000.0};
  long nb = darcy_nblocks(&p);
  p.laws = calloc(nb, sizeof(flow_law));
  p.k_lin = calloc(nb, sizeof(double));
  for (long b = 0; b < nb; b++) p.laws[b] = (flow_law){.kind = LAW_DARCY, .k = k};
  p.rtol = 1e-12;
  p.max_it = 50;
  return p;
}

static inline void test_fix_face(darcy_problem *p, int face, double value) {
  long n = darcy_face_count(p, face);
  p->fixed[face] = 1;
  p->bc_p[face] = malloc(n * sizeof(double));
  for (long c = 0; c < n; c++) p->bc_p[face][c] = value;
}

#endif
