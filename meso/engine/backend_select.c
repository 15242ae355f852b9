/* Which backend runs a simulation: --backend cpu|cuda|auto, and the ops table of the choice. */
#include "engine/sim_internal.h"

#include <string.h>

static int cuda_device_count_or_why(char *why, size_t len) {
#ifdef MDPORE_HAVE_CUDA
  return backend_cuda_device_count(why, len);
#else
  snprintf(why, len, "this mdpore was built without CUDA (MDPORE_CUDA=OFF or no nvcc found)");
  return 0;
#endif
}

int sim_backend_choose(const char *name, int nranks, int *backend, char *err, size_t errlen) {
  char why[256] = "";
  const int gpus = cuda_device_count_or_why(why, sizeof why);
  (void)nranks;
  if (!name || !strcmp(name, "auto")) {
    /* One GPU per rank: the ranks of a node share its GPUs in turn (cuda_create.cu); every rank
     * must agree, so the choice is collective (a rank that sees no GPU makes all run on CPUs). */
    int cuda = gpus > 0;
    MPI_Allreduce(MPI_IN_PLACE, &cuda, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    *backend = cuda ? SCENE_BACKEND_CUDA : SCENE_BACKEND_CPU;
    return 0;
  }
  if (!strcmp(name, "cpu")) {
    *backend = SCENE_BACKEND_CPU;
    return 0;
  }
  if (strcmp(name, "cuda")) {
    snprintf(err, errlen, "--backend: expected cpu, cuda or auto (got '%s')", name);
    return -1;
  }
  if (gpus < 1) {
    snprintf(err, errlen, "--backend cuda: no GPU available: %s", why);
    return -1;
  }
  *backend = SCENE_BACKEND_CUDA;
  return 0;
}

const backend_ops_t *sim_backend_ops(int backend, int nranks) {
  if (backend != SCENE_BACKEND_CUDA) return &backend_cpu_ops;
#ifdef MDPORE_HAVE_CUDA
  return backend_cuda_ops(nranks);
#else
  (void)nranks;
  return NULL;
#endif
}
