/* `mdpore darcy CONFIG`: continuum single-phase flow over a grid of rock blocks, each with its own
 * law. */
#include <mpi.h>
#include <petscsys.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "darcy_config.h"
#include "darcy_output.h"
#include "darcy_post.h"
#include "darcy_solve.h"

static const char *usage_text =
    "usage: mdpore darcy CONFIG.yaml [--quiet] [PETSc options with prefix -darcy_, e.g. "
    "-darcy_snes_monitor]\n"
    "Solves steady single-phase flow on a 2D/3D grid of blocks (two-point flux finite volumes, one "
    "flow\n"
    "law per block; docs/darcy-config.md) and writes pressures, face fluxes, per-block pressure "
    "drops\n"
    "and gradients (HDF5) and a JSON summary with the effective permeability.\n";

int cmd_darcy(int argc, char **argv) {
  int rank = 0, size = 1, quiet = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const char *config = NULL;
  char **pargv = calloc(argc + 1, sizeof(char *));
  int pargc = 0;
  pargv[pargc++] = argv[0];
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      if (rank == 0) fputs(usage_text, stdout);
      free(pargv);
      return 0;
    }
    if (!strcmp(argv[i], "--quiet"))
      quiet = 1;
    else if (argv[i][0] == '-' && argv[i][1] != '-')
      pargv[pargc++] = argv[i];
    else if (argv[i][0] != '-' && !config)
      config = argv[i];
    else if (argv[i][0] != '-' && pargc > 1)
      pargv[pargc++] = argv[i]; /* a PETSc option's value */
    else {
      if (rank == 0)
        fprintf(stderr, "mdpore darcy: unexpected argument '%s'\n%s", argv[i], usage_text);
      free(pargv);
      return 2;
    }
  }
  if (!config) {
    if (rank == 0) fprintf(stderr, "mdpore darcy: no CONFIG given\n%s", usage_text);
    free(pargv);
    return 2;
  }
  darcy_config c;
  int rc = darcy_config_read(config, &c, rank != 0); /* every rank reads it (small); 0 reports */
  if (rc) {
    free(pargv);
    return 1;
  }
  if (PetscInitialize(&pargc, &pargv, NULL, NULL)) {
    free(pargv);
    return 1;
  }
  double *pressure = NULL;
  darcy_stats st;
  rc = darcy_solve(PETSC_COMM_WORLD, &c.problem, &pressure, &st) ? 1 : 0;
  if (!rc && rank == 0) {
    darcy_post post;
    darcy_post_compute(&c.problem, pressure, &post);
    if (c.hdf5_path[0] && darcy_write_hdf5(c.hdf5_path, &c, pressure, &post)) rc = 1;
    if (c.json_path[0] && darcy_write_json(c.json_path, config, &c, pressure, &post, &st, size))
      rc = 1;
    if (!quiet) {
      printf("mdpore darcy: %s: %d x %d x %d blocks, %s, %s (%s, %d Newton / %d linear iterations, "
             "residual %.3g)\n",
             config, c.problem.n[0], c.problem.n[1], c.problem.n[2],
             st.linear ? "linear (KSP)" : "nonlinear (SNES)",
             st.converged ? "converged" : "NOT converged", st.reason, st.newton_its, st.linear_its,
             st.residual);
      for (int a = 0; a < c.problem.dim; a++)
        if (post.keff_defined[a])
          printf("  effective permeability along %c: %.6g (inflow %.6g, outflow %.6g)\n", "xyz"[a],
                 post.keff[a], post.q_in[a], post.q_out[a]);
      printf("  mass balance relative error %.2e; pressure in [%.6g, %.6g]\n",
             post.mass_balance_rel, post.pmin, post.pmax);
      if (c.hdf5_path[0]) printf("  wrote %s\n", c.hdf5_path);
      if (c.json_path[0]) printf("  wrote %s\n", c.json_path);
    }
    if (!st.converged) {
      fprintf(stderr, "mdpore darcy: the solver did not converge (%s)\n", st.reason);
      rc = 1;
    }
    darcy_post_free(&post);
  }
  free(pressure);
  MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
  darcy_problem_free(&c.problem);
  PetscFinalize();
  free(pargv);
  return rc;
}
