/* Device-side state of the CUDA backend (internal to meso/backend/cuda). Particle arrays are kept
 * in cell order: every step they are sorted by cell (stable radix sort, so the order, and with it
 * every per-particle sum, is a deterministic function of the configuration). */
#ifndef MESO_BACKEND_CUDA_STATE_CUH
#define MESO_BACKEND_CUDA_STATE_CUH

#include "cuda_backend.h"
#include "effects/effect_list.h"
#include "physics/hd.h"

#include <cub/device/device_radix_sort.cuh>
#include <cuda_runtime.h>
#include <stdio.h>
#include <stdint.h>

/* Threads per block of the per-particle kernels (a build option only for measuring:
 * -DCUDA_BLOCK=N in CMAKE_CUDA_FLAGS; bench/RESULTS.md, 2026-11-27 94ed3e8). */
#ifndef CUDA_BLOCK
#define CUDA_BLOCK 128
#endif
/* Verlet skin of the lists on one GPU when --skin is not given (rc units). bench/RESULTS.md has the
 * time-vs-skin curve this was chosen from: at dt = 0.01 the fastest of millions of particles moves
 * ~0.06 rc per step, so a list outlives only 2-3 steps, and the longer lists cost the pair passes
 * more than the saved builds; 0 (lists rebuilt every step) is the fastest. */
#define CUDA_DEFAULT_SKIN 0.0
#define NBR_SLOT_BITS 27 /* slots < 2^27 particles per GPU; 5 bits for the 27 bin offsets */

/* Constants of one species pair in the pair math's precision (plan.h pair_coef_t). */
struct dev_coef {
  meso_real A, B, gamma, sigma;
  meso_real inv_rc, rc2, inv_rd, rd2, wnorm, cut2;
  meso_real wall_phi2; /* wall_boundary: r_phi^2 of a mobile-frozen pair, else 0 */
  meso_real s_exp;     /* exponent s of the thermostat weight w_R = (1 - r/rc)^s */
  int s_one;           /* s_exp == 1: the standard weight, no pow */
};

/* Everything the kernels need besides the particle arrays; passed by value to each launch. */
struct dev_params {
  int n_species, terms, density, kernel, walls, particle_forces, use_vpred;
  meso_real inv_sqrt_dt;
  uint64_t seed;
  int rng; /* generator of the pair random numbers (enum pair_rng): the force kernel's template
              parameter, chosen at launch */
  double dt, half_dt, max_disp;
  double predict_c; /* (vv_lambda - 1/2) dt: v~ = v + predict_c f / m (Groot-Warren) */
  int mobile[SCENE_MAX_SPECIES];
  int moving[SCENE_MAX_SPECIES];        /* frozen species translating at wall_u (Couette) */
  int static_frozen[SCENE_MAX_SPECIES]; /* frozen, not moving: density part cached */
  int density_cache;                    /* plan.density_cache (one rank only: cuda_density.cu) */
  double wall_u[SCENE_MAX_SPECIES][3];
  double inv_mass[SCENE_MAX_SPECIES], mass[SCENE_MAX_SPECIES];
  particle_effects_t pe; /* the per-particle effects of the plan (effects/effect_list.h) */
  /* The box (periodic wrap and walls in the integration). */
  double box_lo[3], box_hi[3], box_len[3];
  int box_periodic[3];
  /* The cell grid: origin lo, extent L; periodic[d]: bins wrap (one rank). With several ranks
   * (multi) the grid covers the subdomain plus the ghost layer and never wraps (ghosts carry the
   * images); particles of this rank outside [sub_lo, sub_hi) get the sentinel bin ncell. */
  double lo[3], hi[3], L[3];
  int periodic[3];
  int multi;    /* several ranks */
  int split[3]; /* axis cut between ranks: ghosts along it; other axes wrap on the device */
  double sub_lo[3], sub_hi[3], rcut;
  /* Cells: nb[d] bins of width >= the cutoff; periodic axes wrap. A periodic axis too short for 3
   * bins has one bin the box long and takes the nearest image (the box is >= 2 cutoffs). */
  int nb[3], ncell;
  double inv_bin[3];
  meso_real bin_w[3], box_L[3], inv_box_L[3]; /* in the pair math's precision */
  /* The minimum image of a separation x along axis d is x - near_L rint(x near_inv_L): box_L and
   * inv_box_L along an axis that takes it, 0 along the others (x as it is, without a branch). */
  meso_real near_L[3], near_inv_L[3];
  int near_axes; /* bit d: axis d takes the minimum image; 0: none (3D boxes), else quasi-2D */
  meso_real cut2_max, rd2_max; /* largest squared cutoffs of any pair (tested before the table) */
  /* 1: every pair of species has the same coefficients (coef[0][0]; a scene with pairs.default
   * only): the every-step force kernel reads them at fixed offsets of the kernel parameters, not
   * from the table by the partner's species (force pass 424 -> 408 us on porous 33; the same in
   * the density scan gained nothing: bench/RESULTS.md, 2026-11-27 2703ae8).
   * MDPORE_CUDA_UNIFORM=0 turns it off, for measuring. */
  int coef_uniform;
  /* Verlet skin (one rank only): lists hold the partners within list_cut2 = (cutoff + skin)^2 and
   * are kept until some particle has moved more than skin / 2 since they were built (then no pair
   * within the cutoff can be missing). skin = 0: lists rebuilt every step. */
  double skin;
  meso_real list_cut2, half_skin2;
  int off_lo[3], off_hi[3], min_image[3];
  /* The bins the particles are sorted into (the keys): sub[d] fine bins of width fine_w[d] per bin
   * along each axis, nf[d] = sub[d] nb[d] of them, ncell = nf[0] nf[1] nf[2] (docs/engine-cuda.md
   * "Neighbour scan"). Positions stay packed relative to their coarse bin (nb), and list entries
   * keep the coarse offset code. On one rank sub = 4 along x; along y and z 2 in a quasi-2D box
   * (some axis of fewer than 3 bins), else 1; 1 along an axis that takes the minimum image and on
   * several ranks (cuda_create.cu fill_cells). row_scan: the row traversal (dev_scan_rows);
   * trim_any: its rows cut to the caller's reach; scan_cut2, scan_rd2: the list and density
   * cutoffs squared with a margin over the float rounding of the trimming. */
  int sub[3], sub_shift[3], nf[3], row_scan, trim_any; /* sub = 1 << sub_shift */
  /* tail: the static frozen particles sit in the slots after every other (the static tail, sorted
   * by bin once per upload; cuda_sim.tail_on), their bin starts at cell_start + tail_off (= ncell +
   * 1); every scan visits a row's slots of both ranges. */
  int tail, tail_off;
  meso_real fine_w[3], inv_fine_w[3], scan_cut2, scan_rd2;
  struct dev_coef coef[SCENE_MAX_SPECIES][SCENE_MAX_SPECIES];
};

/* Packed copies for the pair passes, rebuilt every step after the sort: the position relative to
 * the lower corner of the particle's own bin (small numbers, so single precision keeps ~1e-7 of a
 * bin width in any box size) with the species, and the velocity the thermostat sees. One 16-byte
 * load per candidate in single precision. */
#ifdef MESO_REAL_FLOAT
struct __align__(16) dev_pos {
  float x, y, z;
  int species;
};
struct __align__(16) dev_vel {
  float x, y, z, pad;
};
#else
struct __align__(32) dev_pos {
  double x, y, z;
  long long species;
};
struct __align__(32) dev_vel {
  double x, y, z, pad;
};
#endif

/* One particle field set (double-buffered for the cell sort). */
struct dev_fields {
  int64_t *id;
  int32_t *species;
  double *x[3], *v[3], *f[3], *vpred[3];
};

/* Device record of problems, one slot per kind (the first particle that claimed it). */
struct dev_problem {
  int kind, at_drift;
  unsigned long long count[CUDA_PROBLEM_KINDS];
  int claimed[CUDA_PROBLEM_KINDS];
  long long id[CUDA_PROBLEM_KINDS];
  double x[CUDA_PROBLEM_KINDS][3];
  double value[CUDA_PROBLEM_KINDS];
};

#define THERMO_SUMS 17
#define THERMO_BLOCKS 512

struct cuda_sim {
  struct dev_params prm;
  int n, cap;
  struct dev_fields a, b; /* a: current; b: scratch for the sort (not allocated in the compact
                             mode on one rank: the fields go through sort_scratch one by one) */
  /* Memory mode (docs/engine-cuda.md "Memory modes"): 0 fast (per-step neighbour lists, ~790 B per
   * particle); 1 compact (no lists: the force and wall-field passes scan the bins again; on one
   * rank the sort gathers one field at a time through sort_scratch, <= 200 B per particle). */
  int compact;
  int memory_request;   /* enum scene_gpu_memory: auto, fast or compact (auto: compact only when the
                         fast mode's memory would not fit) */
  double *sort_scratch; /* [cap] 8 bytes per slot (compact, one rank) */
  meso_real *rho;       /* [cap] (density pass only) */
  double *virial;       /* [6 cap] per-particle virial (on request) */
  int virial_cap;
  uint32_t *key, *key_sorted; /* cell of each particle */
  int *iota, *perm;
  int *cell_start;  /* [ncell + 1] */
  int *gcell_start; /* [ncell + 1] ghosts (multi), slots relative to n */
  int n_ghost;      /* ghosts after the n owned particles (multi) */
  int n_boundary;   /* owned particles sent out as ghosts: slots perm[0..n_boundary) (multi) */
  int n_leaving;    /* leavers still counted in n until the sort phase drops them (multi) */
  int leaver_flags_ready; /* the kick-drift flagged the leavers in iota (multi) */
  int *counter;           /* [1] device counter (boundary selection) */
  meso_real *rho_stage;   /* [cap] densities on their way to or from the host (multi) */
  struct dev_pos *pos;    /* [cap] packed positions (cell order) */
  struct dev_vel *vel;    /* [cap] packed thermostat velocities (thermostat only) */
  /* Per-step neighbour lists written by the density pass (cuda_density.cu): entry k of particle i
   * at nbr[nbr_index(i, k, cap)], slot | bin-offset code << NBR_SLOT_BITS, partners within the
   * largest cutoff in traversal order. */
  uint32_t *nbr;
  int *nbr_count, *nbr_most; /* [cap]; [1] the longest list of the last pass */
  int nbr_stride;
  struct dev_pos *pos0;   /* [cap] packed positions when the lists were built (skin > 0) */
  int *rebuild;           /* [1] set by the pack kernel: a particle moved more than skin / 2 */
  int lists_valid;        /* the lists were built for the current particle order (cleared by a
                             sort, an upload or arrivals) */
  long n_builds, n_steps; /* list builds and steps since creation (reported by the benchmark) */
  void *sort_tmp;
  size_t sort_tmp_bytes;
  double *block_virial; /* [6 * blocks] pair virial per force block (reduced in cuda_thermo.cu) */
  int block_virial_cap, n_force_blocks;
  int want_pressure;  /* the next force passes fill block_virial (a thermo sample follows) */
  int pressure_valid; /* block_virial belongs to the last force pass */
  uint64_t last_force_step;
  /* Several ranks: the interior passes run while the host exchanges (MDPORE_CUDA_OVERLAP). */
  int overlap;
  /* One rank, neighbour lists, frozen particles present: the force pass runs over the mobile slots
   * only (cub select in slot order; their count stays on the device), so that no lane of its warps
   * holds a frozen particle, which computes no force of its own; the frozen particles' f is zeroed
   * by a small kernel instead. MDPORE_CUDA_MOBILE_SLOTS=0 turns it off (bench/RESULTS.md). */
  int mobile_slots_on;
  int *mobile_slot; /* room of mobile_slot_bytes (cuda_dev_room) */
  size_t mobile_slot_bytes;
  int *mobile_count; /* [1] */
  /* The static tail (one rank, lists, no skin, static frozen species and no moving ones; off with
   * MDPORE_CUDA_TAIL=0): the first sort after an upload puts the static frozen particles last, in
   * bin order, into both field sets; later sorts, gathers and kick-drifts cover only the n_dyn
   * slots before them, which never change. prm.tail: that first sort is done (cleared by an
   * upload, the test fault hook and the compact mode). With the tail the frozen particles are a
   * contiguous part already, so mobile_slots_on is 0. */
  int tail_on, n_dyn;
  /* The tail's static density part (its tail partners within rd), per tail slot, summed once per
   * placement (tail_rho_ready); the density pass then scans only the other slots for them. */
  meso_real *tail_rho;
  size_t tail_rho_bytes;
  int tail_rho_ready, tail_rho_on; /* (on unless MDPORE_CUDA_TAIL_RHO=0) */
  /* mobile_slot holds this build's partition (the mobile slots, then the frozen ones): made by the
   * density pass, used again by the force pass; cleared by a sort or an upload. */
  int mobile_slots_ready;
  /* Pinned host staging buffer of the halo transfers (cuda_halo.cu). */
  char *pinned;
  size_t pinned_bytes;
  /* Ghosts packed on the device (cuda_halo_device.cu; one axis cut between ranks): the counts of
   * this step (sent down, sent up, received from above, received from below), the records on
   * their way out and in, the selection's scratch, and the event that ends a packed download. */
  int halo_n[4];
  int *halo_count_dev; /* [3]: the two sets' sizes, the boundary slots' count */
  /* The boundary slots (key 0) of this step, for the boundary parts of the split passes (NULL
   * until the device selection made them: the passes then run over every slot). */
  int *bslots;               /* storage of the selected list */
  const int *boundary_slots; /* the list in use: bslots, or perm when the send sets cover it */
  int n_bslots;
  size_t bslots_cap;
  char *ghost_send_dev, *ghost_recv_dev;
  size_t ghost_send_cap, ghost_recv_cap, pinned_send_bytes;
  void *select_tmp;
  size_t select_tmp_bytes;
  cudaEvent_t packed;
  int packed_made;
  /* The halo copies run on their own stream, so that the interior passes on the default stream do
   * not wait for them (and they not for the interior passes): ready (default -> copies: the data
   * to copy is written), copied (copies -> default: the data arrived). */
  cudaStream_t copies;
  cudaEvent_t ready, copied;
  /* The ghost densities were put on the copy stream (cuda_halo_rho_unpack): the boundary forces
   * follow them there, concurrent with the interior forces (cuda_halo_forces). */
  int rho_on_copies;
  /* Migration as records (cuda_halo_device.cu, one axis cut): the leavers' and arrivals' records
   * on the device and in a pinned buffer of their own. */
  char *mig_dev, *mig_pinned;
  void *mig_pinned_dev; /* mig_pinned as the device sees it (mapped; the leavers' pack writes it) */
  size_t mig_dev_cap, mig_pinned_bytes;
  /* Small pinned host room for the counts a host decision waits for (one synchronising copy each
   * time; cuda_counts_down). */
  int *counts_pinned;
  /* GPU idle probes (MDPORE_CUDA_IDLE=1; cuda_util.cu): per section, the events that open and
   * close it, its state (0 none, 1 opened, 2 closed) and the device time between them. */
  int idle_on;
  cudaEvent_t idle_ev[2 * CUDA_IDLE_SECTIONS];
  int idle_state[CUDA_IDLE_SECTIONS];
  double idle_ms[CUDA_IDLE_SECTIONS];
  long idle_n[CUDA_IDLE_SECTIONS];
  /* This step's passes were split in an interior and a boundary part (key holds the flags). */
  int split_passes;
  /* One rank with a skin: the sort phase left the choice (keep the lists or sort and rebuild) to
   * the neighbour phase, which decides after the prediction, as the displacement check needs it. */
  int lists_maybe_valid;
  int sort_pending; /* a step's sort, done by the neighbour phase (after the prediction) */
  /* One rank: the kick-drift wrote this step's sort keys (key, iota) for the particles as they
   * are; cleared by the sort that takes them and by anything that changes the particles besides
   * the step (an upload, the test fault hook). */
  int keys_ready;
  double *thermo_part; /* [THERMO_SUMS * THERMO_BLOCKS] then [THERMO_SUMS] */
  struct dev_problem *problem;
  /* device bytes held: fixed_bytes (the effect arrays, bin starts and small records made once at
   * creation) plus the arrays made for the particles (reset to fixed_bytes when they are made
   * again); the benchmark's bytes per particle */
  size_t bytes, fixed_bytes;
  char device_name[256];
  /* Device copies of the plan's per-particle effect arrays (plan.arrays), pointed at by prm.pe. */
  void *effect_arrays[PLAN_MAX_ARRAYS];
  int n_effect_arrays;
  /* wall_boundary: phi and grad phi per owned slot (cuda_wall_field.cu), pointed at by
   * prm.pe.wall_boundary.field; NULL without the effect. */
  wall_field_t *wall_field;
  /* Density cache of static frozen particles (plan.density_cache, one rank; cuda_density.cu): the
   * static-static part of each one's density by particle id (NaN: not computed yet), and per bin
   * whether it holds a mobile or moving particle this build. */
  meso_real *rho_static;
  long long rho_static_len;
  int *cell_dynamic;
};

/* Entry k of the list of particle i: chunks of NBR_CHUNK entries, chunk-major (chunk c of particle
 * i at (c cap + i) NBR_CHUNK). The density pass writes a particle's chunk with two 16-byte stores
 * (one sector) instead of eight scattered 4-byte ones; a warp's reads at one k stay within 32
 * sectors that serve the next 7 entries from L1. (Measured: entry-major k cap + i and one row per
 * particle, bench/RESULTS.md.) Strides are multiples of NBR_CHUNK. */
#define NBR_CHUNK 8
static_assert(NBR_CHUNK == 8, "nbr_for_each and the density pass's flush take 8 entries a chunk");
__device__ __forceinline__ size_t nbr_index(int i, int k, int cap) {
  return ((size_t)(k / NBR_CHUNK) * (size_t)cap + (size_t)i) * NBR_CHUNK + (size_t)(k % NBR_CHUNK);
}

/* f(e) for the m entries of particle i's list, in order: each chunk read with two 16-byte loads
 * (a chunk's room exists past m: strides are multiples of NBR_CHUNK), the entries taken from
 * registers, so the pair loops pay no index arithmetic and one load per four entries. */
template <class F>
__device__ __forceinline__ void nbr_for_each(const uint32_t *__restrict__ nbr, int i, int m,
                                             int cap, F &&f) {
  const uint4 *chunk = (const uint4 *)(nbr + (size_t)i * NBR_CHUNK);
  const size_t chunk_step = (size_t)cap * NBR_CHUNK / 4; /* uint4 from chunk c to c + 1 */
  for (int k0 = 0; k0 < m; k0 += NBR_CHUNK, chunk += chunk_step) {
    const uint4 lo = chunk[0], hi = chunk[1];
    const uint32_t e[NBR_CHUNK] = {lo.x, lo.y, lo.z, lo.w, hi.x, hi.y, hi.z, hi.w};
    const int left = m - k0;
#pragma unroll
    for (int k = 0; k < NBR_CHUNK; k++)
      if (k < left) f(e[k]);
  }
}

/* cuda_util.cu */
/* 0 when e is cudaSuccess; else -1 after "mdpore: CUDA error in WHAT: ..." on stderr (a memory
 * error with the device's free memory and what to try; the error cleared when it is not sticky). */
int cuda_check(cudaError_t e, const char *what);
/* The same for an allocation of `bytes` (where: "GPU" or "host, pinned"): the message names it, its
 * size, the free memory and what to try. */
int cuda_check_alloc(cudaError_t e, const char *what, size_t bytes, const char *where);
/* Device memory of `bytes`, counted in g->bytes; a failure is reported by cuda_check_alloc under
 * the name of the pointer (cuda_alloc's macro passes its text). 0 or -1. */
int cuda_alloc_named(struct cuda_sim *g, void **ptr, size_t bytes, const char *what);
#define cuda_alloc(g, ptr, bytes) cuda_alloc_named((g), (ptr), (bytes), #ptr)
void cuda_free_ptr(struct cuda_sim *g, void **ptr);
int cuda_reserve(struct cuda_sim *g, int n);
int cuda_grow(struct cuda_sim *g, int need);
int cuda_set_virial(struct cuda_sim *g, int on);
int cuda_nbr_reserve(struct cuda_sim *g, int stride);
/* Device room of at least bytes in *buf, *cap its size (grown with a margin; contents not kept).
 * 0 or -1. */
int cuda_dev_room(struct cuda_sim *g, char **buf, size_t *cap, size_t bytes);
/* Slots [k, k + m) of every field of src into dst (device to device; vpred where src has it;
 * what names the step in an error). 0 or -1. */
int cuda_copy_fields(struct dev_fields *dst, const struct dev_fields *src, size_t k, size_t m,
                     const char *what);
/* The cub selections' temporary storage, at least need bytes (g->select_tmp). 0 or -1. */
int cuda_select_room(struct cuda_sim *g, size_t need);
/* The slots i < n with flag[i] != 0, in slot order, into out; their count into *count_dev (device).
 * Queued on the default stream (cub select; scratch grown as needed). 0 or -1. */
int cuda_select_slots(struct cuda_sim *g, const int *flag, int *out, int *count_dev, int n,
                      const char *what);
/* Switch to the compact mode (lists, and on one rank the sort's second field set, freed; the
 * particles kept). 0 or -1. */
int cuda_go_compact(struct cuda_sim *g, const char *why);

/* cuda_halo.cu: the pinned host buffer of the halo transfers, grown to at least bytes (contents
 * not kept; the caller makes sure no copy from or to it is in flight). NULL on failure. */
char *cuda_pinned(struct cuda_sim *g, size_t bytes);
/* cuda_halo.cu: k ints (k <= 4) from the device into out, after the work queued on the default
 * stream (one synchronising copy through pinned memory). */
int cuda_counts_down(struct cuda_sim *g, int *out, const int *dev, int k, const char *what);
/* cuda_util.cu: MDPORE_CUDA_TIGHT_ROOM=1 (tests): buffers start with almost no spare room, so that
 * their growth paths run. */
int cuda_tight_room(void);
/* cuda_halo.cu: the leavers' slots into perm[0, *g->counter) (g->n > 0), nothing downloaded. */
int cuda_leavers_select(struct cuda_sim *g);
/* cuda_halo.cu: out[k] = rho[perm[k]] for k < n (the boundary densities in the send order), and
 * rho[n0 + k] = in[perm[n0 + k]] for k < ng (arrived densities into the ghost slots through the
 * ghost sort's permutation), queued on stream. */
void cuda_rho_gather(int n, const int *perm, const meso_real *rho, meso_real *out,
                     cudaStream_t stream);
void cuda_rho_scatter(int n0, int ng, const int *perm, const meso_real *in, meso_real *rho,
                      cudaStream_t stream);

/* cuda_cells.cu: sort the particles by cell and build cell_start. */
/* with_f: carry the forces along (they are needed after the sort only when kept from a checkpoint
 * or when particles leave for another rank; a step recomputes them). pack: the packed copies
 * (cuda_pack) made too, on one rank by the sort's gather itself. */
int cuda_sort_cells(struct cuda_sim *g, int with_f, int pack);
int cuda_sort_ghosts(struct cuda_sim *g);
/* Pack positions (bin-relative) and thermostat velocities for the pair passes (after the
 * prediction). */
void cuda_pack(struct cuda_sim *g);
void cuda_pack_range(struct cuda_sim *g, int i0, int i1);
/* Pack and, with a skin, check the displacement since the last build: 1 when the lists must be
 * rebuilt (always 1 without a skin), 0 when they still hold, -1 on a CUDA error. */
int cuda_pack_check(struct cuda_sim *g);

/* cuda_density.cu (densities + neighbour lists; 0 or -1) / cuda_force.cu */
int cuda_density_pass(struct cuda_sim *g);
/* Densities over the lists of the last build (skin > 0, lists still valid). */
void cuda_density_from_lists(struct cuda_sim *g);
/* Copy rho of slots [i0, i1) into the thermostat velocity's spare lane (vel.pad) for the force
 * pass. */
void cuda_rho_to_vel(struct cuda_sim *g, int i0, int i1, cudaStream_t stream);
/* Several ranks with overlap: interior part first (no ghosts needed), then the boundary part. */
int cuda_density_pass_interior(struct cuda_sim *g);
int cuda_density_pass_rest(struct cuda_sim *g);
void cuda_force_pass_part(struct cuda_sim *g, uint64_t step, int want_virial, int keep_forces,
                          int part, cudaStream_t stream);
int cuda_force_boundary_rows_fit(const struct cuda_sim *g);
/* finish (one rank, a step; not with keep_forces): the force threads also end their particles'
 * steps (cuda_finish.cuh), so no finishing kernel follows. */
void cuda_force_pass(struct cuda_sim *g, uint64_t step, int want_virial, int keep_forces,
                     int finish);
/* cuda_force.cu: the mobile slots first, then the frozen ones, into g->mobile_slot (once per build,
 * one rank with lists). 0 or -1. */
int cuda_mobile_partition(struct cuda_sim *g);
/* cuda_wall_field.cu: the wall field of every owned particle from the lists of this step. */
void cuda_wall_field(struct cuda_sim *g);

/* cuda_integrate.cu */
void cuda_kick_drift(struct cuda_sim *g);
void cuda_predict(struct cuda_sim *g, int setup);
void cuda_finish_forces(struct cuda_sim *g, int add_body, int kick);
int cuda_problem_fetch(struct cuda_sim *g, cuda_problem_t *pr);

/* Record a problem from device code (first particle of each kind keeps its slot). */
__device__ __forceinline__ void dev_note(struct dev_problem *pb, int kind, int at_drift, int64_t id,
                                         double x0, double x1, double x2, double value) {
  atomicAdd(&pb->count[kind], 1ull);
  if (atomicCAS(&pb->claimed[kind], 0, 1) == 0) {
    pb->id[kind] = (long long)id;
    pb->x[kind][0] = x0;
    pb->x[kind][1] = x1;
    pb->x[kind][2] = x2;
    pb->value[kind] = value;
    if (at_drift) atomicMax(&pb->at_drift, 1);
  }
  atomicMax(&pb->kind, kind);
}

#endif
