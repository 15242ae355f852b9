/* Device reductions for sim_thermo, in double and in a fixed order (deterministic): a fixed grid
 * strides over the particles (and over the force pass's per-block virial rows), one block then sums
 * the grid's rows. Quantities: N_mobile, KE, momentum (3), sum m v_a v_b (6), pair virial (6).
 * The flux output's sums (sim_flux_sums) the same way: per species, mobile count and sum v_axis. */
#include "cuda_state.cuh"

#include <cub/block/block_reduce.cuh>

__global__ void __launch_bounds__(256)
    k_thermo_part(const struct dev_params q, int n, struct dev_fields p, int nvb,
                  const double *__restrict__ block_virial, double *part) {
  double s[THERMO_SUMS];
  for (int k = 0; k < THERMO_SUMS; k++) s[k] = 0.0;
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x) {
    const int sp = p.species[i];
    const double m = q.mass[sp], vx = p.v[0][i], vy = p.v[1][i], vz = p.v[2][i];
    s[5] += m * vx * vx;
    s[6] += m * vy * vy;
    s[7] += m * vz * vz;
    s[8] += m * vx * vy;
    s[9] += m * vx * vz;
    s[10] += m * vy * vz;
    if (!q.mobile[sp]) continue;
    s[0] += 1.0;
    s[1] += 0.5 * m * (vx * vx + vy * vy + vz * vz);
    s[2] += m * vx;
    s[3] += m * vy;
    s[4] += m * vz;
  }
  for (int b = blockIdx.x * blockDim.x + threadIdx.x; b < nvb; b += gridDim.x * blockDim.x)
    for (int k = 0; k < 6; k++) s[11 + k] += block_virial[6 * b + k];
  typedef cub::BlockReduce<double, 256> reduce_t;
  __shared__ typename reduce_t::TempStorage tmp;
  for (int k = 0; k < THERMO_SUMS; k++) {
    const double t = reduce_t(tmp).Sum(s[k]);
    if (threadIdx.x == 0) part[THERMO_SUMS * blockIdx.x + k] = t;
    __syncthreads();
  }
}

/* Sums the first `nsum` of the THERMO_SUMS columns of the grid's rows into the last row. */
__global__ void __launch_bounds__(256) k_thermo_final(int rows, int nsum, double *part) {
  typedef cub::BlockReduce<double, 256> reduce_t;
  __shared__ typename reduce_t::TempStorage tmp;
  for (int k = 0; k < nsum; k++) {
    double s = 0.0;
    for (int r = threadIdx.x; r < rows; r += blockDim.x) s += part[THERMO_SUMS * r + k];
    const double t = reduce_t(tmp).Sum(s);
    if (threadIdx.x == 0) part[THERMO_SUMS * THERMO_BLOCKS + k] = t;
    __syncthreads();
  }
}

/* Flux sums in the thermo rows (columns 0..FLUX_SUMS-1): per species s, mobile count (column s)
 * and sum v_axis (column MESO_MAX_SPECIES + s). */
#define FLUX_SUMS (2 * MESO_MAX_SPECIES)
static_assert(FLUX_SUMS <= THERMO_SUMS, "flux sums must fit the thermo rows");

__global__ void __launch_bounds__(256)
    k_flux_part(const struct dev_params q, int n, struct dev_fields p, int axis, double *part) {
  double s[FLUX_SUMS];
  for (int k = 0; k < FLUX_SUMS; k++) s[k] = 0.0;
  const double *va = p.v[axis];
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x) {
    const int sp = p.species[i];
    if (!q.mobile[sp]) continue;
      /* unrolled species test keeps s[] in registers */
#pragma unroll
    for (int k = 0; k < MESO_MAX_SPECIES; k++)
      if (k == sp) {
        s[k] += 1.0;
        s[MESO_MAX_SPECIES + k] += va[i];
      }
  }
  typedef cub::BlockReduce<double, 256> reduce_t;
  __shared__ typename reduce_t::TempStorage tmp;
  for (int k = 0; k < FLUX_SUMS; k++) {
    const double t = reduce_t(tmp).Sum(s[k]);
    if (threadIdx.x == 0) part[THERMO_SUMS * blockIdx.x + k] = t;
    __syncthreads();
  }
}

extern "C" void cuda_sim_want_pressure(cuda_sim_t *g, int on) {
  g->want_pressure = on != 0;
}

extern "C" int cuda_sim_thermo_sums(cuda_sim_t *g, double sums[THERMO_SUMS]) {
  if (!g->pressure_valid && g->n_force_blocks > 0) {
    /* The last force pass skipped the pair virial (no sample was announced): run it again for the
     * virial only; the forces are kept, and the same step keys the same random numbers. */
    const int w = g->want_pressure;
    g->want_pressure = 1;
    cuda_force_pass(g, g->last_force_step, 0, 1, 0);
    g->want_pressure = w;
  }
  k_thermo_part<<<THERMO_BLOCKS, 256>>>(g->prm, g->n, g->a, g->n_force_blocks, g->block_virial,
                                        g->thermo_part);
  k_thermo_final<<<1, 256>>>(THERMO_BLOCKS, THERMO_SUMS, g->thermo_part);
  return cuda_check(cudaMemcpy(sums, g->thermo_part + THERMO_SUMS * THERMO_BLOCKS,
                               THERMO_SUMS * sizeof(double), cudaMemcpyDeviceToHost),
                    "thermo");
}

extern "C" int cuda_sim_flux_sums(cuda_sim_t *g, int axis, double sums[2 * MESO_MAX_SPECIES]) {
  k_flux_part<<<THERMO_BLOCKS, 256>>>(g->prm, g->n, g->a, axis, g->thermo_part);
  k_thermo_final<<<1, 256>>>(THERMO_BLOCKS, FLUX_SUMS, g->thermo_part);
  return cuda_check(cudaMemcpy(sums, g->thermo_part + THERMO_SUMS * THERMO_BLOCKS,
                               FLUX_SUMS * sizeof(double), cudaMemcpyDeviceToHost),
                    "flux");
}
