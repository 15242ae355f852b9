/* How many runs of a campaign execute at once (--jobs; campaign_exec.c runs them).
 *
 * --jobs N is taken as given (default 1: the runs one after another, as before the option). --jobs
 * auto chooses from the machine:
 *  - a build with CUDA and a visible GPU: the runs share the GPU (every run's rank 0 is on GPU 0:
 *    meso/backend/cuda/cuda_create.cu picks the device by local rank), so as many as fit in GPU 0's
 *    free memory, each taking its particles (the campaign's particles_estimate, its largest run) at
 *    the fast mode's ~791 bytes per particle (bench/RESULTS.md) with a quarter for the ghost layer
 *    and growth, plus a CUDA context per process; at most CAMP_AUTO_JOBS_MAX (bench/RESULTS.md,
 *    2026-11-29: 8-10 runs at once fill an H200 with runs of 0.25-3.4 M particles, so more only
 *    queue on it). A scene input has no estimate: 1.
 *  - otherwise (CPU): floor(cores / np), the cores this process may run on (its affinity mask).
 * The GPU is asked in a child process that exits at once, so this process holds no CUDA context
 * (hundreds of MB of the device's memory) while its runs execute. */
#define _GNU_SOURCE
#include <math.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#ifdef MDPORE_HAVE_CUDA
#include <cuda_runtime_api.h>
#endif

#include "campaign.h"

/* The fast memory mode's bytes per particle (meso/backend/cuda/cuda_util.cu, measured 791 on the
 * porous benchmark), a quarter more for the ghost layer and the slots' margin, and the memory a
 * CUDA context takes (about 0.5 GB on Hopper; rounded up). */
#define GPU_BYTES_PER_PARTICLE (791.0 * 1.25)
#define GPU_CONTEXT_BYTES 0.6e9
/* Of the free memory, what the runs may plan on (the rest: the runs' growth and others' use). */
#define GPU_FREE_FRACTION 0.9

int camp_jobs_auto_gpu(double free_bytes, int gpus, double particles, int np) {
  if (gpus < 1 || !(particles > 0) || !(free_bytes > 0)) return 1;
  const int ranks_on_gpu0 = (np + gpus - 1) / gpus; /* ranks take the GPUs in turn */
  const double per_run =
      ranks_on_gpu0 * (particles / np * GPU_BYTES_PER_PARTICLE + GPU_CONTEXT_BYTES);
  const double n = floor(GPU_FREE_FRACTION * free_bytes / per_run);
  return n < 1 ? 1 : n > CAMP_AUTO_JOBS_MAX ? CAMP_AUTO_JOBS_MAX : (int)n;
}

int camp_jobs_auto_cpu(int cores, int np) {
  const int n = np > 0 ? cores / np : 1;
  return n < 1 ? 1 : n > CAMP_MAX_JOBS ? CAMP_MAX_JOBS : n;
}

static int cores_here(void) {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return CPU_COUNT(&set);
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? (int)n : 1;
}

/* Visible GPUs and GPU 0's free and total memory, asked in a child. 0 when none (or no CUDA). */
static int probe_gpu(double *free_bytes, double *total_bytes) {
  *free_bytes = *total_bytes = 0;
#ifdef MDPORE_HAVE_CUDA
  int fd[2];
  if (pipe(fd)) return 0;
  fflush(NULL);
  const pid_t pid = fork();
  if (pid < 0) {
    close(fd[0]);
    close(fd[1]);
    return 0;
  }
  if (pid == 0) {
    close(fd[0]);
    double msg[3] = {0, 0, 0};
    int n = 0;
    size_t f = 0, t = 0;
    if (cudaGetDeviceCount(&n) == cudaSuccess && n > 0 && cudaSetDevice(0) == cudaSuccess &&
        cudaMemGetInfo(&f, &t) == cudaSuccess) {
      msg[0] = n;
      msg[1] = (double)f;
      msg[2] = (double)t;
    }
    _exit(write(fd[1], msg, sizeof msg) == (ssize_t)sizeof msg ? 0 : 1);
  }
  close(fd[1]);
  double msg[3] = {0, 0, 0};
  const ssize_t got = read(fd[0], msg, sizeof msg);
  close(fd[0]);
  while (waitpid(pid, NULL, 0) < 0) {
  }
  if (got != (ssize_t)sizeof msg) return 0;
  *free_bytes = msg[1];
  *total_bytes = msg[2];
  return (int)msg[0];
#else
  return 0;
#endif
}

int camp_jobs(const camp_opts *o, const campaign *c, int *on_gpu) {
  double free_b, total_b;
  *on_gpu = 0;
  if (o->jobs > 0) {
    const int n = o->jobs > CAMP_MAX_JOBS ? CAMP_MAX_JOBS : o->jobs;
    /* --job-mode auto needs to know whether the runs at once share a GPU */
    if (n > 1 && o->job_replicas < 0) *on_gpu = probe_gpu(&free_b, &total_b) > 0;
    if (n > 1)
      fprintf(stderr, "mdpore permeability: up to %d runs at once (--jobs %d)\n", n, o->jobs);
    return n;
  }
  const int gpus = probe_gpu(&free_b, &total_b);
  int n;
  *on_gpu = gpus > 0;
  if (gpus > 0) {
    n = camp_jobs_auto_gpu(free_b, gpus, c->particles_estimate, o->np);
    if (isfinite(c->particles_estimate))
      fprintf(stderr,
              "mdpore permeability: --jobs auto: %d runs at once on the GPU (%.1f of %.1f GB "
              "free on GPU 0, about %.3g particles per run at ~%.0f bytes each plus a CUDA "
              "context per rank; at most %d)\n",
              n, free_b / 1e9, total_b / 1e9, c->particles_estimate, GPU_BYTES_PER_PARTICLE,
              CAMP_AUTO_JOBS_MAX);
    else
      fprintf(stderr, "mdpore permeability: --jobs auto: 1 run at a time on the GPU (no particle "
                      "estimate for a SCENE input: give --jobs N)\n");
  } else {
    const int cores = cores_here();
    n = camp_jobs_auto_cpu(cores, o->np);
    fprintf(stderr,
            "mdpore permeability: --jobs auto: %d run%s at once on the CPU (%d cores / %d "
            "rank%s per run; no GPU visible to this build)\n",
            n, n > 1 ? "s" : "", cores, o->np, o->np > 1 ? "s" : "");
  }
  return n;
}

char *const *camp_jobs_env(const camp_opts *o, int jobs) {
  static char threads[64], binding[] = "OMPI_MCA_hwloc_base_binding_policy=none";
  static char *env[3];
  if (jobs <= 1) return NULL;
  int k = 0;
  if (!getenv("OMP_NUM_THREADS")) {
    const int t = cores_here() / (jobs * o->np);
    snprintf(threads, sizeof threads, "OMP_NUM_THREADS=%d", t < 1 ? 1 : t);
    env[k++] = threads;
  }
  if (o->np > 1 && !getenv("OMPI_MCA_hwloc_base_binding_policy")) env[k++] = binding;
  env[k] = NULL;
  return env;
}
