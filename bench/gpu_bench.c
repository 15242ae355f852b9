/* GPU throughput benchmark (not a test): particle-steps per second, ns per
 * particle-step and device bytes per particle of the CUDA path.
 *   bulk K   : periodic mDPD fluid, rho = 6.2, cubic box of side K
 *   porous K : the paper's homogeneous porous medium (physics.md section 7), K x K quasi-2D cells
 *              Lx = Lz = 16, Ly = 2; a ring of frozen wall particles (radii 6..7, density 8),
 *              fluid at density 6.2 outside it; even rows of cells shifted by Lx/2; A = -40 for
 *              all pairs, B = 25, rd = 0.75, gamma = 4.5, g_z = 0.02 on the fluid, dt = 0.01.
 * usage: [mpiexec -n R] gpu_bench bulk|porous K [steps] [warmup] [cpu|cuda] [SKIN[,SKIN...]]
 *        [MEMORY[,MEMORY...]]
 * MEMORY: the CUDA path's memory modes to time in turn (auto, fast, compact; default auto), each on
 * a fresh system (docs/engine-cuda.md "Memory modes"). The line also gives the set-up time (filling
 * the host arrays, then sim_setup: upload, sort, first forces), the fluid-only rate and the
 * projected wall time of 3000 time units at this rate.
 * On R ranks (one GPU each) the box is R times longer along x and split along x: weak scaling.
 * SKIN: Verlet skins of the neighbour lists to time in turn (default: the backend's); each gets a
 * fresh system. After the timed steps, 100 more steps with a thermo sample every 10 give <T> and
 * <p>: a skin that missed a pair would show there (the skin changes no physics).
 * Particles start at random positions (fixed seed); the warm-up steps relax the overlaps.
 * MDPORE_BENCH_RNG=philox|philox2x32|fast: the generator of the pair random numbers
 * (dpd_thermostat's rng; default philox), printed as rng=... */
#include "common/mpi_singleton.h"
#include "bench_scene.h"
#include "effects/dpd_thermostat.h"
#include "effects/effect.h"
#include "engine/sim.h"
#include "engine/sim_balance.h"
#include "engine/sim_internal.h"
#include "physics/pair_random.h"
#ifdef MDPORE_HAVE_CUDA
#include "backend/cuda/cuda_backend.h"
#endif

#include <math.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng_state = 2024;
static double uniform(void) {
  return bench_uniform(&rng_state);
}

static void scene_base(scene_t *s, double lx, double ly, double lz, int n_species) {
  const double L[3] = {lx, ly, lz};
  bench_scene_mdpd(s, "gpu_bench", L, n_species);
  const char *rng = getenv("MDPORE_BENCH_RNG");
  for (int r = 0; rng && r < PAIR_RNG_COUNT; r++)
    if (!strcmp(rng, pair_rng_word(r)))
      SCENE_EFFECT_OPTIONS(s, EFFECT_DPD_THERMOSTAT, dpd_thermostat_options_t)->rng = r;
}

static long add(sim_t *sim, long id, int species, double x, double y, double z, const scene_t *s) {
  double pos[3] = {x, y, z}, v[3];
  for (int d = 0; d < 3; d++) {
    const double L = s->box_hi[d];
    pos[d] = fmod(pos[d], L);
    if (pos[d] < 0) pos[d] += L;
    v[d] = species == 0 ? sqrt(3.0) * (2.0 * uniform() - 1.0) : 0.0;
  }
  return sim_add_particle(sim, id, species, pos, v) < 0 ? -1 : id + 1;
}

static long fill_bulk(sim_t *sim, const scene_t *s) {
  const long n = lround(6.2 * s->box_hi[0] * s->box_hi[1] * s->box_hi[2]);
  long id = 0;
  for (long k = 0; k < n && id >= 0; k++)
    id = add(sim, id, 0, s->box_hi[0] * uniform(), s->box_hi[1] * uniform(),
             s->box_hi[2] * uniform(), s);
  return id;
}

/* One cell of the porous medium centred on its ring (cx, cz): wall particles in 6 <= r < 7 at
 * density 8, fluid at r >= 7 at density 6.2 within the 16 x 16 square around the centre. */
static long fill_porous(sim_t *sim, const scene_t *s, int kx, int k) {
  const double c = 16.0, ly = 2.0, pi = 3.14159265358979323846;
  const long n_wall = lround(8.0 * pi * (49.0 - 36.0) * ly);
  const long n_fluid = lround(6.2 * (c * c - pi * 49.0) * ly);
  long id = 0;
  for (int iz = 0; iz < k && id >= 0; iz++)
    for (int ix = 0; ix < kx && id >= 0; ix++) {
      const double cx = c * ix + c / 2 + (iz % 2 == 0 ? c / 2 : 0.0), cz = c * iz + c / 2;
      for (long w = 0; w < n_wall && id >= 0;) {
        const double dx = 14.0 * uniform() - 7.0, dz = 14.0 * uniform() - 7.0;
        const double r2 = dx * dx + dz * dz;
        if (r2 < 36.0 || r2 >= 49.0) continue;
        id = add(sim, id, 1, cx + dx, ly * uniform(), cz + dz, s);
        w++;
      }
      for (long f = 0; f < n_fluid && id >= 0;) {
        const double dx = c * uniform() - c / 2, dz = c * uniform() - c / 2;
        if (dx * dx + dz * dz < 49.0) continue;
        id = add(sim, id, 0, cx + dx, ly * uniform(), cz + dz, s);
        f++;
      }
    }
  return id;
}

/* Build, warm up and time one system; one line of results on rank 0. 0 or 1. */
static int run_one(scene_t *s, int porous, int k, int nranks, int grow, int rank, int steps,
                   int warm) {
  const double t_fill = MPI_Wtime();
  sim_t *sim = sim_create(s, MPI_COMM_WORLD);
  const long n = sim ? (porous ? fill_porous(sim, s, k * grow, k) : fill_bulk(sim, s)) : -1;
  const double t_setup = MPI_Wtime();
  if (n < 0 || sim_setup(sim)) return 1;
  const double fill_s = t_setup - t_fill, setup_s = MPI_Wtime() - t_setup;
  /* fluid share: the wall particles of the porous cells (fill_porous's counts) */
  const double c = 16.0, pi = 3.14159265358979323846;
  const double n_wall_cell = (double)lround(8.0 * pi * (49.0 - 36.0) * 2.0);
  const double n_fluid_cell = (double)lround(6.2 * (c * c - pi * 49.0) * 2.0);
  const double fluid_share = porous ? n_fluid_cell / (n_fluid_cell + n_wall_cell) : 1.0;
  for (int i = 0; i < warm; i++)
    if (sim_step(sim)) return 1;
  MPI_Barrier(MPI_COMM_WORLD);
  sim_phase_seconds_reset(sim);
#ifdef MDPORE_HAVE_CUDA
  cuda_sim_t *gpu_dev = cuda_backend_device(sim_state(sim), sim_backend_name(sim));
  double idle_ms[CUDA_IDLE_SECTIONS];
  long idle_n[CUDA_IDLE_SECTIONS];
  if (gpu_dev) cuda_idle_read(gpu_dev, idle_ms, idle_n, 1); /* the warm-up's: dropped */
#endif
  const double t0 = MPI_Wtime();
  for (int i = 0; i < steps; i++)
    if (sim_step(sim)) return 1;
  const double t = MPI_Wtime() - t0; /* each step ends with a device->host copy: synchronised */
  /* Where the step's host time goes, per phase (max over the ranks, ms per step): the GPU's
   * kernels run asynchronously, so their time shows in the phase where the host next waits. */
  double ph[PHASE_COUNT];
  MPI_Reduce(sim_phase_seconds(sim), ph, PHASE_COUNT, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
  if (rank == 0 && getenv("GPU_BENCH_PHASES")) {
    printf("phases (ms per step, max over %d rank(s)):", nranks);
    for (int k = 0; k < PHASE_COUNT; k++)
      if (ph[k] > 0) printf(" %s %.3f", step_phase_names[k], 1e3 * ph[k] / steps);
    printf("\n");
  }
#ifdef MDPORE_HAVE_CUDA
  /* MDPORE_CUDA_IDLE=1: device time between the probes' marks (cuda_backend.h), ms per step, max
   * over the ranks: the host's exchanges and waits as the GPU sees them */
  if (gpu_dev && getenv("MDPORE_CUDA_IDLE")) {
    cuda_idle_read(gpu_dev, idle_ms, idle_n, 1);
    double per[CUDA_IDLE_SECTIONS], per_max[CUDA_IDLE_SECTIONS];
    for (int k = 0; k < CUDA_IDLE_SECTIONS; k++)
      per[k] = idle_n[k] > 0 ? idle_ms[k] / (double)idle_n[k] : 0.0;
    MPI_Reduce(per, per_max, CUDA_IDLE_SECTIONS, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    if (rank == 0)
      printf(
          "gpu_idle (ms per step, max over %d rank(s)): migrate %.3f select %.3f step_end %.3f\n",
          nranks, per_max[CUDA_IDLE_MIGRATE], per_max[CUDA_IDLE_SELECT],
          per_max[CUDA_IDLE_STEP_END]);
  }
#endif
  long builds = 0, nsteps = 0;
  double skin = 0;
  const char *device = "cpu", *memory = "-";
  double bytes = 0;
#ifdef MDPORE_HAVE_CUDA
  cuda_sim_t *gpu = cuda_backend_device(sim_state(sim), sim_backend_name(sim));
  if (gpu) {
    device = cuda_sim_device_name(gpu);
    bytes = (double)cuda_sim_bytes(gpu) / (double)n;
    memory = cuda_sim_memory_mode(gpu);
    cuda_sim_list_stats(gpu, &builds, &nsteps, &skin);
  }
#endif
  /* Statistics after the timing: <T>, <p> over 10 samples of the next 100 steps. */
  double T = 0, p = 0;
  thermo_t th;
  for (int i = 1; i <= 100; i++) {
    sim_announce_thermo(sim, i % 10 == 0);
    if (sim_step(sim)) return 1;
    if (i % 10) continue;
    sim_thermo(sim, &th);
    T += th.temperature / 10;
    p += (th.pressure[0] + th.pressure[1] + th.pressure[2]) / 30;
  }
  const double mps = (double)n * steps / t;
  /* 3000 time units (the paper's flooding runs) at dt = s->dt */
  const double project_h = 3000.0 / s->dt * (double)n / mps / 3600.0;
  if (rank == 0)
    printf("case=%s scaling=%s K=%d ranks=%d particles=%ld steps=%d device=\"%s\" memory=%s rng=%s "
           "skin=%.2f list_builds_per_step=%.3f seconds=%.3f MPS=%.4g MPS_fluid=%.4g "
           "ns_per_particle_step=%.4g gpu_bytes_per_particle=%.1f fill_s=%.1f setup_s=%.1f "
           "hours_for_3000_tau=%.2f T=%.4f p=%.4f\n",
           porous ? "porous" : "bulk", grow == nranks ? "weak" : "strong", k, nranks, n, steps,
           device, memory,
           pair_rng_word(
               SCENE_EFFECT_OPTIONS(s, EFFECT_DPD_THERMOSTAT, dpd_thermostat_options_t)->rng),
           skin, nsteps > 0 ? (double)builds / (double)(nsteps + 1) : 1.0, t, mps / 1e6,
           mps * fluid_share / 1e6, 1e9 / mps, bytes * nranks, fill_s, setup_s, project_h, T, p);
  fflush(stdout);
  sim_destroy(sim);
  return 0;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  if (argc < 3) {
    fprintf(stderr, "usage: gpu_bench bulk|porous K [steps] [warmup] [cpu|cuda]\n");
    return 2;
  }
  const int porous = !strcmp(argv[1], "porous"), k = atoi(argv[2]);
  const int steps = argc > 3 ? atoi(argv[3]) : 100, warm = argc > 4 ? atoi(argv[4]) : 50;
  const char *backend = argc > 5 ? argv[5] : "cuda";
  int nranks = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  /* GPU_BENCH_STRONG=1: the same box on any number of ranks (strong scaling); else the box grows
   * with the ranks along x (weak scaling). */
  const int strong = getenv("GPU_BENCH_STRONG") && !strcmp(getenv("GPU_BENCH_STRONG"), "1");
  const int grow = strong ? 1 : nranks;
  scene_t *s = malloc(sizeof *s);
  if (porous) {
    scene_base(s, 16.0 * k * grow, 2.0, 16.0 * k, 2);
    s->procs[0] = nranks; /* split along x only */
    s->procs[1] = s->procs[2] = 1;
    effect_name_in_scene(s, EFFECT_BODY_FORCE);
    SCENE_EFFECT_OPTIONS(s, EFFECT_BODY_FORCE, body_force_params_t)->g[0][2] = 0.02;
  } else {
    scene_base(s, (double)k * grow, k, k, 1);
    s->procs[0] = nranks;
    s->procs[1] = s->procs[2] = 1;
  }
  char err[512];
  if (sim_backend_choose(backend, nranks, &s->backend, err, sizeof err)) {
    fprintf(stderr, "gpu_bench: %s\n", err);
    return 1;
  }
  char skins[256];
  snprintf(skins, sizeof skins, "%s", argc > 6 ? argv[6] : "-1");
  char modes[256];
  snprintf(modes, sizeof modes, "%s", argc > 7 ? argv[7] : "auto");
  char *save_mode = NULL;
  for (char *mode = strtok_r(modes, ",", &save_mode); mode;
       mode = strtok_r(NULL, ",", &save_mode)) {
    if (!strcmp(mode, "auto"))
      s->gpu_memory = SCENE_GPU_MEMORY_AUTO;
    else if (!strcmp(mode, "fast"))
      s->gpu_memory = SCENE_GPU_MEMORY_FAST;
    else if (!strcmp(mode, "compact"))
      s->gpu_memory = SCENE_GPU_MEMORY_COMPACT;
    else {
      fprintf(stderr, "gpu_bench: memory mode: expected auto, fast or compact (got '%s')\n", mode);
      return 2;
    }
    char skin_list[256];
    snprintf(skin_list, sizeof skin_list, "%s", skins);
    char *save_skin = NULL;
    for (char *tok = strtok_r(skin_list, ",", &save_skin); tok;
         tok = strtok_r(NULL, ",", &save_skin)) {
      s->neighbour_skin = atof(tok);
      if (run_one(s, porous, k, nranks, grow, rank, steps, warm)) return 1;
    }
  }
  free(s);
  MPI_Finalize();
  return 0;
}
