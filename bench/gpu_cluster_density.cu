/* Prototype, not the engine (what a cluster-pair layout would give the density
 * pass). The engine's density scan gives each thread one particle and its own rows of bins: the
 * row set-up is per particle and the warp's lanes diverge (ncu, 2026-11-27: 17 of 32 threads
 * active on average). Here, as in GROMACS' GPU pair lists (Pall and Hess 2013), particles are
 * sorted into columns along z, cut into clusters of 4, and a warp computes an 8 x 4 tile of pairs
 * at a time (an i-cluster of 8 against a j-cluster of 4, every lane busy); the lists hold cluster
 * pairs whose bounding boxes come within the cutoff.
 *
 * Measured on uniform random particles at the engine's density (6.2 per rc^3, periodic cube, the
 * bulk benchmark's box): the cluster sort's passes, the pair search (lists to rc for a force pass
 * and to rd for the density pass) and the density pass over the rd lists (Warren's weight, rd =
 * 0.75), median of 9 (CUDA events). Checked against a brute-force sum on the host (a small box):
 * every pair within rd found, densities to float rounding. Not a test; usage: gpu_cluster_density
 * [N ...] */
#define MESO_REAL_FLOAT /* the engine's pair math: float */
#include "physics/density_kernels.h"

#include <cub/cub.cuh>
#define BENCH_NAME "gpu_cluster_density"
#include "bench_cuda.cuh"

#include <cuda_runtime.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#define DENSITY 6.2f
#define RC 1.0f
#define RD 0.75f
#define LIST_CAP 160 /* cluster pairs per i-cluster (an overflow is reported) */
#define PAD 1e15f    /* padding particles' coordinate: never within a cutoff */

struct box {
  float L, cs; /* box edge; column width along x and y */
  int ncx;     /* columns per axis (ncx^2 columns) */
};

/* Column of a particle and its z as one 64-bit key: sorted, each column's particles by z. */
__global__ void k_keys(int n, const float4 *p, box b, uint64_t *key, int *val) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const int cx = min((int)(p[i].x / b.cs), b.ncx - 1), cy = min((int)(p[i].y / b.cs), b.ncx - 1);
  key[i] = (uint64_t)(cx + b.ncx * cy) << 32 | __float_as_uint(p[i].z);
  val[i] = i;
}

__global__ void k_count(int n, const uint64_t *key, int *count) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) atomicAdd(&count[key[i] >> 32], 1);
}

__global__ void k_pad_counts(int ncol, const int *count, int *padded) {
  const int c = blockIdx.x * blockDim.x + threadIdx.x;
  if (c < ncol) padded[c] = (count[c] + 7) & ~7; /* i-clusters of 8 never span two columns */
}

__global__ void k_fill_pads(int m, float4 *q) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < m) q[k] = make_float4(PAD, PAD, PAD, __int_as_float(-1));
}

/* Sorted particle k to its slot in the padded layout (w: its index in the input). */
__global__ void k_scatter(int n, const uint64_t *key, const int *val, const int *ustart,
                          const int *pstart, const float4 *p, float4 *q) {
  const int k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= n) return;
  const int c = (int)(key[k] >> 32), dst = pstart[c] + (k - ustart[c]);
  const float4 a = p[val[k]];
  q[dst] = make_float4(a.x, a.y, a.z, __int_as_float(val[k]));
}

/* Bounding box of each j-cluster of 4 (padding excluded; an all-padding cluster gets an empty
 * box). */
__global__ void k_bbox(int nj, const float4 *q, float4 *lo, float4 *hi) {
  const int j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= nj) return;
  float3 l = make_float3(1e30f, 1e30f, 1e30f), h = make_float3(-1e30f, -1e30f, -1e30f);
  for (int k = 0; k < 4; k++) {
    const float4 a = q[4 * j + k];
    if (__float_as_int(a.w) < 0) continue;
    l = make_float3(fminf(l.x, a.x), fminf(l.y, a.y), fminf(l.z, a.z));
    h = make_float3(fmaxf(h.x, a.x), fmaxf(h.y, a.y), fmaxf(h.z, a.z));
  }
  lo[j] = make_float4(l.x, l.y, l.z, 0);
  hi[j] = make_float4(h.x, h.y, h.z, 0);
}

__device__ __forceinline__ float gap(float alo, float ahi, float blo, float bhi) {
  return fmaxf(0.0f, fmaxf(blo - ahi, alo - bhi));
}

/* One thread per i-cluster (j-clusters 2 ic, 2 ic + 1): the j-clusters of the (2R+1)^2 columns
 * around it and of the three z images whose boxes come within rc (list_c) and rd (list_d). Entry:
 * j-cluster << 5 | image code (sx + 1) + 3 (sy + 1) + 9 (sz + 1). */
__global__ void k_search(int ni, box b, int R, const int *icol, const int *pstart, const int *count,
                         const float4 *lo, const float4 *hi, uint32_t *list_c, int *n_c,
                         uint32_t *list_d, int *n_d, int *overflow) {
  const int ic = blockIdx.x * blockDim.x + threadIdx.x;
  if (ic >= ni) return;
  const float4 l0 = lo[2 * ic], l1 = lo[2 * ic + 1], h0 = hi[2 * ic], h1 = hi[2 * ic + 1];
  const float3 il = make_float3(fminf(l0.x, l1.x), fminf(l0.y, l1.y), fminf(l0.z, l1.z));
  const float3 ih = make_float3(fmaxf(h0.x, h1.x), fmaxf(h0.y, h1.y), fmaxf(h0.z, h1.z));
  int mc = 0, md = 0;
  if (il.x <= ih.x) { /* (not an all-padding cluster) */
    const int c = icol[ic], cx = c % b.ncx, cy = c / b.ncx;
    for (int oy = -R; oy <= R; oy++) {
      int yy = cy + oy, sy = 0;
      if (yy < 0) yy += b.ncx, sy = -1;
      if (yy >= b.ncx) yy -= b.ncx, sy = 1;
      for (int ox = -R; ox <= R; ox++) {
        int xx = cx + ox, sx = 0;
        if (xx < 0) xx += b.ncx, sx = -1;
        if (xx >= b.ncx) xx -= b.ncx, sx = 1;
        const int cc = xx + b.ncx * yy;
        const int j0 = pstart[cc] / 4, nj = (count[cc] + 3) / 4; /* non-empty j-clusters */
        for (int sz = -1; sz <= 1; sz++) {
          const float qlo = il.z - RC - sz * b.L, qhi = ih.z + RC - sz * b.L;
          if (qhi < 0.0f || qlo > b.L || nj == 0) continue;
          int a = 0, e = nj; /* first j-cluster whose top reaches qlo (tops rise along z) */
          while (a < e) {
            const int mid = (a + e) / 2;
            if (hi[j0 + mid].z < qlo)
              a = mid + 1;
            else
              e = mid;
          }
          for (int k = a; k < nj && lo[j0 + k].z <= qhi; k++) {
            const int j = j0 + k;
            const float gx = gap(il.x, ih.x, lo[j].x + sx * b.L, hi[j].x + sx * b.L);
            const float gy = gap(il.y, ih.y, lo[j].y + sy * b.L, hi[j].y + sy * b.L);
            const float gz = gap(il.z, ih.z, lo[j].z + sz * b.L, hi[j].z + sz * b.L);
            const float g2 = gx * gx + gy * gy + gz * gz;
            const uint32_t entry =
                (uint32_t)j << 5 | (uint32_t)((sx + 1) + 3 * (sy + 1) + 9 * (sz + 1));
            if (g2 < RC * RC) {
              if (mc < LIST_CAP) list_c[(size_t)ic * LIST_CAP + mc] = entry;
              mc++;
            }
            if (g2 < RD * RD) {
              if (md < LIST_CAP) list_d[(size_t)ic * LIST_CAP + md] = entry;
              md++;
            }
          }
        }
      }
    }
  }
  n_c[ic] = min(mc, LIST_CAP);
  n_d[ic] = min(md, LIST_CAP);
  if (mc > LIST_CAP) atomicMax(overflow, mc);
}

/* One warp per i-cluster: lane = i (lane & 7) x j (lane >> 3) of each 8 x 4 tile; rho_i summed
 * over the tiles and the warp's four j lanes (Warren's weight of physics/density_kernels.h, as the
 * engine's). */
__global__ void k_density(int ni, box b, const float4 *q, const uint32_t *list_d, const int *n_d,
                          float *rho) {
  const int ic = (blockIdx.x * blockDim.x + threadIdx.x) >> 5, lane = threadIdx.x & 31;
  if (ic >= ni) return;
  const int il = lane & 7, jl = lane >> 3, me = 8 * ic + il;
  const float4 pi = q[me];
  const float wnorm = w_rho_norm(MESO_KERNEL_WARREN, RD), inv_rd = 1.0f / RD;
  float sum = 0.0f;
  const int m = n_d[ic];
  for (int e = 0; e < m; e++) {
    const uint32_t entry = list_d[(size_t)ic * LIST_CAP + e];
    const int j = (int)(entry >> 5) * 4 + jl, code = (int)(entry & 31);
    const int sz = code / 9 - 1, sy = (code / 3) % 3 - 1, sx = code % 3 - 1;
    const float4 pj = q[j];
    const float dx = pi.x - (pj.x + sx * b.L), dy = pi.y - (pj.y + sy * b.L),
                dz = pi.z - (pj.z + sz * b.L);
    const float r2 = dx * dx + dy * dy + dz * dz;
    const float w = w_rho_warren_inv(sqrtf(r2), inv_rd, wnorm);
    sum += (r2 < RD * RD && j != me) ? w : 0.0f;
  }
  sum += __shfl_xor_sync(0xffffffffu, sum, 8);
  sum += __shfl_xor_sync(0xffffffffu, sum, 16);
  if (jl == 0 && __float_as_int(pi.w) >= 0) rho[__float_as_int(pi.w)] = sum;
}

static int blocks(long n, int t) {
  return (int)((n + t - 1) / t);
}

/* One box of n particles: the passes, timed, and (small n) the host check. 0 or 1. */
static int run(long n, int check) {
  box b;
  b.L = cbrtf((float)n / DENSITY);
  b.ncx = (int)(b.L / cbrtf(4.0f / DENSITY)); /* clusters of 4 about as tall as wide */
  b.cs = b.L / b.ncx;
  const int R = (int)ceilf(RC / b.cs), ncol = b.ncx * b.ncx;
  float4 *h = (float4 *)malloc(n * sizeof(float4));
  uint64_t s = 88172645463325252ull;
  for (long i = 0; i < n; i++) {
    float c[3];
    for (int d = 0; d < 3; d++) {
      s ^= s << 13, s ^= s >> 7, s ^= s << 17;
      c[d] = (float)((double)(s >> 11) / 9007199254740992.0) * b.L;
      if (c[d] >= b.L) c[d] = 0.0f;
    }
    h[i] = make_float4(c[0], c[1], c[2], 0);
  }
  float4 *p, *q, *lo, *hi;
  uint64_t *key, *key2;
  int *val, *val2, *cnt, *padded, *pstart, *ustart, *icol, *n_c, *n_d, *ovf;
  uint32_t *list_c, *list_d;
  float *rho;
  const long mpad = n + 8L * ncol; /* room for every column's padding */
  CHECK(cudaMalloc(&p, n * sizeof(float4)));
  CHECK(cudaMalloc(&q, mpad * sizeof(float4)));
  CHECK(cudaMalloc(&key, n * sizeof(uint64_t)));
  CHECK(cudaMalloc(&key2, n * sizeof(uint64_t)));
  CHECK(cudaMalloc(&val, n * sizeof(int)));
  CHECK(cudaMalloc(&val2, n * sizeof(int)));
  CHECK(cudaMalloc(&cnt, (ncol + 1) * sizeof(int)));
  CHECK(cudaMalloc(&padded, (ncol + 1) * sizeof(int)));
  CHECK(cudaMalloc(&pstart, (ncol + 1) * sizeof(int)));
  CHECK(cudaMalloc(&ustart, (ncol + 1) * sizeof(int)));
  CHECK(cudaMalloc(&lo, mpad / 4 * sizeof(float4)));
  CHECK(cudaMalloc(&hi, mpad / 4 * sizeof(float4)));
  CHECK(cudaMalloc(&icol, mpad / 8 * sizeof(int)));
  CHECK(cudaMalloc(&n_c, mpad / 8 * sizeof(int)));
  CHECK(cudaMalloc(&n_d, mpad / 8 * sizeof(int)));
  CHECK(cudaMalloc(&ovf, sizeof(int)));
  CHECK(cudaMalloc(&list_c, (size_t)(mpad / 8) * LIST_CAP * sizeof(uint32_t)));
  CHECK(cudaMalloc(&list_d, (size_t)(mpad / 8) * LIST_CAP * sizeof(uint32_t)));
  CHECK(cudaMalloc(&rho, n * sizeof(float)));
  CHECK(cudaMemcpy(p, h, n * sizeof(float4), cudaMemcpyHostToDevice));
  size_t tmp_sort = 0, tmp_scan = 0;
  cub::DeviceRadixSort::SortPairs(NULL, tmp_sort, key, key2, val, val2, (int)n);
  cub::DeviceScan::ExclusiveSum(NULL, tmp_scan, cnt, pstart, ncol + 1);
  void *tmp;
  CHECK(cudaMalloc(&tmp, tmp_sort > tmp_scan ? tmp_sort : tmp_scan));
  int ni = 0;
  /* the cluster layout: keys, sort, column counts, padded starts, scatter, boxes */
  const auto layout = [&] {
    k_keys<<<blocks(n, 256), 256>>>((int)n, p, b, key, val);
    cub::DeviceRadixSort::SortPairs(tmp, tmp_sort, key, key2, val, val2, (int)n);
    cudaMemsetAsync(cnt, 0, (ncol + 1) * sizeof(int));
    k_count<<<blocks(n, 256), 256>>>((int)n, key2, cnt);
    k_pad_counts<<<blocks(ncol + 1, 256), 256>>>(ncol + 1, cnt, padded);
    cub::DeviceScan::ExclusiveSum(tmp, tmp_scan, padded, pstart, ncol + 1);
    cub::DeviceScan::ExclusiveSum(tmp, tmp_scan, cnt, ustart, ncol + 1);
    k_fill_pads<<<blocks(mpad, 256), 256>>>((int)mpad, q);
    k_scatter<<<blocks(n, 256), 256>>>((int)n, key2, val2, ustart, pstart, p, q);
  };
  layout();
  int *hp = (int *)malloc((ncol + 1) * sizeof(int));
  CHECK(cudaMemcpy(hp, pstart, (ncol + 1) * sizeof(int), cudaMemcpyDeviceToHost));
  const int mtot = hp[ncol];
  ni = mtot / 8;
  int *hic = (int *)malloc(ni * sizeof(int));
  for (int c = 0; c < ncol; c++)
    for (int k = hp[c] / 8; k < hp[c + 1] / 8; k++) hic[k] = c;
  CHECK(cudaMemcpy(icol, hic, ni * sizeof(int), cudaMemcpyHostToDevice));
  const auto boxes = [&] { k_bbox<<<blocks(mtot / 4, 256), 256>>>(mtot / 4, q, lo, hi); };
  const auto search = [&] {
    k_search<<<blocks(ni, 128), 128>>>(ni, b, R, icol, pstart, cnt, lo, hi, list_c, n_c, list_d,
                                       n_d, ovf);
  };
  const auto density = [&] {
    k_density<<<blocks(32L * ni, 128), 128>>>(ni, b, q, list_d, n_d, rho);
  };
  CHECK(cudaMemset(ovf, 0, sizeof(int)));
  boxes();
  search();
  density();
  CHECK(cudaDeviceSynchronize());
  int over = 0;
  CHECK(cudaMemcpy(&over, ovf, sizeof(int), cudaMemcpyDeviceToHost));
  const float t_layout = median_ms(layout), t_boxes = median_ms(boxes),
              t_search = median_ms(search), t_density = median_ms(density);
  int *hc = (int *)malloc(ni * sizeof(int)), *hd = (int *)malloc(ni * sizeof(int));
  CHECK(cudaMemcpy(hc, n_c, ni * sizeof(int), cudaMemcpyDeviceToHost));
  CHECK(cudaMemcpy(hd, n_d, ni * sizeof(int), cudaMemcpyDeviceToHost));
  double sc = 0, sd = 0;
  for (int k = 0; k < ni; k++) sc += hc[k], sd += hd[k];
  /* pairs per particle within rc and rd at this density: 4/3 pi r^3 rho */
  const double true_c = 4.18879 * DENSITY, true_d = 4.18879 * RD * RD * RD * DENSITY;
  printf("n=%ld box=%.2f columns=%dx%d (%.3f rc) padded=%d (+%.1f%%) i-clusters=%d R=%d\n", n, b.L,
         b.ncx, b.ncx, b.cs, mtot, 100.0 * (mtot - n) / n, ni, R);
  printf("  lists: %.1f j-clusters per i-cluster to rc (%.0f pair slots per particle, %.1f%% "
         "within rc), %.1f to rd (%.0f slots, %.1f%% within rd); overflow %d\n",
         sc / ni, 4.0 * sc / ni, 100.0 * true_c / (4.0 * sc / ni), sd / ni, 4.0 * sd / ni,
         100.0 * true_d / (4.0 * sd / ni), over);
  printf("  us: layout (keys, sort, counts, scatter) %.1f, boxes %.1f, pair search %.1f, "
         "density over the rd lists %.1f; search + density %.1f (%.3f ns per particle)\n",
         1e3 * t_layout, 1e3 * t_boxes, 1e3 * t_search, 1e3 * t_density,
         1e3 * (t_search + t_density), 1e6 * (t_search + t_density) / n);
  int bad = over != 0;
  if (check) { /* brute force on the host, an independent reference in double (Warren 2003:
                 w = 15 / (2 pi rd^3) (1 - r / rd)^2): every pair within rd, minimum image */
    float *g = (float *)malloc(n * sizeof(float));
    CHECK(cudaMemcpy(g, rho, n * sizeof(float), cudaMemcpyDeviceToHost));
    double worst = 0;
    const double wnorm = 15.0 / (2.0 * M_PI * RD * RD * RD);
    for (long i = 0; i < n; i++) {
      double sum = 0;
      for (long j = 0; j < n; j++) {
        if (j == i) continue;
        double d2 = 0;
        const float a[3] = {h[i].x, h[i].y, h[i].z}, c[3] = {h[j].x, h[j].y, h[j].z};
        for (int d = 0; d < 3; d++) {
          double x = a[d] - c[d];
          x -= b.L * rint(x / b.L);
          d2 += x * x;
        }
        if (d2 < (double)RD * RD) {
          const double t = 1.0 - sqrt(d2) / RD;
          sum += wnorm * t * t;
        }
      }
      worst = fmax(worst, fabs(sum - g[i]) / fmax(sum, 1.0));
    }
    printf("  check against the host's brute force: max relative rho difference %.2e\n", worst);
    bad |= !(worst < 1e-4);
    free(g);
  }
  free(h);
  free(hp);
  free(hic);
  free(hc);
  free(hd);
  cudaFree(p), cudaFree(q), cudaFree(key), cudaFree(key2), cudaFree(val), cudaFree(val2);
  cudaFree(cnt), cudaFree(padded), cudaFree(pstart), cudaFree(ustart), cudaFree(lo), cudaFree(hi);
  cudaFree(icol), cudaFree(n_c), cudaFree(n_d), cudaFree(ovf), cudaFree(list_c), cudaFree(list_d);
  cudaFree(rho), cudaFree(tmp);
  return bad;
}

int main(int argc, char **argv) {
  cudaDeviceProp prop;
  CHECK(cudaGetDeviceProperties(&prop, 0));
  printf("device=\"%s\" density %.1f, rc %.2f, rd %.2f, clusters 8 x 4\n", prop.name, DENSITY, RC,
         RD);
  int bad = run(6000, 1); /* the check */
  for (int a = 1; a < argc; a++) bad |= run(atol(argv[a]), 0);
  if (argc < 2) bad |= run(2126600, 0) | run(10186798, 0);
  if (bad) printf("gpu_cluster_density: FAILED (overflow or check)\n");
  return bad;
}
