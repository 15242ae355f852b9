/* Device velocity-Verlet pieces, the arithmetic of meso/physics/verlet.h in double (the CPU
 * backend calls the same functions): kick + drift (+ displacement check), periodic wrap, the
 * position constraints and particle forces of the named effects (effects/effect_list.h:
 * box_walls, body_force), Groot-Warren prediction, second kick. Problems are recorded on the
 * device and fetched once per step. */
#include "cuda_finish.cuh"
#include "cuda_neighbours.cuh"
#include "physics/periodic_slab.h"
#include "physics/verlet.h"

#include <string.h>

/* leaver (several ranks, else NULL): 1 for a particle outside this rank's subdomain after the
 * drift, k_leaver_flags' test (cuda_halo.cu) folded in here: no second pass over x. key (one rank,
 * else NULL): the bin each particle is sorted into next (k_cell_keys' key and iota, written here
 * while x is in registers). */
__global__ void k_kick_drift(const struct dev_params q, int n, struct dev_fields p,
                             struct dev_problem *pb, int *leaver, uint32_t *key, int *iota) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const int s = p.species[i];
  double x[3] = {p.x[0][i], p.x[1][i], p.x[2][i]};
  double v[3] = {p.v[0][i], p.v[1][i], p.v[2][i]};
  const double x_old[3] = {x[0], x[1], x[2]};
  int nonfinite = 0; /* noted once per particle: the count of a kind is a particle count */
  if (q.mobile[s]) {
    const double f[3] = {p.f[0][i], p.f[1][i], p.f[2][i]};
    const double d2 = verlet_kick_drift(x, v, f, q.dt, q.half_dt, q.inv_mass[s]);
    if (!(d2 < q.max_disp * q.max_disp)) {
      if (isfinite(d2)) {
        dev_note(pb, CUDA_TOO_FAST, 1, p.id[i], x[0], x[1], x[2], sqrt(d2));
      } else {
        dev_note(pb, CUDA_NONFINITE, 1, p.id[i], x[0], x[1], x[2], 0.0);
        nonfinite = 1;
      }
    }
  } else if (q.moving[s]) { /* a moving wall: x += u dt, v = u (physics/verlet.h) */
    verlet_moving_wall_drift(x, v, q.wall_u[s], q.dt);
  }
  /* the position constraints of the named effects (box_walls, bounce_back, wall_boundary) on
   * mobile particles, on the unwrapped drift (x - x_old is the displacement) */
  if (q.walls && q.mobile[s] && particle_effects_after_drift(&q.pe, i, x, v, x_old))
    dev_note(pb, CUDA_LOST, 1, p.id[i], x[0], x[1], x[2], 1.0);
  /* d2 is the displacement, blind to a position that was already non-finite before the drift or
   * that a wall effect made non-finite after it (as the CPU path's kick_drift): such a particle
   * would sit in bin 0 on one rank, or be dropped as lost by the host migration on several, and
   * the run would stop on the wrong cause or on none. Folded into this kernel's record: no
   * extra launch or copy. */
  if (q.mobile[s] && !nonfinite && !isfinite(x[0] + x[1] + x[2] + v[0] + v[1] + v[2]))
    dev_note(pb, CUDA_NONFINITE, 1, p.id[i], x[0], x[1], x[2], 0.0);
  /* the periodic wrap (the CPU path's migration: decomp_wrap); farther than two box lengths from
   * the lower face is a loss there (migrate.c wrap_axis_in_place), not a wrap */
  int far = 0;
  for (int d = 0; d < 3; d++)
    if (q.box_periodic[d] && isfinite(x[d]) && fabs(x[d] - q.box_lo[d]) > 2.0 * q.box_len[d])
      far = 1;
  if (far) dev_note(pb, CUDA_LOST, 1, p.id[i], x[0], x[1], x[2], 1.0);
  /* Along an axis cut between ranks the host migration wraps (migrate.c sends a leaver the way it
   * moved and wraps it while crossing the periodic face): wrapped here, a leaver of the last
   * subdomain would look like one of the first and go the wrong way on 3 or more ranks. */
  for (int d = 0; d < 3; d++)
    if (q.box_periodic[d] && !q.split[d])
      x[d] = box_wrap(x[d], q.box_lo[d], q.box_hi[d], q.box_len[d]);
  for (int d = 0; d < 3; d++) {
    p.x[d][i] = x[d];
    p.v[d][i] = v[d];
  }
  if (leaver)
    leaver[i] = !(x[0] >= q.sub_lo[0] && x[0] < q.sub_hi[0] && x[1] >= q.sub_lo[1] &&
                  x[1] < q.sub_hi[1] && x[2] >= q.sub_lo[2] && x[2] < q.sub_hi[2]);
  if (key) {
    key[i] = dev_cell_key(q, x[0], x[1], x[2]);
    iota[i] = i;
  }
}

__global__ void k_predict(const struct dev_params q, int n, struct dev_fields p, int setup) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const int s = p.species[i];
  const double k = (!setup && q.mobile[s]) ? q.predict_c * q.inv_mass[s] : 0.0;
  const double v[3] = {p.v[0][i], p.v[1][i], p.v[2][i]};
  const double f[3] = {p.f[0][i], p.f[1][i], p.f[2][i]};
  double vp[3];
  verlet_predict(vp, v, f, k);
  for (int d = 0; d < 3; d++) p.vpred[d][i] = vp[d];
}

/* Particle forces of the named effects (when add_particle), finite check of f, second half kick
 * (when kick): dev_finish_particle. On one rank a step's force pass does this itself
 * (cuda_force.cu); this kernel serves the set-up and several ranks. */
__global__ void k_finish(const struct dev_params q, int n, struct dev_fields p,
                         struct dev_problem *pb, int add_particle, int kick) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  const int s = p.species[i];
  double f[3] = {p.f[0][i], p.f[1][i], p.f[2][i]};
  dev_finish_particle(q, p, pb, i, s, f, add_particle, kick);
  if (add_particle && q.particle_forces)
    for (int d = 0; d < 3; d++) p.f[d][i] = f[d];
}

/* One value of one particle (the test-only fault hook). */
__global__ void k_fault_write(int n, struct dev_fields p, int64_t id, int field, int axis,
                              double value, int add) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n || p.id[i] != id) return;
  double *a = field ? p.v[axis] : p.x[axis];
  a[i] = add ? a[i] + value : value;
}

/* Flooding (run/run_flood.c): species `from` -> `to` for the particles in the periodic slab
 * [lo, hi) along `axis`; the count into *changed (device). */
__global__ void k_recolor(int n, struct dev_fields p, int axis, double lo, double hi, double box_lo,
                          double box_len, int from, int to, unsigned long long *changed) {
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n || p.species[i] != from || !periodic_in_slab(p.x[axis][i], lo, hi, box_lo, box_len))
    return;
  p.species[i] = to;
  atomicAdd(changed, 1ull);
}

static int blocks_of(int n) {
  return (n + CUDA_BLOCK - 1) / CUDA_BLOCK;
}

void cuda_kick_drift(struct cuda_sim *g) {
  /* several ranks: the leavers' flags into iota, for cuda_halo_find_leavers; one rank: the sort
   * keys of the step's sort (cuda_sort_cells takes them while keys_ready) */
  const int multi = g->prm.multi;
  int *leaver = multi ? g->iota : NULL;
  const int n_move = g->prm.tail ? g->n_dyn : g->n; /* (the tail never moves) */
  if (n_move)
    k_kick_drift<<<blocks_of(n_move), CUDA_BLOCK>>>(g->prm, n_move, g->a, g->problem, leaver,
                                                    multi ? NULL : g->key, multi ? NULL : g->iota);
  g->leaver_flags_ready = leaver != NULL;
  g->keys_ready = n_move > 0 && !multi;
}

void cuda_predict(struct cuda_sim *g, int setup) {
  if (g->n && g->prm.use_vpred)
    k_predict<<<blocks_of(g->n), CUDA_BLOCK>>>(g->prm, g->n, g->a, setup);
}

void cuda_finish_forces(struct cuda_sim *g, int add_particle, int kick) {
  if (g->n)
    k_finish<<<blocks_of(g->n), CUDA_BLOCK>>>(g->prm, g->n, g->a, g->problem, add_particle, kick);
}

extern "C" int cuda_sim_fault_write(cuda_sim_t *g, int64_t id, int field, int axis, double value,
                                    int add) {
  if (!g->n) return 0;
  g->keys_ready = 0; /* (a position may have changed since the kick-drift's keys) */
  g->prm.tail = 0;   /* (and a static particle's: the next sort places the tail again) */
  k_fault_write<<<blocks_of(g->n), CUDA_BLOCK>>>(g->n, g->a, id, field, axis, value, add);
  return cuda_check(cudaDeviceSynchronize(), "test fault");
}

extern "C" int cuda_sim_recolor(cuda_sim_t *g, int axis, double lo, double hi, double box_lo,
                                double box_len, int from, int to, long *changed) {
  *changed = 0;
  if (!g->n) return 0;
  unsigned long long *d_count = NULL, h_count = 0;
  if (cuda_check(cudaMalloc((void **)&d_count, sizeof *d_count), "recolor")) return -1;
  int rc = cuda_check(cudaMemset(d_count, 0, sizeof *d_count), "recolor");
  if (!rc)
    k_recolor<<<blocks_of(g->n), CUDA_BLOCK>>>(g->n, g->a, axis, lo, hi, box_lo, box_len, from, to,
                                               d_count);
  if (!rc)
    rc = cuda_check(cudaMemcpy(&h_count, d_count, sizeof h_count, cudaMemcpyDeviceToHost),
                    "recolor");
  cudaFree(d_count);
  *changed = (long)h_count;
  return rc;
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
