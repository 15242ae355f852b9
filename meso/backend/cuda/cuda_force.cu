/* Device force pass: the fused pair kernel of the CUDA path (physics.md section 1, paper eq. 1),
 *   F_ij = [A w_c + B (rho_i + rho_j) w_d] e - gamma w_R^2 (e . v~_ij) e + sigma w_R xi_ij /
 * sqrt(dt) e with the pair functions of meso/physics/pair_forces.h and xi_ij of pair_random.h (the
 * same numbers as the CPU path draws). One thread per particle over its neighbour list of this step
 * (written by the density pass, cuda_density.cu; full traversal, each pair from both sides with
 * exactly negated separation and velocity difference). Bin-relative positions and the pair math in
 * meso_real (float unless MDPORE_DOUBLE), the sum per particle in meso_real, the pair virial per
 * block in double. The term set is a template parameter, so unused terms cost nothing (as in
 * backend/cpu), and so is the generator of xi_ij (RNG, enum pair_rng: dpd_thermostat's option
 * rng), so the default Philox4x32-10 kernel is the one it was, without a branch per pair. */
#include "cuda_finish.cuh"
#include "cuda_neighbours.cuh"
#include "cuda_select.cuh"
#include "physics/pair_forces.h"
#include "physics/pair_random.h"
#include "physics/wall_boundary.h"

#include <cub/block/block_reduce.cuh>
#include <type_traits>

struct force_args {
  const uint32_t *nbr;
  const int *count;
  int cap;
  const struct dev_pos *pos;
  const struct dev_vel *vel;
  const int64_t *id;
  const meso_real *rho;
  double *fx, *fy, *fz, *virial, *block_virial;
  uint64_t step;
  /* the generator's round keys for (seed, step) (pair_random_keys: once per pass, not per pair) */
  struct pair_rng_keys keys;
  int n, write_f;
  /* Several ranks with overlap: only slots whose boundary flag (cuda_halo.cu) equals part_flag;
   * NULL: every slot. accumulate: add to the block virial rows (the second part). */
  const uint32_t *part;
  uint32_t part_flag;
  int accumulate;
  /* Compact mode (nbr NULL): the bins to scan (owned; ghosts with several ranks, NULL in the
   * interior part) and each slot's bin. */
  const int *start, *gstart;
  const uint32_t *key;
  /* The boundary part's slot list (several ranks, ghosts selected on the device): thread t
   * computes slot slots[t], t < n_slots; NULL: thread i computes slot i. */
  const int *slots;
  int n_slots;
  /* With slots: their count on the device instead of n_slots (NULL: n_slots). */
  const int *n_slots_dev;
  /* finish (one rank, a step): each thread ends its particle's step (dev_finish_particle: particle
   * forces, finite check, second half kick on the fields fin, problems into problem), so no
   * finishing kernel reads f, v and x again. */
  int finish;
  struct dev_fields fin;
  struct dev_problem *problem;
};

/* Block sums of the pair virial in double, one row per block (reduced in fixed order later). */
__device__ __forceinline__ void block_virial_sums(const meso_real w[6], double *block_virial,
                                                  int accumulate) {
  typedef cub::BlockReduce<double, CUDA_BLOCK> reduce_t;
  __shared__ typename reduce_t::TempStorage tmp;
  for (int k = 0; k < 6; k++) {
    const double s = reduce_t(tmp).Sum((double)w[k]);
    if (threadIdx.x == 0) {
      if (accumulate)
        block_virial[6 * blockIdx.x + k] += s;
      else
        block_virial[6 * blockIdx.x + k] = s;
    }
    __syncthreads();
  }
}

/* TERMS: the pair terms; VIRIAL: per-particle virial (stress profiles); PV: block sums of the pair
 * virial (the pressure of a thermo sample; skipped on the other steps); LISTS 0: the compact memory
 * mode, partners found by scanning the bins again (the same traversal order and float operations
 * as the list build, so the same forces bitwise); RNG: the generator of xi (PAIR_RNG_PHILOX for
 * term sets without the thermostat). With the thermostat the partner's density travels
 * in its packed velocity (vel.pad, cuda_rho_to_vel): one load less. UNI: every pair has the
 * coefficients of q.coef[0][0] (q.coef_uniform), read at fixed offsets: no table load by species
 * per pair. */
template <int TERMS, int VIRIAL, int PV, int LISTS, int RNG, int UNI = 0>
__global__ void __launch_bounds__(CUDA_BLOCK)
    k_force(const struct dev_params q, struct force_args a) {
  const int t_id = blockIdx.x * blockDim.x + threadIdx.x;
  const int n_slots = a.n_slots_dev ? *a.n_slots_dev : a.n_slots;
  const int i = !a.slots ? t_id : (t_id < n_slots ? a.slots[t_id] : a.n);
  meso_real w[6] = {0, 0, 0, 0, 0, 0};
  if (i < a.n && (!a.part || a.part[i] == a.part_flag)) {
    const struct dev_pos pi = a.pos[i];
    const struct dev_coef *row = q.coef[pi.species];
    struct dev_vel vi = {0, 0, 0, 0};
    if (TERMS & PAIR_TERM_THERMOSTAT) vi = a.vel[i];
    const meso_real rho_i = !(TERMS & PAIR_TERM_MANYBODY)    ? MESO_R(0.0)
                            : (TERMS & PAIR_TERM_THERMOSTAT) ? vi.pad
                                                             : a.rho[i];
    const int64_t id_i = a.id[i];
    /* wall_boundary's no slip: Li's ratio(phi_i) scales the thermostat of the wall pairs */
    meso_real wall_ratio = MESO_R(1.0), wall_sqrt_ratio = MESO_R(1.0);
    if (TERMS & PAIR_TERM_WALL_NO_SLIP) {
      wall_ratio = (meso_real)q.pe.wall_boundary.field[i].ratio; /* capped (wall_boundary.h) */
      wall_sqrt_ratio = (meso_real)q.pe.wall_boundary.field[i].sqrt_ratio;
    }
    meso_real sfx = 0, sfy = 0, sfz = 0;
    const auto pair = [&](int t, const struct dev_pos &pj, meso_real dx, meso_real dy,
                          meso_real dz) {
      const meso_real r2 = dx * dx + dy * dy + dz * dz;
      const struct dev_coef &c = UNI ? q.coef[0][0] : row[pj.species];
      /* r2 below the smallest normal float (r < 1.1e-19 rc): coincident, no direction */
      if (r2 >= c.cut2 || !(r2 >= MESO_R_MIN_NORMAL)) return;
      const meso_real inv_r = dev_rsqrt_normal(r2), dist = r2 * inv_r; /* no division */
      struct dev_vel vj = {0, 0, 0, 0};
      if (TERMS & PAIR_TERM_THERMOSTAT) vj = a.vel[t];
      meso_real fp = 0;
      if ((TERMS & PAIR_TERM_CONSERVATIVE) && r2 < c.rc2)
        fp += pair_conservative_inv(c.A, dist, c.inv_rc);
      if ((TERMS & PAIR_TERM_MANYBODY) && r2 < c.rd2)
        fp += pair_manybody_inv(c.B, rho_i + ((TERMS & PAIR_TERM_THERMOSTAT) ? vj.pad : a.rho[t]),
                                dist, c.inv_rd);
      if ((TERMS & PAIR_TERM_THERMOSTAT) && r2 < c.rc2) {
        const meso_real wR = pair_weight_random_inv(dist, c.inv_rc, c.s_exp, c.s_one);
        const meso_real e_dot_v =
            (dx * (vi.x - vj.x) + dy * (vi.y - vj.y) + dz * (vi.z - vj.z)) * inv_r;
        const meso_real xi_ij =
            pair_random_from_bits(pair_random_bits_keyed(RNG, a.keys, id_i, a.id[t]));
        const bool wall = (TERMS & PAIR_TERM_WALL_NO_SLIP) && c.wall_phi2 > MESO_R(0.0);
        fp += pair_thermostat(wall ? wall_ratio * c.gamma : c.gamma,
                              wall ? wall_sqrt_ratio * c.sigma : c.sigma, wR, e_dot_v, xi_ij,
                              q.inv_sqrt_dt);
      }
      const meso_real s = fp * inv_r;
      sfx += s * dx;
      sfy += s * dy;
      sfz += s * dz;
      if (!PV && !VIRIAL) return;
      const meso_real hs = MESO_R(0.5) * s; /* each pair is seen from both sides */
      w[0] += hs * dx * dx;
      w[1] += hs * dy * dy;
      w[2] += hs * dz * dz;
      w[3] += hs * dx * dy;
      w[4] += hs * dx * dz;
      w[5] += hs * dy * dz;
    };
    /* a frozen particle is never integrated: no force of its own (the pairs with mobile partners
     * are evaluated from their side), so wall-wall pairs are never computed */
    if (LISTS) {
      const int m = q.mobile[pi.species] ? a.count[i] : 0;
      /* AX: the minimum-image axes of dev_offset_sep; the every-step kernels (no virial) are
       * compiled for boxes with none (3D) and with the thin y axis of the ring medium too */
      const auto over_list = [&](auto ax) {
        nbr_for_each(a.nbr, i, m, a.cap, [&](uint32_t e) {
          const int t = (int)(e & ((1u << NBR_SLOT_BITS) - 1));
          const struct dev_pos pj = a.pos[t];
          meso_real dx, dy, dz;
          dev_offset_sep<decltype(ax)::value>(q, pi, pj, e >> NBR_SLOT_BITS, &dx, &dy, &dz);
          pair(t, pj, dx, dy, dz);
        });
      };
      if constexpr (!VIRIAL && !PV) {
        if (q.near_axes == 0)
          over_list(std::integral_constant<int, 0>());
        else if (q.near_axes == 2)
          over_list(std::integral_constant<int, 2>());
        else
          over_list(std::integral_constant<int, 7>());
      } else {
        over_list(std::integral_constant<int, 7>());
      }
    } else if (q.mobile[pi.species]) {
      dev_for_each_neighbour(
          q, a.start, a.gstart, a.n, a.pos, pi, a.key[i],
          [&](int t, int code, const struct dev_pos &pj, meso_real dx, meso_real dy, meso_real dz) {
            (void)code;
            if (t != i) pair(t, pj, dx, dy, dz);
          },
          q.scan_cut2);
    }
    if (a.write_f && a.finish) {
      double f[3] = {sfx, sfy, sfz};
      dev_finish_particle(q, a.fin, a.problem, i, (int)pi.species, f, 1, 1);
      a.fx[i] = f[0];
      a.fy[i] = f[1];
      a.fz[i] = f[2];
    } else if (a.write_f) {
      a.fx[i] = sfx;
      a.fy[i] = sfy;
      a.fz[i] = sfz;
    }
    if (VIRIAL)
      for (int k = 0; k < 6; k++) a.virial[6 * (size_t)i + k] = w[k];
  }
  if (PV) block_virial_sums(w, a.block_virial, a.accumulate);
}

template <int T, int R, int LISTS>
static void launch_mode(const struct dev_params &q, const struct force_args &a, int blocks,
                        int virial, int pv, cudaStream_t stream) {
  if (virial)
    k_force<T, 1, 1, LISTS, R><<<blocks, CUDA_BLOCK, 0, stream>>>(q, a);
  else if (pv)
    k_force<T, 0, 1, LISTS, R><<<blocks, CUDA_BLOCK, 0, stream>>>(q, a);
  else if (q.coef_uniform)
    k_force<T, 0, 0, LISTS, R, 1><<<blocks, CUDA_BLOCK, 0, stream>>>(q, a);
  else
    k_force<T, 0, 0, LISTS, R><<<blocks, CUDA_BLOCK, 0, stream>>>(q, a);
}

/* The list (fast memory mode) or the bin scan (compact). */
template <int T, int R>
static void launch_rng(const struct dev_params &q, const struct force_args &a, int blocks,
                       int virial, int pv, cudaStream_t stream) {
  if (a.nbr)
    launch_mode<T, R, 1>(q, a, blocks, virial, pv, stream);
  else
    launch_mode<T, R, 0>(q, a, blocks, virial, pv, stream);
}

/* One kernel per generator for the term sets with the thermostat; the others draw no random
 * numbers and have one (R = PAIR_RNG_PHILOX for every q.rng). */
template <int T>
static void launch(const struct dev_params &q, const struct force_args &a, int blocks, int virial,
                   int pv, cudaStream_t stream) {
  const bool xi = (T & PAIR_TERM_THERMOSTAT) != 0;
  switch (q.rng) {
  case PAIR_RNG_FAST:
    launch_rng<T, xi ? PAIR_RNG_FAST : PAIR_RNG_PHILOX>(q, a, blocks, virial, pv, stream);
    break;
  case PAIR_RNG_PHILOX2X32:
    launch_rng<T, xi ? PAIR_RNG_PHILOX2X32 : PAIR_RNG_PHILOX>(q, a, blocks, virial, pv, stream);
    break;
  default:
    launch_rng<T, PAIR_RNG_PHILOX>(q, a, blocks, virial, pv, stream);
    break;
  }
}

/* Whether slot i holds a mobile species (bit s of mask). */
struct is_mobile {
  const struct dev_pos *pos;
  unsigned mask;
  __device__ __forceinline__ bool operator()(int i) const {
    return (mask >> (unsigned)pos[i].species) & 1u;
  }
};

/* The frozen particles' f zeroed: threads [*n_mobile, n) over the frozen part of the partition
 * (cuda_mobile_partition), so no lane reads a mobile slot. */
__global__ void k_zero_frozen_f(int n, const int *__restrict__ part, const int *n_mobile,
                                double *fx, double *fy, double *fz) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= n || t < *n_mobile) return;
  const int i = part[t];
  fx[i] = fy[i] = fz[i] = 0.0;
}

/* The same with the named effects' particle forces: the frozen particles' step ended as the force
 * pass ends the mobile ones'. */
__global__ void k_finish_frozen(const struct dev_params q, int n, const int *__restrict__ part,
                                const int *n_mobile, struct dev_fields p, struct dev_problem *pb) {
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= n || t < *n_mobile) return;
  const int i = part[t];
  double f[3] = {0.0, 0.0, 0.0};
  dev_finish_particle(q, p, pb, i, p.species[i], f, 1, 1);
  p.f[0][i] = f[0];
  p.f[1][i] = f[1];
  p.f[2][i] = f[2];
}

/* One rank with lists (g->mobile_slots_on): this build's slots into g->mobile_slot, the mobile ones
 * first (slot order; their count into g->mobile_count, on the device), then the frozen ones; once
 * per build (g->mobile_slots_ready). 0 or -1. */
int cuda_mobile_partition(struct cuda_sim *g) {
  if (g->mobile_slots_ready) return 0;
  const int n = g->n;
  struct is_mobile pred = {g->pos, 0u};
  for (int s = 0; s < g->prm.n_species; s++)
    if (g->prm.mobile[s]) pred.mask |= 1u << s;
  if (cuda_dev_room(g, (char **)&g->mobile_slot, &g->mobile_slot_bytes, (size_t)n * sizeof(int)) ||
      (!g->mobile_count && cuda_alloc(g, (void **)&g->mobile_count, sizeof(int))) ||
      cuda_partition_slots_if(g, pred, g->mobile_slot, g->mobile_count, n, "mobile slots"))
    return -1;
  g->mobile_slots_ready = 1;
  return 0;
}

/* The force pass over the mobile slots (cuda_mobile_partition), and the frozen particles' f zeroed
 * (what the full pass writes for them; with finish, their step ended). 0 or -1. */
static int select_mobile(struct cuda_sim *g, int write_f, int finish) {
  const int n = g->n;
  if (cuda_mobile_partition(g)) return -1;
  const int blocks = (n + CUDA_BLOCK - 1) / CUDA_BLOCK;
  const int *part = g->mobile_slot, *n_mobile = g->mobile_count;
  if (write_f && finish && g->prm.particle_forces)
    k_finish_frozen<<<blocks, CUDA_BLOCK>>>(g->prm, n, part, n_mobile, g->a, g->problem);
  else if (write_f)
    k_zero_frozen_f<<<blocks, CUDA_BLOCK>>>(n, part, n_mobile, g->a.f[0], g->a.f[1], g->a.f[2]);
  return 0;
}

/* part < 0: every owned particle; 1 / 0: only the interior / boundary particles (several ranks,
 * overlap: cuda_halo.cu), the boundary part second. The boundary part over its slot list when
 * there is one; on `stream` (not the default stream: concurrent with the interior part) its
 * virial rows follow the interior part's, else they add to the interior part's first rows.
 * finish (one rank, every particle, forces written): the threads end their particles' steps. */
static void force_pass(struct cuda_sim *g, uint64_t step, int want_virial, int keep_forces,
                       int part, cudaStream_t stream, int finish) {
  const int n = g->n;
  const int virial = want_virial && g->virial != NULL;
  /* one rank, lists, no per-particle virial (whose frozen rows the full pass writes): over the
   * mobile slots, the grid still sized for every slot (threads past the device count leave) */
  const int mobile = part < 0 && n > 0 && g->mobile_slots_on && !g->prm.multi && !g->compact &&
                     !virial && g->nbr && select_mobile(g, !keep_forces, finish) == 0;
  const int *slots = part == 0 ? g->boundary_slots : mobile ? g->mobile_slot : NULL;
  const int threads = part == 0 && slots ? g->n_bslots : n,
            blocks = (threads + CUDA_BLOCK - 1) / CUDA_BLOCK;
  const int own_rows = part == 0 && stream != 0;
  double *rows = own_rows ? g->block_virial + 6 * (size_t)g->n_force_blocks : g->block_virial;
  if (part != 0) g->n_force_blocks = n > 0 ? blocks : 0;
  const int pv = g->want_pressure || want_virial;
  g->pressure_valid = pv;
  g->last_force_step = step;
  if (n == 0 || threads == 0) return;
  if (own_rows) g->n_force_blocks += blocks; /* (room: cuda_force_boundary_rows_fit) */
  struct force_args a = {g->compact ? NULL : g->nbr,
                         g->nbr_count,
                         g->cap,
                         g->pos,
                         g->vel,
                         g->a.id,
                         g->rho,
                         g->a.f[0],
                         g->a.f[1],
                         g->a.f[2],
                         g->virial,
                         rows,
                         step,
                         pair_random_keys(g->prm.rng, g->prm.seed, step),
                         n,
                         !keep_forces,
                         part >= 0 ? g->key : NULL,
                         (uint32_t)(part > 0 ? 1 : 0),
                         part == 0 && !own_rows,
                         g->cell_start,
                         g->prm.multi && part != 1 ? g->gcell_start : NULL,
                         g->key_sorted,
                         slots,
                         threads,
                         mobile ? g->mobile_count : NULL,
                         finish,
                         g->a,
                         g->problem};
  switch (g->prm.terms & 15) { /* 8 (wall no slip) comes with 4 (its check) */
  case 0:
    launch<0>(g->prm, a, blocks, virial, pv, stream);
    break;
  case 1:
    launch<1>(g->prm, a, blocks, virial, pv, stream);
    break;
  case 2:
    launch<2>(g->prm, a, blocks, virial, pv, stream);
    break;
  case 3:
    launch<3>(g->prm, a, blocks, virial, pv, stream);
    break;
  case 4:
    launch<4>(g->prm, a, blocks, virial, pv, stream);
    break;
  case 5:
    launch<5>(g->prm, a, blocks, virial, pv, stream);
    break;
  case 6:
    launch<6>(g->prm, a, blocks, virial, pv, stream);
    break;
  case 7:
    launch<7>(g->prm, a, blocks, virial, pv, stream);
    break;
  case 12:
    launch<12>(g->prm, a, blocks, virial, pv, stream);
    break;
  case 13:
    launch<13>(g->prm, a, blocks, virial, pv, stream);
    break;
  case 14:
    launch<14>(g->prm, a, blocks, virial, pv, stream);
    break;
  default:
    launch<15>(g->prm, a, blocks, virial, pv, stream);
    break;
  }
}

void cuda_force_pass_part(struct cuda_sim *g, uint64_t step, int want_virial, int keep_forces,
                          int part, cudaStream_t stream) {
  force_pass(g, step, want_virial, keep_forces, part, stream, 0);
}

void cuda_force_pass(struct cuda_sim *g, uint64_t step, int want_virial, int keep_forces,
                     int finish) {
  /* The density pass stored the owned densities in vel.pad already; the ghosts' arrived since. */
  if (g->n > 0 && g->prm.multi && (g->prm.terms & PAIR_TERM_THERMOSTAT))
    cuda_rho_to_vel(g, g->n, g->n + g->n_ghost, 0);
  force_pass(g, step, want_virial, keep_forces, -1, 0, finish && !keep_forces && !g->prm.multi);
}

/* Whether the boundary part's virial rows fit after the interior part's (block_virial_cap). */
int cuda_force_boundary_rows_fit(const struct cuda_sim *g) {
  const int b = (g->n_bslots + CUDA_BLOCK - 1) / CUDA_BLOCK;
  return g->boundary_slots && g->n_force_blocks + b <= g->block_virial_cap;
}
