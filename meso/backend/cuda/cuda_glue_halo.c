/* The CUDA backend's ops on several MPI ranks, one GPU each: the device keeps the
 * owned particles; each step only the leavers and the boundary set (owned particles within the
 * ghost cutoff of a face) come to the host, where the CPU path's own exchanges run on them:
 * migration (migrate.c), the 3-stage ghost build with periodic images (ghosts.c) and the density
 * halo (ghosts_sync_scalar). So the images, stages and messages are the CPU path's; the ghosts go
 * back to the device after the owned particles (docs/engine-cuda.md). Halo data is staged through
 * pinned host buffers: the ghost build itself runs on the host, so it needs the boundary set there
 * even with a CUDA-aware MPI (Open MPI 4.1 on the GPU machines is not one). While the host
 * exchanges, the GPU computes the interior particles (cuda_step.cu). Every phase enters its
 * collective exchange even after a local failure (st->failed), so the ranks stay matched. */
#include "backend/cuda/cuda_glue.h"
#include "domain/particle_store.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#if defined(OPEN_MPI) && OPEN_MPI
#include <mpi-ext.h> /* MPIX_Query_cuda_support */
#endif

/* Whether the MPI library says it is CUDA-aware: "yes", "no" or "unknown" (not Open MPI). */
static const char *mpi_cuda_aware(void) {
#if defined(MPIX_CUDA_AWARE_SUPPORT) && MPIX_CUDA_AWARE_SUPPORT
  return MPIX_Query_cuda_support() ? "yes" : "no";
#elif defined(MPIX_CUDA_AWARE_SUPPORT)
  return "no";
#else
  return "unknown";
#endif
}

static int ready(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  if (c->halo_ready) return 0;
  if (pstore_init(&c->halo_b, 0, 0) || pstore_init(&c->halo_m, 0, 0)) return -1;
  /* Axes not cut between ranks wrap on the device: no ghost images along them. */
  c->halo_dc = st->dc;
  for (int d = 0; d < 3; d++)
    if (st->dc.dims[d] == 1) c->halo_dc.nbr[d][0] = c->halo_dc.nbr[d][1] = MPI_PROC_NULL;
  c->halo_ready = 1;
  if (st->dc.rank == 0)
    printf("mdpore: GPU halo staged through pinned host memory (MPI CUDA-aware: %s); interior "
           "passes overlap the exchanges: %s\n",
           mpi_cuda_aware(), cuda_sim_overlap(c->g) ? "yes" : "no (MDPORE_CUDA_OVERLAP=0)");
  return 0;
}

/* The host halo buffers, then the state both tables share. */
static void destroy(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  if (c && c->halo_ready) {
    pstore_free(&c->halo_b);
    pstore_free(&c->halo_m);
    xbuf_free(&c->mig_in);
    free(c->halo_rho);
    c->halo_rho = NULL;
    c->halo_ready = 0;
  }
  cuda_glue_destroy(st);
}

static int keep_forces(const sim_state_t *st) {
  return st->in_setup && st->forces_loaded;
}

static int setup_begin(sim_state_t *st) {
  return ready(st) || cuda_glue_setup_begin(st) ? -1 : 0;
}

static int device_halo_axis(const sim_state_t *st);

/* One axis cut: the leavers as records in one download, migrate_records (collective: the CPU
 * path's directions, wraps and loss tests), the records that stay and arrive in one upload. */
static int migrate_on_device(sim_state_t *st, int axis) {
  cuda_glue_t *c = cuda_glue(st);
  int m = 0;
  const void *out = NULL;
  cuda_idle_mark(c->g, CUDA_IDLE_MIGRATE, 0);
  int rc = st->failed || cuda_halo_take_leaving(c->g, &m, &out);
  if (rc) m = 0;
  const int n_in = migrate_records(&st->dc, axis, out, m, &st->sbuf, &st->rbuf, &c->mig_in, &c->mr);
  rc = rc || c->mr.out_of_memory || cuda_halo_add_migrants(c->g, c->mig_in.data, n_in);
  cuda_idle_mark(c->g, CUDA_IDLE_MIGRATE, 1);
  return rc ? -1 : 0;
}

/* Leavers out of the device, through the CPU path's migration (collective), arrivals in. */
static int migrate(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  /* MDPORE_CUDA_HOST_MIGRATE=1: the host arrays' path even with one axis cut (for comparison) */
  const char *host = getenv("MDPORE_CUDA_HOST_MIGRATE");
  const int axis = host && !strcmp(host, "1") ? -1 : device_halo_axis(st);
  if (axis >= 0) return migrate_on_device(st, axis);
  particles_t *m = &c->halo_m;
  int n_leave = 0;
  int rc = st->failed || cuda_halo_find_leavers(c->g, &n_leave) || pstore_reserve(m, n_leave + 1) ||
           cuda_halo_take_leavers(c->g, n_leave, m);
  if (rc) m->n_local = 0;
  migrate_particles(&st->dc, m, &st->sbuf, &st->rbuf, &c->mr); /* collective */
  return rc || c->mr.out_of_memory || cuda_halo_add_owned(c->g, m) ? -1 : 0;
}

static int sort(sim_state_t *st) {
  if (st->failed) return 0;
  return cuda_halo_resort(cuda_glue(st)->g, keep_forces(st));
}

/* The one axis cut between ranks when the ghosts can be packed on the device (the others wrap on
 * the device), else -1: several axes cut (edge and corner ghosts: the CPU path's stages), or
 * MDPORE_CUDA_HOST_HALO=1 (the host path, kept for comparison: bench/RESULTS.md). */
static int device_halo_axis(const sim_state_t *st) {
  const char *host = getenv("MDPORE_CUDA_HOST_HALO");
  if (host && !strcmp(host, "1")) return -1;
  int axis = -1, cut = 0;
  for (int d = 0; d < 3; d++)
    if (st->dc.dims[d] > 1) {
      axis = d;
      cut++;
    }
  return cut == 1 ? axis : -1;
}

/* Every rank's local failure, agreed (collective): all ranks skip the exchange together. */
static int any_failed(const sim_state_t *st, int rc) {
  int any = rc != 0;
  MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_LOR, st->dc.cart);
  return any;
}

/* Send n_down items of `size` bytes from send to the rank below and receive n_up from the rank
 * above into recv, then n_up_send from send + n_down items up and n_from_down from below after
 * recv's first part (the CPU path's ghosts.c order: from above first). Collective over the pair. */
static void exchange_sets(const sim_state_t *st, int axis, size_t size, const char *send,
                          int n_down, int n_upward, char *recv, int n_from_up, int n_from_down,
                          int tag) {
  const int down = st->dc.nbr[axis][0], up = st->dc.nbr[axis][1];
  MPI_Sendrecv(send, (int)(n_down * size), MPI_BYTE, down, tag, recv, (int)(n_from_up * size),
               MPI_BYTE, up, tag, st->dc.cart, MPI_STATUS_IGNORE);
  MPI_Sendrecv(send + n_down * size, (int)(n_upward * size), MPI_BYTE, up, tag + 1,
               recv + n_from_up * size, (int)(n_from_down * size), MPI_BYTE, down, tag + 1,
               st->dc.cart, MPI_STATUS_IGNORE);
}

/* Ghosts packed on the device (cuda_halo_device.cu): the sets' sizes to the neighbours, the
 * records down (the interior densities launched meanwhile), straight through MPI, up as ghosts. */
static int ghosts_on_device(sim_state_t *st, int axis) {
  cuda_glue_t *c = cuda_glue(st);
  const int down = st->dc.nbr[axis][0], up = st->dc.nbr[axis][1];
  int n_send[2] = {0, 0}, n_recv[2] = {0, 0}; /* recv: from above, from below */
  cuda_idle_mark(c->g, CUDA_IDLE_SELECT, 0);
  int rc = st->failed ||
           cuda_halo_select(c->g, axis, down != MPI_PROC_NULL, up != MPI_PROC_NULL, n_send);
  if (rc) n_send[0] = n_send[1] = 0;
  /* the four counts in flight together (one wait) */
  MPI_Request req[4];
  MPI_Irecv(&n_recv[0], 1, MPI_INT, up, 310, st->dc.cart, &req[0]);
  MPI_Irecv(&n_recv[1], 1, MPI_INT, down, 311, st->dc.cart, &req[1]);
  MPI_Isend(&n_send[0], 1, MPI_INT, down, 310, st->dc.cart, &req[2]);
  MPI_Isend(&n_send[1], 1, MPI_INT, up, 311, st->dc.cart, &req[3]);
  MPI_Waitall(4, req, MPI_STATUSES_IGNORE);
  /* crossing the periodic boundary: ghosts.c's images */
  const double shift_lo = st->dc.coords[axis] == 0 ? st->dc.L[axis] : 0.0;
  const double shift_hi = st->dc.coords[axis] == st->dc.dims[axis] - 1 ? -st->dc.L[axis] : 0.0;
  void *send = NULL, *recv = NULL;
  for (int k = 0; k < 2; k++) /* one MPI message per set: its byte count must fit an int */
    if ((long long)(n_send[k] > n_recv[k] ? n_send[k] : n_recv[k]) * CUDA_GHOST_RECORD_BYTES >
        INT_MAX) {
      snprintf(st->err, sizeof st->err,
               "%d ghost records in one message: more than MPI's int count",
               n_send[k] > n_recv[k] ? n_send[k] : n_recv[k]);
      rc = 1;
    }
  if (!rc) rc = cuda_halo_pack(c->g, axis, shift_lo, shift_hi, n_recv[0], n_recv[1], &send, &recv);
  cuda_idle_mark(c->g, CUDA_IDLE_SELECT, 1); /* before the interior densities */
  if (!rc) rc = cuda_halo_density_early(c->g) || cuda_halo_wait_packed(c->g);
  if (any_failed(st, rc)) return -1;
  exchange_sets(st, axis, CUDA_GHOST_RECORD_BYTES, send, n_send[0], n_send[1], recv, n_recv[0],
                n_recv[1], 312);
  return cuda_halo_unpack(c->g) ? -1 : 0;
}

/* The density halo of the device-packed ghosts: boundary densities down in the records' order (the
 * interior forces launched meanwhile), exchanged, up into the ghosts. */
static int rho_sync_on_device(sim_state_t *st, int axis) {
  cuda_glue_t *c = cuda_glue(st);
  void *send = NULL, *recv = NULL;
  int rc = st->failed || cuda_halo_rho_pack(c->g, &send, &recv) ||
           cuda_halo_forces_early(c->g, st->step, st->want_virial, keep_forces(st)) ||
           cuda_halo_wait_packed(c->g);
  if (any_failed(st, rc)) return -1;
  int n[4];
  cuda_halo_counts(c->g, n);
  exchange_sets(st, axis, cuda_sim_double_precision() ? 8 : 4, send, n[0], n[1], recv, n[2], n[3],
                320);
  return cuda_halo_rho_unpack(c->g) ? -1 : 0;
}

/* Boundary set -> host, the CPU path's ghost stages (collective), ghosts -> device; the interior
 * densities are launched first and run meanwhile. */
static int ghosts(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  const int axis = device_halo_axis(st);
  if (axis >= 0) return ghosts_on_device(st, axis);
  particles_t *hb = &c->halo_b;
  int rc = st->failed || pstore_reserve(hb, cuda_sim_count(c->g) + 1) ||
           cuda_halo_boundary(c->g, hb) || cuda_halo_density_early(c->g);
  if (rc) hb->n_local = hb->n_ghost = 0;
  /* ghosts_build is collective: every rank enters it even after a local failure. */
  rc |= ghosts_build(&st->ghosts, &c->halo_dc, hb, st->plan.rcut, st->plan.ghost_v);
  return rc || cuda_halo_set_ghosts(c->g, hb) ? -1 : 0;
}

/* The boundary part of the neighbour scan (everything without overlap), with the densities. */
static int neighbours(sim_state_t *st) {
  if (st->failed) return 0;
  return cuda_halo_density(cuda_glue(st)->g);
}

/* Boundary densities out, the interior forces launched, the density halo (collective), ghost
 * densities in. */
static int rho_sync(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  const int axis = device_halo_axis(st);
  if (axis >= 0) return rho_sync_on_device(st, axis);
  particles_t *hb = &c->halo_b;
  int rc = st->failed;
  const int nh = hb->n_local + hb->n_ghost;
  if (!rc && nh + 1 > c->halo_rho_cap) {
    double *f = realloc(c->halo_rho, (size_t)(nh + 1) * sizeof(double));
    if (f) {
      c->halo_rho = f;
      c->halo_rho_cap = nh + 1;
    } else {
      rc = 1;
    }
  }
  if (!rc) rc = cuda_halo_rho_out(c->g, c->halo_rho);
  if (!rc) rc = cuda_halo_forces_early(c->g, st->step, st->want_virial, keep_forces(st));
  rc |= ghosts_sync_scalar(&st->ghosts, &c->halo_dc, c->halo_rho); /* collective */
  return rc || cuda_halo_rho_in(c->g, c->halo_rho + hb->n_local) ? -1 : 0;
}

static int pair_forces(sim_state_t *st) {
  cuda_glue_t *c = cuda_glue(st);
  if (st->failed) return 0;
  /* without a density halo the interior forces start here */
  if (!st->plan.density && cuda_halo_forces_early(c->g, st->step, st->want_virial, keep_forces(st)))
    return -1;
  return cuda_halo_forces(c->g, st->step, st->want_virial, keep_forces(st));
}

static const char *phase_note(const plan_t *plan, int phase) {
  (void)plan;
  switch (phase) {
  case PHASE_MIGRATE:
    return "leavers to the host, the CPU path's migration, arrivals back to the device";
  case PHASE_GHOSTS:
    return "one axis cut: the boundary records packed on the device go through MPI from pinned "
           "memory and come back as ghosts; several axes cut (or MDPORE_CUDA_HOST_HALO=1): the "
           "boundary set to the host, the CPU path's ghost stages, ghosts to the device; the "
           "interior densities run meanwhile";
  case PHASE_NEIGHBOURS:
    return "boundary part of the bin scan (lists and densities)";
  case PHASE_RHO_SYNC:
    return "through pinned host memory; the interior forces run meanwhile";
  default:
    return cuda_glue_phase_note(phase);
  }
}

const backend_ops_t cuda_ops_ranks = {
    .name = "cuda",
    .create = cuda_glue_create,
    .destroy = destroy,
    .setup_begin = setup_begin,
    .phase =
        {
            [PHASE_KICK_DRIFT] = cuda_glue_kick_drift,
            [PHASE_MIGRATE] = migrate,
            [PHASE_SORT] = sort,
            [PHASE_PREDICT] = cuda_glue_predict,
            [PHASE_GHOSTS] = ghosts,
            [PHASE_NEIGHBOURS] = neighbours,
            [PHASE_RHO_SYNC] = rho_sync,
            [PHASE_PAIR_FORCES] = pair_forces,
            [PHASE_KICK] = cuda_glue_kick,
            [PHASE_CHECK] = cuda_glue_check,
        },
    .phase_note = phase_note,
    .thermo_sums = cuda_glue_thermo_sums,
    .sync_host = cuda_glue_sync_host,
    .want_pressure = cuda_glue_want_pressure,
    .rebuild_lists = cuda_glue_rebuild_lists,
    .flux_sums = cuda_glue_flux_sums,
    .fault_write = cuda_glue_fault_write,
    .recolor = cuda_glue_recolor,
    .device_bytes_per_particle = cuda_device_bytes_per_particle,
};
