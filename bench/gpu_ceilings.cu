/* The two ceilings of the GPU this runs on (bench/README.md, the device tool's METHOD.md), measured
 * rather than read off a datasheet:
 *   bandwidth : a large device-to-device copy, bytes read + bytes written per second;
 *   fp32      : fused multiply-adds per second from a kernel of independent FMA chains (2 flop
 * each); int32 mul : 32-bit integer multiply-high per second (Philox, the pair random numbers, is
 * made of these), same kernel shape. The pair kernels are judged against these in bench/RESULTS.md.
 * Median of 9 timed repeats, CUDA events, after a warm-up; inputs are non-zero. Not a test. usage:
 * gpu_ceilings */
#define BENCH_NAME "gpu_ceilings"
#include "bench_cuda.cuh"

#include <cuda_runtime.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#define CHAINS 8
#define ITERS 4096

/* CHAINS independent FMA chains per thread (enough to hide the FMA latency). */
__global__ void k_fma(float *out, float a, float b) {
  float x[CHAINS];
  for (int c = 0; c < CHAINS; c++) x[c] = (float)(threadIdx.x + c) * 1e-3f;
  for (int it = 0; it < ITERS; it++)
#pragma unroll
    for (int c = 0; c < CHAINS; c++) x[c] = fmaf(x[c], a, b);
  float s = 0;
  for (int c = 0; c < CHAINS; c++) s += x[c];
  if (s == 12345.678f) out[0] = s; /* keeps the work; never true for these inputs */
}

/* CHAINS independent chains of 32-bit multiply-high (as in Philox rounds). */
__global__ void k_mulhi(uint32_t *out, uint32_t m) {
  uint32_t x[CHAINS];
  for (int c = 0; c < CHAINS; c++) x[c] = threadIdx.x * 2654435761u + c;
  for (int it = 0; it < ITERS; it++)
#pragma unroll
    for (int c = 0; c < CHAINS; c++) x[c] = __umulhi(x[c], m) ^ x[c];
  uint32_t s = 0;
  for (int c = 0; c < CHAINS; c++) s ^= x[c];
  if (s == 0x12345678u) out[0] = s;
}

int main(void) {
  cudaDeviceProp prop;
  CHECK(cudaGetDeviceProperties(&prop, 0));
  const size_t bytes = (size_t)2 << 30; /* 2 GiB each way: far beyond the L2 */
  char *a, *b;
  CHECK(cudaMalloc(&a, bytes));
  CHECK(cudaMalloc(&b, bytes));
  CHECK(cudaMemset(a, 1, bytes));
  const float copy_ms =
      median_ms([&] { CHECK(cudaMemcpyAsync(b, a, bytes, cudaMemcpyDeviceToDevice)); });
  const double bw = 2.0 * (double)bytes / (copy_ms * 1e-3);

  const int blocks = prop.multiProcessorCount * 8, threads = 256;
  float *fo;
  uint32_t *io;
  CHECK(cudaMalloc(&fo, sizeof(float)));
  CHECK(cudaMalloc(&io, sizeof(uint32_t)));
  const float fma_ms = median_ms([&] { k_fma<<<blocks, threads>>>(fo, 0.999f, 1e-4f); });
  const double n_ops = (double)blocks * threads * ITERS * CHAINS;
  const float mul_ms = median_ms([&] { k_mulhi<<<blocks, threads>>>(io, 0xD2511F53u); });

  printf("device=\"%s\" SMs=%d L2=%d MiB\n", prop.name, prop.multiProcessorCount,
         prop.l2CacheSize >> 20);
  printf("bandwidth: D2D copy of %zu MiB: %.3f ms, %.0f GB/s (read + write)\n", bytes >> 20,
         copy_ms, bw / 1e9);
  printf("fp32: %.3f ms, %.1f TFLOP/s (FMA = 2 flop), %.1f T FMA/s\n", fma_ms,
         2.0 * n_ops / (fma_ms * 1e-3) / 1e12, n_ops / (fma_ms * 1e-3) / 1e12);
  printf("int32 mul.hi + xor: %.3f ms, %.2f T mul.hi/s\n", mul_ms, n_ops / (mul_ms * 1e-3) / 1e12);
  CHECK(cudaFree(a));
  CHECK(cudaFree(b));
  CHECK(cudaFree(fo));
  CHECK(cudaFree(io));
  return 0;
}
