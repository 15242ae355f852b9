/* Device velocity-Verlet pieces, the same arithmetic as meso/engine/integrate.c in double:
 * kick + drift (+ displacement check), box walls (effects/box_walls.c), periodic wrap (the CPU
 * path's migration, engine/decomp.c decomp_wrap), Groot-Warren prediction, body force
 * (effects/body_force.c) + second kick. Problems are recorded on the device and fetched once per
 * step. */
#include "cuda_state.cuh"

#include <string.h>

__global__ void k_kick_drift(const struct dev_params q, int n, struct dev_fields p,
                             struct dev_problem *pb) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const int s = p.species[i];
  double x[3] = {p.x[0][i], p.x[1][i], p.x[2][i]};
  double v[3] = {p.v[0][i], p.v[1][i], p.v[2][i]};
  if (q.mobile[s]) {
    const double h = 0.5 * q.dt * q.inv_mass[s];
    double d2 = 0.0;
    for (int d = 0; d < 3; d++) {
      v[d] = v[d] + h * p.f[d][i];
      x[d] += q.dt * v[d];
      d2 += (q.dt * v[d]) * (q.dt * v[d]);
    }
    if (!(d2 < q.max_disp * q.max_disp)) {
      if (isfinite(d2))
        dev_note(pb, CUDA_TOO_FAST, 1, p.id[i], x[0], x[1], x[2], sqrt(d2));
      else
        dev_note(pb, CUDA_NONFINITE, 1, p.id[i], x[0], x[1], x[2], 0.0);
    }
  }
  for (int d = 0; d < 3; d++) {
    if (q.box_periodic[d]) {
      /* decomp_wrap */
      if (isfinite(x[d]) && (x[d] < q.box_lo[d] || x[d] >= q.box_hi[d])) {
        x[d] = q.box_lo[d] + fmod(x[d] - q.box_lo[d], q.box_len[d]);
        if (x[d] < q.box_lo[d]) x[d] += q.box_len[d];
        if (x[d] >= q.box_hi[d]) x[d] = nextafter(q.box_hi[d], q.box_lo[d]);
      }
    } else if (q.walls) {
      /* specular reflection (box_walls) */
      if (x[d] < q.box_lo[d]) {
        x[d] = 2.0 * q.box_lo[d] - x[d];
        v[d] = -v[d];
      } else if (x[d] >= q.box_hi[d]) {
        x[d] = 2.0 * q.box_hi[d] - x[d];
        v[d] = -v[d];
        if (x[d] >= q.box_hi[d]) x[d] = nextafter(q.box_hi[d], q.box_lo[d]);
      }
      if (!(x[d] >= q.box_lo[d] && x[d] < q.box_hi[d]))
        dev_note(pb, CUDA_LOST, 1, p.id[i], x[0], x[1], x[2], 1.0);
    }
  }
  for (int d = 0; d < 3; d++) {
    p.x[d][i] = x[d];
    p.v[d][i] = v[d];
  }
}

__global__ void k_predict(const struct dev_params q, int n, struct dev_fields p, int setup) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const int s = p.species[i];
  const double k = (!setup && q.mobile[s]) ? q.predict_c * q.inv_mass[s] : 0.0;
  for (int d = 0; d < 3; d++) p.vpred[d][i] = p.v[d][i] + k * p.f[d][i];
}

/* Body force (when named and add_body), finite check of f, second half kick (kick). */
__global__ void k_finish(const struct dev_params q, int n, struct dev_fields p,
                         struct dev_problem *pb, int add_body, int kick) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const int s = p.species[i];
  double f[3] = {p.f[0][i], p.f[1][i], p.f[2][i]};
  if (add_body && q.particle_forces) {
    const double sign = (q.rev_axis >= 0 && p.x[q.rev_axis][i] >= q.centre) ? -1.0 : 1.0;
    for (int d = 0; d < 3; d++) f[d] += sign * q.g[s][d];
    for (int d = 0; d < 3; d++) p.f[d][i] = f[d];
  }
  if (!isfinite(f[0] + f[1] + f[2]))
    dev_note(pb, CUDA_NONFINITE, 0, p.id[i], p.x[0][i], p.x[1][i], p.x[2][i], 0.0);
  if (!kick || !q.mobile[s]) return;
  const double h = 0.5 * q.dt * q.inv_mass[s];
  for (int d = 0; d < 3; d++) p.v[d][i] += h * f[d];
}

static int blocks_of(int n) {
  return (n + CUDA_BLOCK - 1) / CUDA_BLOCK;
}

void cuda_kick_drift(struct cuda_sim *g) {
  if (g->n) k_kick_drift<<<blocks_of(g->n), CUDA_BLOCK>>>(g->prm, g->n, g->a, g->problem);
}

void cuda_predict(struct cuda_sim *g, int setup) {
  if (g->n && g->prm.use_vpred)
    k_predict<<<blocks_of(g->n), CUDA_BLOCK>>>(g->prm, g->n, g->a, setup);
}

void cuda_finish_forces(struct cuda_sim *g, int add_body, int kick) {
  if (g->n)
    k_finish<<<blocks_of(g->n), CUDA_BLOCK>>>(g->prm, g->n, g->a, g->problem, add_body, kick);
}

/* Copy the problem record to the host (this synchronises with the step) and clear it. */
int cuda_problem_fetch(struct cuda_sim *g, cuda_problem_t *pr) {
  struct dev_problem h;
  memset(pr, 0, sizeof *pr);
  if (cuda_check(cudaMemcpy(&h, g->problem, sizeof h, cudaMemcpyDeviceToHost), "step")) return -1;
  if (h.kind == 0) return 0;
  pr->kind = h.kind;
  pr->at_drift = h.at_drift;
  pr->id = h.id[h.kind];
  for (int d = 0; d < 3; d++) pr->x[d] = h.x[h.kind][d];
  pr->value = h.value[h.kind];
  pr->count = (long)h.count[h.kind];
  return cuda_check(cudaMemset(g->problem, 0, sizeof h), "step");
}
