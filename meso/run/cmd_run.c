/* mdpore run [--explain] [--steps N] [--output-dir D] [--restart FILE] SCENE
 * mdpore run --replicas [--steps N] [--backend B] ... SCENE [SCENE...] (run/run_replicas.c) */
#include "effects/scene_load.h"
#include "commands.h"
#include "engine/sim.h"
#include "common/atomic_file.h"
#include "common/cli_help.h"
#include "run/run_loop.h"
#include "run/run_replicas.h"

#include <getopt.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const cli_help_option_t run_options[] = {
    {"--replicas",
     "run each SCENE as its own one-rank run, all at once in this process (one thread each, "
     "sharing the GPU or the cores); each writes its outputs into its scene's folder, as "
     "--output-dir DIR DIR/scene.yaml would; one that fails leaves the others running (exit 1 "
     "naming it)",
     0},
    {"--explain", "print the per-step plan the scene's effects produce, and exit", 1},
    {"--steps N", "run N steps instead of run.steps (after a restart: N more steps)", 1},
    {"--output-dir DIR", "write the outputs (relative paths) into DIR (created if needed)", 1},
    {"--restart FILE", "continue from a checkpoint (overrides the scene's 'restart')", 1},
    {"--backend B",
     "cpu, cuda or auto (default: cuda when every rank sees a GPU; one GPU per rank)", 1},
    {"--skin S",
     "Verlet skin of the CUDA path's neighbour lists on one GPU, in rc units (default 0: rebuilt "
     "every step, the fastest at dt = 0.01; the physics is the same)",
     0},
    {"--gpu-memory M",
     "auto, fast or compact: the CUDA path with per-step neighbour lists (fast, ~790 bytes per "
     "particle) or without (compact, <= 200 bytes per particle, slower; the same forces). auto "
     "(default): compact only when the fast mode would not fit in the GPU's memory",
     0},
    {NULL, NULL, 0}};

static const cli_help_page_t run_help = {
    .command = "run",
    .usage = "usage: mdpore run [--explain] [--steps N] [--output-dir DIR] [--restart FILE]\n"
             "                  SCENE.yaml\n"
             "       mdpore run --replicas [--steps N] [--backend B] SCENE.yaml...\n",
    .purpose = "Run a scene (format: docs/scene-format.md) on all MPI ranks.",
    .options = run_options,
    .more = "docs/scene-format.md, docs/engine-core.md, docs/engine-cuda.md",
    .name_width = 16,
};

/* --replicas: load every scene first (a scene that does not load stops the command before any
 * runs), then run them at once. */
static int run_replica_scenes(int n, char **files, long steps, double skin, int gpu_memory,
                              const char *backend, int single_only, int size) {
  if (single_only) {
    fprintf(stderr, "mdpore run: --replicas: --explain, --output-dir and --restart are for one "
                    "scene (a replica writes into its scene's folder; set restart in its scene)\n");
    return 2;
  }
  if (n < 1) {
    cli_help_print(stderr, &run_help, CLI_HELP_SHORT);
    return 2;
  }
  int provided = MPI_THREAD_SINGLE;
  MPI_Query_thread(&provided);
  if (size > 1) {
    fprintf(stderr,
            "mdpore run: --replicas: each replica runs on one rank in this process: start "
            "it without mpiexec (got %d ranks)\n",
            size);
    return 2;
  }
  if (provided < MPI_THREAD_MULTIPLE) {
    fprintf(stderr,
            "mdpore run: --replicas: this MPI gave thread level %d, MPI_THREAD_MULTIPLE (%d) is "
            "needed (spell --replicas in full: mdpore asks for it when it sees that word)\n",
            provided, MPI_THREAD_MULTIPLE);
    return 2;
  }
  scene_t *scenes = calloc((size_t)n, sizeof *scenes);
  if (!scenes) {
    fprintf(stderr, "mdpore run: out of memory for %d scenes\n", n);
    return 1;
  }
  int chosen = SCENE_BACKEND_CPU;
  char err[512];
  if (sim_backend_choose(backend, 1, &chosen, err, sizeof err)) {
    fprintf(stderr, "mdpore run: %s\n", err);
    free(scenes);
    return 2;
  }
  for (int i = 0; i < n; i++) {
    if (scene_load(files[i], &scenes[i])) {
      fprintf(stderr, "mdpore run: --replicas: %s (replica %d of %d) did not load; nothing ran\n",
              files[i], i + 1, n);
      free(scenes);
      return 1;
    }
    if (steps >= 0) scenes[i].steps = steps;
    if (skin >= 0.0) scenes[i].neighbour_skin = skin;
    scenes[i].gpu_memory = gpu_memory;
    scenes[i].backend = chosen;
  }
  int rc = run_replicas_prepare(scenes, n) ? 2 : 0;
  if (!rc) rc = run_replicas(scenes, n, run_replicas_omp_threads(n));
  free(scenes);
  return rc;
}

int cmd_run(int argc, char **argv) {
  int rank, size;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  static const struct option opts[] = {{"explain", no_argument, NULL, 'e'},
                                       {"steps", required_argument, NULL, 's'},
                                       {"output-dir", required_argument, NULL, 'o'},
                                       {"restart", required_argument, NULL, 'r'},
                                       {"backend", required_argument, NULL, 'b'},
                                       {"skin", required_argument, NULL, 'k'},
                                       {"gpu-memory", required_argument, NULL, 'm'},
                                       {"replicas", no_argument, NULL, 'R'},
                                       {"help", no_argument, NULL, 'h'},
                                       {"help-all", no_argument, NULL, 'H'},
                                       {NULL, 0, NULL, 0}};
  int explain = 0, replicas = 0, c;
  long steps = -1;
  const char *outdir = NULL, *restart = NULL, *backend = "auto";
  double skin = -1.0;
  int gpu_memory = SCENE_GPU_MEMORY_AUTO;
  optind = 1;
  opterr = rank == 0;
  while ((c = getopt_long(argc, argv, "es:o:r:b:k:m:Rh", opts, NULL)) != -1) {
    switch (c) {
    case 'e':
      explain = 1;
      break;
    case 's': {
      char *end;
      steps = strtol(optarg, &end, 10);
      if (*end || steps < 0) {
        if (rank == 0)
          fprintf(stderr, "mdpore run: --steps: expected an integer >= 0 (got '%s')\n", optarg);
        return 2;
      }
      break;
    }
    case 'o':
      outdir = optarg;
      break;
    case 'r':
      restart = optarg;
      break;
    case 'b':
      backend = optarg;
      break;
    case 'k': {
      char *end;
      skin = strtod(optarg, &end);
      if (*end || !(skin >= 0.0 && skin <= 2.0)) {
        if (rank == 0)
          fprintf(stderr, "mdpore run: --skin: expected a number in [0, 2] (rc units; got '%s')\n",
                  optarg);
        return 2;
      }
      break;
    }
    case 'm':
      if (!strcmp(optarg, "auto"))
        gpu_memory = SCENE_GPU_MEMORY_AUTO;
      else if (!strcmp(optarg, "fast"))
        gpu_memory = SCENE_GPU_MEMORY_FAST;
      else if (!strcmp(optarg, "compact"))
        gpu_memory = SCENE_GPU_MEMORY_COMPACT;
      else {
        if (rank == 0)
          fprintf(stderr, "mdpore run: --gpu-memory: expected auto, fast or compact (got '%s')\n",
                  optarg);
        return 2;
      }
      break;
    case 'R':
      replicas = 1;
      break;
    case 'h':
    case 'H':
      if (rank == 0) cli_help_print(stdout, &run_help, c == 'H' ? CLI_HELP_ALL : CLI_HELP_SHORT);
      return 0;
    default:
      if (rank == 0) cli_help_print(stderr, &run_help, CLI_HELP_SHORT);
      return 2;
    }
  }
  if (replicas)
    return run_replica_scenes(argc - optind, argv + optind, steps, skin, gpu_memory, backend,
                              explain || outdir || restart, size);
  if (optind != argc - 1) {
    if (rank == 0) cli_help_print(stderr, &run_help, CLI_HELP_SHORT);
    return 2;
  }
  scene_t *scene = malloc(sizeof *scene);
  if (!scene || scene_load(argv[optind], scene)) {
    free(scene);
    return 1;
  }
  if (steps >= 0) scene->steps = steps;
  if (skin >= 0.0) scene->neighbour_skin = skin;
  scene->gpu_memory = gpu_memory;
  char err[512];
  if (sim_backend_choose(backend, size, &scene->backend, err, sizeof err)) {
    if (rank == 0) fprintf(stderr, "mdpore run: %s\n", err);
    free(scene);
    return 2;
  }
  if (restart) snprintf(scene->restart_from, sizeof scene->restart_from, "%s", restart);
  int rc = 0;
  if (explain) {
    if (rank == 0) sim_explain(scene, size, stdout);
  } else {
    if (outdir) {
      int bad = rank == 0 ? make_dirs(outdir) : 0;
      MPI_Bcast(&bad, 1, MPI_INT, 0, MPI_COMM_WORLD);
      if (bad) {
        free(scene);
        return 1;
      }
      run_apply_output_dir(scene, outdir);
    }
    rc = run_scene(scene, MPI_COMM_WORLD);
  }
  free(scene);
  return rc;
}
