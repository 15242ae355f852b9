/* mdpore build patches [--edge E] [--density D] [--seed S] [--out FILE]: build (or find) the wall
 * patch database (populate/wall_patches.h) and print one line about it. */
#include "common/cli_help.h"
#include "populate/wall_patches.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int cmd_build(int argc, char **argv); /* the dispatcher declares it in app/commands.h */

static const cli_help_option_t patches_options[] = {
    {"--edge E",
     "patch edge = voxel edge, in rc (default 1; " CLI_HELP_STR(
         WALL_PATCHES_EDGE_MIN) " to " CLI_HELP_STR(WALL_PATCHES_EDGE_MAX) ")",
     1},
    {"--density D",
     "wall particles per rc^3 (default 8; > 0, <= " CLI_HELP_STR(WALL_PATCHES_DENSITY_MAX) ")", 1},
    {"--seed S", "seed of the equilibration run (default 1; an integer >= 0)", 1},
    {"--out FILE",
     "the HDF5 file (default: the cache, $MDPORE_CACHE_DIR, else $XDG_CACHE_HOME/mdpore, else "
     "~/.cache/mdpore)",
     1},
    {NULL, NULL, 0}};

static const cli_help_page_t patches_help = {
    .command = "build patches",
    .usage = "usage: mdpore build patches [--edge E] [--density D] [--seed S] [--out FILE]\n",
    .purpose = "Build the database of pre-equilibrated wall patches (docs/walls.md).",
    .about = "Cubes of edge E cut from an equilibrated mDPD liquid at density D, which the image "
             "wall builder copies into the solid voxels near the pore space. Reuses FILE when it "
             "exists.",
    .options = patches_options,
    .more = "docs/walls.md",
    .name_width = 11,
};

static int parse_double(const char *opt, const char *s, double lo, int lo_open, double hi,
                        double *v, int rank) {
  char *end;
  *v = strtod(s, &end);
  if (end == s || *end || !isfinite(*v) || (lo_open ? *v <= lo : *v < lo) || *v > hi) {
    if (rank == 0)
      fprintf(stderr, "mdpore build patches: %s: expected a number %s %g and <= %g (got '%s')\n",
              opt, lo_open ? ">" : ">=", lo, hi, s);
    return -1;
  }
  return 0;
}

static int cmd_patches(int argc, char **argv, int rank) {
  static const struct option opts[] = {{"edge", required_argument, NULL, 'e'},
                                       {"density", required_argument, NULL, 'd'},
                                       {"seed", required_argument, NULL, 's'},
                                       {"out", required_argument, NULL, 'o'},
                                       {"help", no_argument, NULL, 'h'},
                                       {"help-all", no_argument, NULL, 'H'},
                                       {NULL, 0, NULL, 0}};
  double edge = 1.0, density = 8.0;
  unsigned long long seed = 1;
  const char *out = "";
  int c;
  optind = 1;
  opterr = rank == 0;
  while ((c = getopt_long(argc, argv, "e:d:s:o:h", opts, NULL)) != -1) {
    switch (c) {
    case 'e':
      if (parse_double("--edge", optarg, WALL_PATCHES_EDGE_MIN, 0, WALL_PATCHES_EDGE_MAX, &edge,
                       rank))
        return 2;
      break;
    case 'd':
      if (parse_double("--density", optarg, 0.0, 1, WALL_PATCHES_DENSITY_MAX, &density, rank))
        return 2;
      break;
    case 's': {
      char *end;
      errno = 0;
      seed = strtoull(optarg, &end, 10);
      if (!optarg[0] || optarg[0] == '-' || optarg[0] == '+' || *end || errno == ERANGE) {
        if (rank == 0)
          fprintf(stderr,
                  "mdpore build patches: --seed: expected an integer 0 to 2^64 - 1 (got '%s')\n",
                  optarg);
        return 2;
      }
      break;
    }
    case 'o':
      if (!optarg[0]) {
        if (rank == 0) fprintf(stderr, "mdpore build patches: --out: expected a file name\n");
        return 2;
      }
      out = optarg;
      break;
    case 'h':
    case 'H':
      if (rank == 0)
        cli_help_print(stdout, &patches_help, c == 'H' ? CLI_HELP_ALL : CLI_HELP_SHORT);
      return 0;
    default:
      if (rank == 0) cli_help_print(stderr, &patches_help, CLI_HELP_SHORT);
      return 2;
    }
  }
  if (optind < argc) {
    if (rank == 0) {
      fprintf(stderr, "mdpore build patches: unexpected argument '%s'\n", argv[optind]);
      cli_help_print(stderr, &patches_help, CLI_HELP_SHORT);
    }
    return 2;
  }
  wall_patches_t db;
  wall_patches_run_t run;
  char err[1024];
  if (wall_patches_load_or_build_steps(out, edge, density, (uint64_t)seed, WALL_PATCHES_STEPS,
                                       MPI_COMM_WORLD, &db, &run, err, sizeof err)) {
    if (rank == 0) fprintf(stderr, "mdpore build patches: %s\n", err);
    return 1;
  }
  if (rank == 0) {
    char file[4096];
    if (out[0])
      snprintf(file, sizeof file, "%s", out);
    else
      wall_patches_cache_path(edge, density, (uint64_t)seed, file, sizeof file);
    long lo = -1, hi = 0;
    for (int p = 0; p < db.count; p++) {
      const long k = db.start[p + 1] - db.start[p];
      if (lo < 0 || k < lo) lo = k;
      if (k > hi) hi = k;
    }
    printf("%s%s: %d patches of edge %g, particles per patch %.3f mean (min %ld, max %ld; %g "
           "expected), final temperature %.4f (mean %.4f over the second half; %ld steps, %d "
           "run%s)\n",
           file, access(file, F_OK) == 0 ? "" : " (not written: in memory only)", db.count, db.edge,
           (double)db.start[db.count] / db.count, lo, hi, db.density * db.edge * db.edge * db.edge,
           run.temperature, run.temperature_mean, run.steps, run.runs, run.runs == 1 ? "" : "s");
  }
  wall_patches_free(&db);
  return 0;
}

int cmd_build(int argc, char **argv) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (argc < 2 || cli_help_flag(argv[1])) {
    if (rank == 0)
      cli_help_print(argc < 2 ? stderr : stdout, &patches_help,
                     argc < 2 ? CLI_HELP_SHORT : cli_help_flag(argv[1]));
    return argc < 2 ? 2 : 0;
  }
  if (!strcmp(argv[1], "patches")) return cmd_patches(argc - 1, argv + 1, rank);
  if (rank == 0) fprintf(stderr, "mdpore build: unknown subcommand '%s' (patches)\n", argv[1]);
  return 2;
}
