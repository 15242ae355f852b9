/* The CUDA backend's C interface (used by its host glue, cuda_glue.c and cuda_glue_halo.c, which
 * fill the ops table of backend/backend.h). One GPU
 * holds the particles of one rank between steps; the host sees them only through cuda_sim_download
 * (outputs, checkpoints) and, with several ranks, the boundary particles of the halo exchange.
 * Pair math comes from meso/physics (*.h), compiled for the device with MESO_REAL_FLOAT unless the
 * build sets MDPORE_DOUBLE. On one rank the cells wrap periodically on the device (no ghosts). */
#ifndef MESO_BACKEND_CUDA_BACKEND_H
#define MESO_BACKEND_CUDA_BACKEND_H

#include "backend/backend.h"
#include "domain/particles.h"
#include "effects/plan.h"
#include "scene/scene.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cuda_sim cuda_sim_t;

/* Problems the device reports (same order of seriousness as enum step_problem_kind). */
enum cuda_problem_kind {
  CUDA_OK = 0,
  CUDA_NONFINITE = 2,
  CUDA_TOO_FAST = 3,
  CUDA_LOST = 4,
  CUDA_PROBLEM_KINDS = 8
};

typedef struct {
  int kind;     /* enum cuda_problem_kind (the most serious one seen) */
  int at_drift; /* 1: found after the drift (the CPU path reports it at step + 1 before forces) */
  int64_t id;
  double x[3];
  double value;
  long count; /* particles with a problem of this kind */
} cuda_problem_t;

/* Number of visible CUDA devices; 0 with the reason in why (no driver, no device, ...). */
int cuda_device_count(char *why, size_t len);

/* Device state for the scene's box. NULL with a message in err. */
cuda_sim_t *cuda_sim_create(const plan_t *plan, const scene_t *scene, const double sub_lo[3],
                            const double sub_hi[3], const int dims[3], char *err, size_t len);
void cuda_sim_destroy(cuda_sim_t *g);

/* Copy the n_local owned particles of p (id, species, x, v, f) to the device. 0 or -1. */
int cuda_sim_upload(cuda_sim_t *g, const particles_t *p);
/* Copy the device state back into p (n_local, order of the device; rho, vpred, virial when
 * allocated on the host). p must have room (pstore_reserve). 0 or -1. */
int cuda_sim_download(cuda_sim_t *g, particles_t *p);
/* Number of particles on the device. */
int cuda_sim_count(const cuda_sim_t *g);

/* The phases on one rank (cuda_step.cu; the glue in cuda_glue.c calls them in the plan's order):
 * kick + drift + constraints + wrap; sort by cell (set-up: with the loaded forces when keep_forces;
 * a step with a skin may keep the lists: cuda_sim_neighbours decides); prediction (v~ = v at
 * set-up); pack + neighbour scan with the densities; the pair forces at step index `step` (finish:
 * the pass also does the finishing kernel's work with add_particle and kick, so the caller skips
 * the finishing kernel); the finishing kernel (particle forces when add_particle, finite check,
 * second kick when kick); the problem record of the step (synchronises). Each 0 or -1. */
int cuda_sim_kick_drift(cuda_sim_t *g, int want_virial);
int cuda_sim_sort(cuda_sim_t *g, int setup, int keep_forces, int want_virial);
int cuda_sim_predict(cuda_sim_t *g, int setup);
int cuda_sim_neighbours(cuda_sim_t *g);
int cuda_sim_pair_forces(cuda_sim_t *g, long step, int want_virial, int keep_forces, int finish);
int cuda_sim_finish(cuda_sim_t *g, int add_particle, int kick);
int cuda_sim_fetch_problems(cuda_sim_t *g, cuda_problem_t *pr);

/* Several ranks (one GPU each; cuda_halo.cu, cuda_step.cu), in step order: kick-drift; find the
 * leavers (outside the subdomain; *m of them, left in their slots); copy them into `out` (host); add
 * the arrivals after the owned slots; sort by bin, the leavers last and dropped (the step's one
 * sort of the owned particles); predict; boundary set into hb (host: id, species, x,
 * thermostat velocity in v); ghosts of hb (after ghosts_build) to the device; densities; boundary
 * densities out (field[0..n_boundary)), ghost densities in (host ghost order); forces (then
 * cuda_sim_finish and cuda_sim_fetch_problems as on one rank). */
int cuda_halo_kick_drift(cuda_sim_t *g);
int cuda_halo_find_leavers(cuda_sim_t *g, int *m);
int cuda_halo_take_leavers(cuda_sim_t *g, int m, particles_t *out);
int cuda_halo_add_owned(cuda_sim_t *g, const particles_t *in);
int cuda_halo_resort(cuda_sim_t *g, int keep_forces);
int cuda_halo_predict(cuda_sim_t *g, int setup);
int cuda_halo_boundary(cuda_sim_t *g, particles_t *hb);
int cuda_halo_set_ghosts(cuda_sim_t *g, const particles_t *hb);
/* Overlap: launch the interior densities before ghosts_build, the interior forces before the
 * density halo (no-ops when MDPORE_CUDA_OVERLAP=0); cuda_halo_density / cuda_halo_forces then do
 * the boundary particles (or everything, without overlap). */
int cuda_halo_density_early(cuda_sim_t *g);
int cuda_halo_density(cuda_sim_t *g);
int cuda_halo_forces_early(cuda_sim_t *g, long step, int want_virial, int keep_forces);
int cuda_halo_rho_out(cuda_sim_t *g, double *field);
int cuda_halo_rho_in(cuda_sim_t *g, const double *ghost_rho);
int cuda_halo_forces(cuda_sim_t *g, long step, int want_virial, int keep_forces);

/* Ghosts packed on the device (cuda_halo_device.cu), used when exactly one axis is cut between
 * ranks: only the packed boundary records cross to the host, straight into MPI from a pinned
 * buffer, and come back as the neighbours' ghosts (no host particle arrays, no host ghost stages).
 * In step order: select (the boundary flags of the overlap split, the sets within the cutoff of
 * the lower and the upper face of `axis`, their sizes into n_send[0..1]; waits for the device);
 * pack (records of both sets, the periodic shift added, downloaded into the pinned buffer
 * asynchronously; room for n_recv records to arrive; *send and *recv point into the buffer);
 * wait (for that download only); unpack (the n_recv arrived records to the device as ghosts,
 * from above first, then from below: n_from_up, n_from_down). The density halo: rho_pack (the
 * boundary densities in the records' order, downloaded asynchronously), wait, rho_unpack. Record
 * layout: 64 bytes (id, species, pad, x[3], v[3]), as the CPU path's ghosts.c. 0 or -1. */
#define CUDA_GHOST_RECORD_BYTES 64
int cuda_halo_select(cuda_sim_t *g, int axis, int send_lo, int send_hi, int n_send[2]);
int cuda_halo_pack(cuda_sim_t *g, int axis, double shift_lo, double shift_hi, int n_from_up,
                   int n_from_down, void **send, void **recv);
int cuda_halo_wait_packed(cuda_sim_t *g);
int cuda_halo_unpack(cuda_sim_t *g);
int cuda_halo_rho_pack(cuda_sim_t *g, void **send, void **recv);
int cuda_halo_rho_unpack(cuda_sim_t *g);
/* This step's counts: sent down, sent up, received from above, received from below. */
void cuda_halo_counts(const cuda_sim_t *g, int n[4]);
/* Migration as records (one axis cut): the leavers found (as cuda_halo_find_leavers does) and
 * packed as migrant_t records (slot order) straight into pinned host memory, their count in *m,
 * after one synchronising copy (two when the buffer must grow); *out points at them (valid until
 * the next call). Then the m records in (stayers and arrivals, host order) appended after the owned
 * slots in one upload, as cuda_halo_add_owned does with host arrays. 0 or -1. */
int cuda_halo_take_leaving(cuda_sim_t *g, int *m, const void **out);
int cuda_halo_add_migrants(cuda_sim_t *g, const void *in, int m);

/* GPU idle probes (MDPORE_CUDA_IDLE=1, else no-ops): open (end 0) and close (end 1) section s on
 * the default stream; the device time between the two marks, summed over the steps, is read (ms)
 * and reset by cuda_idle_read. Sections: */
enum { CUDA_IDLE_MIGRATE, CUDA_IDLE_SELECT, CUDA_IDLE_STEP_END, CUDA_IDLE_SECTIONS };
void cuda_idle_mark(cuda_sim_t *g, int s, int end);
void cuda_idle_read(cuda_sim_t *g, double ms[CUDA_IDLE_SECTIONS], long n[CUDA_IDLE_SECTIONS],
                    int reset);

/* Announce whether the next steps end in a thermo sample: only then does the force pass sum the
 * pair virial (a sample after a step without it reruns the pair pass for the virial alone). */
void cuda_sim_want_pressure(cuda_sim_t *g, int on);
/* Sort and rebuild the lists in the next step (before a checkpoint: bitwise restarts). */
void cuda_sim_rebuild_lists(cuda_sim_t *g);
/* List builds and steps since creation, the Verlet skin in use (rc units). */
void cuda_sim_list_stats(const cuda_sim_t *g, long *builds, long *steps, double *skin);

/* Local sums for sim_thermo in double, in the CPU path's order of quantities: N_mobile, KE, px, py,
 * pz, sum m v_a v_b (6), pair virial (6). 0 or -1. */
int cuda_sim_thermo_sums(cuda_sim_t *g, double sums[17]);
/* Local sums for sim_flux_sums along `axis`: per species s, mobile count sums[s] and sum of
 * v_axis sums[MESO_MAX_SPECIES + s]. 0 or -1. */
int cuda_sim_flux_sums(cuda_sim_t *g, int axis, double sums[2 * MESO_MAX_SPECIES]);

/* Test-only fault hook: set (add = 0) or add to (add = 1) component `axis` of the position (field
 * 0) or velocity (field 1) of the owned particle `id`, on the device (one kernel over the owned
 * particles, then a synchronisation). 0 or -1. */
int cuda_sim_fault_write(cuda_sim_t *g, int64_t id, int field, int axis, double value, int add);
/* Flooding: species from -> to in the periodic slab [lo, hi) along axis (box_lo, box_len: the box
 * along it); *changed: how many. 0 or -1 (CUDA error printed). */
int cuda_sim_recolor(cuda_sim_t *g, int axis, double lo, double hi, double box_lo, double box_len,
                     int from, int to, long *changed);

/* 1 when the halo steps overlap interior work with the host exchanges. */
int cuda_sim_overlap(const cuda_sim_t *g);
/* The memory mode in use: "fast" (neighbour lists) or "compact" (none; docs/engine-cuda.md). */
const char *cuda_sim_memory_mode(const cuda_sim_t *g);
/* Bytes of device memory this state holds. */
size_t cuda_sim_bytes(const cuda_sim_t *g);
/* The device plan's bytes per particle of a plan on nranks ranks in memory mode gpu_memory (enum
 * scene_gpu_memory; auto counts as fast), the slot margin included (mdpore run --explain). */
double cuda_device_bytes_per_particle(const plan_t *plan, int nranks, int gpu_memory);
/* Whether the plan allows the static tail (static frozen species, no moving ones); the device
 * adds one rank, lists, no skin (cuda_sim_create). */
int cuda_plan_static_tail(const plan_t *plan);
/* Static frozen particles kept in the static tail (sorted once, never drifted; docs/engine-cuda.md
 * step 2), 0 when the tail is off. */
long cuda_sim_static_tail(const cuda_sim_t *g);
/* 1 when every pair of species has the same coefficients and the every-step force kernel reads
 * them at fixed offsets (dev_params.coef_uniform), 0 otherwise. */
int cuda_sim_coef_uniform(const cuda_sim_t *g);
/* 1 when the pair math was built in double (MDPORE_DOUBLE), 0 for single precision. */
int cuda_sim_double_precision(void);
/* Name of the device (for summaries and the benchmark). */
const char *cuda_sim_device_name(const cuda_sim_t *g);

/* The device state of a simulation running on the CUDA backend (st->impl of cuda_glue.c), for
 * benchmarks and tests; NULL for another backend. */
cuda_sim_t *cuda_backend_device(const sim_state_t *st, const char *backend_name);

#ifdef __cplusplus
}
#endif

#endif
