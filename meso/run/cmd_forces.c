/* mdpore forces SCENE [--dump FILE]: zero steps. Builds the scene's initial configuration,
 * evaluates densities and forces once and writes them as a LAMMPS-style dump (id type x y z vx vy
 * vz fx fy fz rho) for cross-checks with LAMMPS (pair mdpd + mdpd/rhosum, or pair dpd). */
#include "effects/scene_load.h"
#include "commands.h"
#include "common/cli_help.h"
#include "engine/sim.h"
#include "io/dump_lammps.h"
#include "populate/init_config.h"

#include <getopt.h>
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

static const cli_help_option_t forces_options[] = {
    {"--dump FILE", "the LAMMPS-style dump (default forces.lammpstrj)", 1},
    {"--backend B", "cpu, cuda or auto (default auto, as mdpore run)", 1},
    {NULL, NULL, 0}};

static const cli_help_page_t forces_help = {
    .command = "forces",
    .usage = "usage: mdpore forces SCENE.yaml [--dump FILE] [--backend cpu|cuda|auto]\n",
    .purpose = "Evaluate densities and forces on the initial configuration; write a LAMMPS dump.",
    .options = forces_options,
    .more = "docs/scene-format.md",
    .name_width = 12,
};

int cmd_forces(int argc, char **argv) {
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  static const struct option opts[] = {{"dump", required_argument, NULL, 'd'},
                                       {"backend", required_argument, NULL, 'b'},
                                       {"help", no_argument, NULL, 'h'},
                                       {"help-all", no_argument, NULL, 'H'},
                                       {NULL, 0, NULL, 0}};
  const char *backend = "auto";
  const char *dump = "forces.lammpstrj";
  int c;
  optind = 1;
  opterr = rank == 0;
  while ((c = getopt_long(argc, argv, "d:b:h", opts, NULL)) != -1) {
    if (c == 'd') {
      dump = optarg;
    } else if (c == 'b') {
      backend = optarg;
    } else {
      const int asked = c == 'h' ? CLI_HELP_SHORT : c == 'H' ? CLI_HELP_ALL : CLI_HELP_NONE;
      if (rank == 0)
        cli_help_print(asked ? stdout : stderr, &forces_help, asked ? asked : CLI_HELP_SHORT);
      return asked ? 0 : 2;
    }
  }
  if (optind != argc - 1) {
    if (rank == 0) cli_help_print(stderr, &forces_help, CLI_HELP_SHORT);
    return 2;
  }
  scene_t *scene = malloc(sizeof *scene);
  if (!scene || scene_load(argv[optind], scene)) {
    free(scene);
    return 1;
  }
  scene->restart_from[0] = 0;
  int nranks = 1;
  char err[512];
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  if (sim_backend_choose(backend, nranks, &scene->backend, err, sizeof err)) {
    if (rank == 0) fprintf(stderr, "mdpore forces: %s\n", err);
    free(scene);
    return 2;
  }
  sim_t *sim = sim_create(scene, MPI_COMM_WORLD);
  int rc = !sim || init_configuration(sim, scene) || sim_setup(sim);
  if (!rc) rc = dump_lammps_frame(dump, sim, 1) != 0;
  if (!rc) {
    thermo_t th;
    sim_thermo(sim, &th);
    particles_t *p = sim_particles(sim);
    double fmax = 0;
    for (int i = 0; i < p->n_local; i++) {
      const double f =
          sqrt(p->f[0][i] * p->f[0][i] + p->f[1][i] * p->f[1][i] + p->f[2][i] * p->f[2][i]);
      if (f > fmax) fmax = f;
    }
    MPI_Allreduce(MPI_IN_PLACE, &fmax, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    if (rank == 0)
      printf("%s: %ld particles, max |f| = %.6g, virial pressure p = %.6g; dump written to %s\n",
             scene->name, th.n_total, fmax, (th.pressure[0] + th.pressure[1] + th.pressure[2]) / 3,
             dump);
  }
  sim_destroy(sim);
  free(scene);
  return rc ? 1 : 0;
}
