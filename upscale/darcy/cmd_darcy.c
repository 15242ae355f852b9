/* `mdpore darcy CONFIG`: continuum single-phase flow over a grid of rock blocks, each with its own
 * law. */
#include <mpi.h>
#include <petscsys.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "common/cli_help.h"
#include "darcy_config.h"
#include "darcy_output.h"
#include "darcy_post.h"
#include "darcy_solve.h"
#include "darcy_units.h"
#include "darcy_upscale.h"
#include "twophase_impes.h"

static const cli_help_option_t darcy_options[] = {
    {"--upscale",
     "the effective permeability tensor of the grid instead, with fixed, linear and periodic "
     "boundary conditions (OPM upscale_perm's families; the config's `upscale:` key may pick "
     "some), in the config's permeability unit and, under SI, in mD",
     1},
    {"--quiet", "no summary or 'wrote' lines on stdout", 1},
    {NULL, NULL, 0}};

static const cli_help_page_t darcy_help = {
    .command = "darcy",
    .usage = "usage: mdpore darcy CONFIG.yaml [--upscale] [--quiet]\n"
             "       [PETSc options with prefix -darcy_, e.g. -darcy_snes_monitor]\n",
    .purpose = "Continuum Darcy/non-Darcy flow on a grid of rock blocks, each with its own law.",
    .about = "Solves steady single-phase flow on a 2D/3D grid of blocks (two-point flux finite "
             "volumes, one flow law per block; docs/darcy-config.md) and writes pressures, face "
             "fluxes, per-block pressure drops and gradients (HDF5) and a JSON summary with the "
             "effective permeability.\n"
             "A `twophase:` block in the config: water displacing oil over time instead (IMPES; "
             "CSV saturation profiles, water cut and recovery; docs/twophase-darcy.md).",
    .options = darcy_options,
    .more = "docs/darcy-config.md",
    .name_width = 10,
};

/* One family's tensor, rows i (flow) by columns j (driving gradient), in m^2 (or rc^2) and mD. */
static void print_tensor(const darcy_config *c, const darcy_upscale_result *r, int f) {
  const int d = r->dim;
  printf("  %s: %s\n    %s, %d solves, %d CG iterations, %.3g s, asymmetry %.2e\n",
         darcy_upscale_names[f], darcy_upscale_conditions(f),
         r->converged[f] ? "converged" : "NOT converged", d, r->linear_its[f], r->seconds[f],
         r->asymmetry[f]);
  for (int mD = 0; mD <= c->si; mD++)
    for (int i = 0; i < d; i++) {
      printf("    %-6s [", i ? "" : mD ? "mD" : darcy_unit_label(QTY_PERMEABILITY, c->si));
      for (int j = 0; j < d; j++) {
        if (r->defined[f][i][j])
          printf(" %13.6g", r->k[f][i][j] / (mD ? DARCY_MD_IN_M2 : 1.0));
        else
          printf(" %13s", "-");
      }
      printf(" ]\n");
    }
}

/* A `twophase:` config: water displacing oil to twophase.end_time (twophase_impes.h). */
static int run_twophase(const char *config, darcy_config *c, int quiet, int rank) {
  twophase_summary s;
  int rc = twophase_run(PETSC_COMM_WORLD, c, &s);
  if (rank == 0 && !rc && !quiet) {
    const twophase_config *tp = &c->twophase;
    printf("mdpore darcy: %s: %d x %d x %d blocks, two-phase IMPES to t = %g: %ld steps (CFL %g, "
           "max df_w/dS %.4g), %d CG iterations\n",
           config, c->problem.n[0], c->problem.n[1], c->problem.n[2], tp->t_end, s.steps, tp->cfl,
           s.max_dfw, s.linear_its);
    printf("  %.6g pore volumes injected, water cut %.6g, oil recovery %.6g", s.pv_injected,
           s.water_cut, s.oil_recovery);
    if (s.breakthrough_pvi >= 0.0)
      printf(", water breakthrough at %.6g pore volumes\n", s.breakthrough_pvi);
    else
      printf(", no water breakthrough yet\n");
    printf("  oil balance relative error %.2e\n", s.oil_balance_rel);
    if (tp->profiles_csv[0]) printf("  wrote %s\n", tp->profiles_csv);
    if (tp->history_csv[0]) printf("  wrote %s\n", tp->history_csv);
  }
  return rc;
}

/* --upscale: the tensor families, written and printed on rank 0. */
static int run_upscale(const char *config, darcy_config *c, int quiet, int rank, int size) {
  darcy_upscale_result r;
  if (darcy_upscale(PETSC_COMM_WORLD, &c->problem, c->upscale, &r)) return 1;
  int rc = 0;
  if (rank == 0) {
    if (c->hdf5_path[0] && darcy_write_upscale_hdf5(c->hdf5_path, c, &r)) rc = 1;
    if (c->json_path[0] && darcy_write_upscale_json(c->json_path, config, c, &r, size)) rc = 1;
    if (!quiet) {
      printf("mdpore darcy --upscale: %s: %d x %d x %d blocks, permeability tensor K[i][j] (row "
             "i: flow, column j: driving gradient)\n",
             config, c->problem.n[0], c->problem.n[1], c->problem.n[2]);
      for (int f = 0; f < UPSCALE_COUNT; f++)
        if (r.done[f]) print_tensor(c, &r, f);
      if (c->hdf5_path[0]) printf("  wrote %s\n", c->hdf5_path);
      if (c->json_path[0]) printf("  wrote %s\n", c->json_path);
    }
    for (int f = 0; f < UPSCALE_COUNT; f++)
      if (r.done[f] && !r.converged[f]) {
        fprintf(stderr, "mdpore darcy: the %s-conditions solve did not converge (%s)\n",
                darcy_upscale_names[f], r.reason[f]);
        rc = 1;
      }
  }
  return rc;
}

int cmd_darcy(int argc, char **argv) {
  int rank = 0, size = 1, quiet = 0, upscale = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const char *config = NULL;
  char **pargv = calloc(argc + 1, sizeof(char *));
  if (!pargv) {
    fprintf(stderr, "mdpore darcy: out of memory\n");
    return 1;
  }
  int pargc = 0;
  pargv[pargc++] = argv[0];
  for (int i = 1; i < argc; i++) {
    if (cli_help_flag(argv[i])) {
      if (rank == 0) cli_help_print(stdout, &darcy_help, cli_help_flag(argv[i]));
      free(pargv);
      return 0;
    }
    if (!strcmp(argv[i], "--quiet"))
      quiet = 1;
    else if (!strcmp(argv[i], "--upscale"))
      upscale = 1;
    else if (argv[i][0] == '-' && argv[i][1] != '-')
      pargv[pargc++] = argv[i];
    else if (argv[i][0] != '-' && !config)
      config = argv[i];
    else if (argv[i][0] != '-' && pargc > 1)
      pargv[pargc++] = argv[i]; /* a PETSc option's value */
    else {
      if (rank == 0) {
        fprintf(stderr, "mdpore darcy: unexpected argument '%s'\n", argv[i]);
        cli_help_print(stderr, &darcy_help, CLI_HELP_SHORT);
      }
      free(pargv);
      return 2;
    }
  }
  if (!config) {
    if (rank == 0) {
      fprintf(stderr, "mdpore darcy: no CONFIG given\n");
      cli_help_print(stderr, &darcy_help, CLI_HELP_SHORT);
    }
    free(pargv);
    return 2;
  }
  darcy_config c;
  /* every rank reads it (small); 0 reports */
  int rc = upscale ? darcy_config_read_upscale(config, &c, rank != 0)
                   : darcy_config_read(config, &c, rank != 0);
  if (rc) {
    free(pargv);
    return 1;
  }
  if (PetscInitialize(&pargc, &pargv, NULL, NULL)) {
    free(pargv);
    return 1;
  }
  if (c.upscale || c.twophase.enabled) {
    rc = c.upscale ? run_upscale(config, &c, quiet, rank, size)
                   : run_twophase(config, &c, quiet, rank);
    MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
    darcy_problem_free(&c.problem);
    twophase_config_free(&c.twophase);
    PetscFinalize();
    free(pargv);
    return rc;
  }
  double *pressure = NULL;
  darcy_stats st;
  rc = darcy_solve(PETSC_COMM_WORLD, &c.problem, &pressure, &st) ? 1 : 0;
  darcy_post post;
  if (!rc && rank == 0 && (!pressure || darcy_post_compute(&c.problem, pressure, &post))) {
    fprintf(stderr, "mdpore darcy: %s: out of memory for the pressure field of %ld blocks\n",
            config, darcy_nblocks(&c.problem));
    rc = 1;
  }
  if (!rc && rank == 0) {
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
        if (post.keff_defined[a]) {
          const char *ku = darcy_unit_label(QTY_PERMEABILITY, c.si);
          const char *ru = darcy_unit_label(c.problem.dim == 3 ? QTY_RATE : QTY_RATE_2D, c.si);
          printf("  effective permeability along %c: %.6g %s", "xyz"[a], post.keff[a], ku);
          if (c.si) printf(" (%.6g mD)", post.keff[a] / DARCY_MD_IN_M2);
          printf(" (inflow %.6g %s, outflow %.6g %s)\n", post.q_in[a], ru, post.q_out[a], ru);
        }
      printf("  mass balance relative error %.2e; pressure in [%.6g, %.6g] %s\n",
             post.mass_balance_rel, post.pmin, post.pmax, darcy_unit_label(QTY_PRESSURE, c.si));
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
