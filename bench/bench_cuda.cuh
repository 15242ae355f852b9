/* Shared by the standalone CUDA benchmarks (gpu_ceilings, gpu_cluster_density): a CUDA call that
 * must succeed, and the median time of 9 timed repeats after a warm-up (CUDA events). */
#ifndef MDPORE_BENCH_CUDA_CUH
#define MDPORE_BENCH_CUDA_CUH

#include <cuda_runtime.h>
#include <stdio.h>
#include <stdlib.h>

/* BENCH_NAME: the program, in the message of a failed call. */
#define CHECK(call)                                                                                \
  do {                                                                                             \
    cudaError_t e_ = (call);                                                                       \
    if (e_ != cudaSuccess) {                                                                       \
      fprintf(stderr, "%s: %s: %s\n", BENCH_NAME, #call, cudaGetErrorString(e_));                  \
      exit(1);                                                                                     \
    }                                                                                              \
  } while (0)

static int bench_cmp_float(const void *a, const void *b) {
  const float x = *(const float *)a, y = *(const float *)b;
  return (x > y) - (x < y);
}

/* Median time in ms of 9 repeats of what launch() enqueues. */
template <class F> static float median_ms(F launch) {
  cudaEvent_t t0, t1;
  CHECK(cudaEventCreate(&t0));
  CHECK(cudaEventCreate(&t1));
  launch(); /* warm-up */
  CHECK(cudaDeviceSynchronize());
  float ms[9];
  for (int r = 0; r < 9; r++) {
    CHECK(cudaEventRecord(t0));
    launch();
    CHECK(cudaEventRecord(t1));
    CHECK(cudaEventSynchronize(t1));
    CHECK(cudaEventElapsedTime(&ms[r], t0, t1));
  }
  CHECK(cudaGetLastError());
  CHECK(cudaEventDestroy(t0));
  CHECK(cudaEventDestroy(t1));
  qsort(ms, 9, sizeof(float), bench_cmp_float);
  return ms[4];
}

#endif
