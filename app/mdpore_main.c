/* mdpore: command-line entry point. Dispatches to one subcommand. */
#include "common/mpi_singleton.h"
#include "commands.h"

#include <mpi.h>
#include <stdio.h>
#include <string.h>

typedef struct {
  const char *name;
  int (*fn)(int, char **);
  const char *summary;
} command_t;

static const command_t commands[] = {
    {"run", cmd_run, "run a scene (mDPD pore solver); --explain prints the step plan"},
    {"forces", cmd_forces, "evaluate forces and densities on a scene's initial configuration"},
    {"image", cmd_image, "segmented 3D images: info, convert, stack, drainage, make"},
    {"build", cmd_build, "build inputs: the wall patch database (build patches)"},
    {"foam", cmd_foam, "OpenFOAM Stokes-flow permeability of an image (cross-check)"},
    {"fit", cmd_fit, "fit Darcy and non-Darcy laws to a flow table (also: fit relperm)"},
    {"darcy", cmd_darcy, "continuum Darcy/non-Darcy solve on a grid of rock blocks"},
    {"permeability", cmd_permeability, "k of an image: a ladder of mdpore runs, flow table, fit"},
    {"relperm", cmd_relperm, "water/oil relative permeability: co-flow runs per saturation"},
    {"couple", cmd_couple, "pore-scale <-> continuum loop: campaigns per block, fitted laws"},
    {"slip", cmd_slip, "slip length from k at several pore sizes (also: fit slip)"},
};
static const int n_commands = (int)(sizeof commands / sizeof commands[0]);

/* The version and the options this binary was built with (defined in app/CMakeLists.txt). */
static void version(void) {
  printf("mdpore %s\n", MDPORE_VERSION);
  printf("  CUDA:      %s\n",
         MDPORE_BUILD_CUDA ? "yes (mdpore run uses a GPU when there is one)" : "no");
  printf("  PETSc:     %s\n",
         MDPORE_BUILD_PETSC ? "yes (darcy, couple)" : "no (darcy, couple absent)");
  printf("  TIFF:      %s\n", MDPORE_BUILD_TIFF ? "yes (TIFF images)" : "no (raw and HDF5 images)");
  printf("  precision: CPU double; GPU pair math %s\n", MDPORE_BUILD_DOUBLE ? "double" : "float");
}

/* The list of commands, within an 80 x 24 terminal (ctest cli_help_docs). */
static void usage(FILE *to) {
  fprintf(to, "usage: mdpore COMMAND [options]\n\ncommands:\n");
  for (int i = 0; i < n_commands; i++)
    fprintf(to, "  %-12s  %s\n", commands[i].name, commands[i].summary);
  fprintf(to, "\n'mdpore COMMAND --help' describes one command and its common options,\n"
              "'mdpore COMMAND --help-all' every option; 'mdpore --version' the build.\n"
              "More: docs/architecture.md lists the pages; README.md is the tour\n");
}

int main(int argc, char **argv) {
  /* `mdpore run --replicas` calls MPI from several threads (meso/run/run_replicas.c); every other
   * command from this one */
  int threads = MPI_THREAD_FUNNELED;
  for (int i = 2; i < argc && !strcmp(argv[1], "run"); i++)
    if (!strcmp(argv[i], "--replicas")) threads = MPI_THREAD_MULTIPLE;
  int provided = 0;
  mpi_singleton_prepare();
  MPI_Init_thread(&argc, &argv, threads, &provided);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int rc = 2;
  if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") ||
      !strcmp(argv[1], "--help-all")) {
    if (rank == 0) usage(argc < 2 ? stderr : stdout);
    rc = argc < 2 ? 2 : 0;
  } else if (!strcmp(argv[1], "--version")) {
    if (rank == 0) version();
    rc = 0;
  } else {
    const command_t *cmd = NULL;
    for (int i = 0; i < n_commands; i++)
      if (!strcmp(argv[1], commands[i].name)) cmd = &commands[i];
    if (argc > 2 && !strcmp(argv[1], "fit") && !strcmp(argv[2], "slip")) { /* = mdpore slip */
      argv++;
      argc--;
      for (int i = 0; i < n_commands; i++)
        if (!strcmp("slip", commands[i].name)) cmd = &commands[i];
    }
    if (!cmd) {
      if (rank == 0) {
        fprintf(stderr, "mdpore: unknown command '%s'\n", argv[1]);
        usage(stderr);
      }
    } else {
      rc = cmd->fn(argc - 1, argv + 1);
    }
  }
  MPI_Finalize();
  return rc;
}
