/* The CUDA path on several MPI ranks, one GPU each (issue 5, item 2): the device keeps the owned
 * particles; each step only the leavers and the boundary set (owned particles within the ghost
 * cutoff of a face) come to the host, where the CPU path's own exchanges run on them: migration
 * (migrate.c), the 3-stage ghost build with periodic images (ghosts.c) and the density halo
 * (ghosts_sync_scalar). So the images, stages and messages are the CPU path's; the ghosts go back
 * to the device after the owned particles (docs/engine-cuda.md). Halo data is staged through pinned
 * host buffers: the ghost build itself runs on the host, so it needs the boundary set there even
 * with a CUDA-aware MPI (Open MPI 4.1 on the GPU machines is not one). While the host exchanges,
 * the GPU computes the interior particles (cuda_step.cu). */
#include "sim_internal.h"

#include "migrate.h"
#include "particle_store.h"

#include <stdlib.h>
#include <string.h>

#ifdef MDPORE_HAVE_CUDA
#include "backend/cuda/cuda_backend.h"

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

static int ready(sim_t *sim) {
  if (sim->halo_ready) return 0;
  if (pstore_init(&sim->halo_b, 0, 0) || pstore_init(&sim->halo_m, 0, 0)) return -1;
  /* Axes not cut between ranks wrap on the device: no ghost images along them. */
  sim->halo_dc = sim->dc;
  for (int d = 0; d < 3; d++)
    if (sim->dc.dims[d] == 1) sim->halo_dc.nbr[d][0] = sim->halo_dc.nbr[d][1] = MPI_PROC_NULL;
  sim->halo_ready = 1;
  if (sim->dc.rank == 0)
    printf("mdpore: GPU halo staged through pinned host memory (MPI CUDA-aware: %s); interior "
           "passes overlap the exchanges: %s\n",
           mpi_cuda_aware(), cuda_sim_overlap(sim->gpu) ? "yes" : "no (MDPORE_CUDA_OVERLAP=0)");
  return 0;
}

void sim_cuda_halo_free(sim_t *sim) {
  if (!sim->halo_ready) return;
  pstore_free(&sim->halo_b);
  pstore_free(&sim->halo_m);
  free(sim->halo_rho);
  sim->halo_rho = NULL;
  sim->halo_ready = 0;
}

/* Boundary set -> host, ghosts (CPU path's stages), ghosts -> device; densities with their halo;
 * the interior forces are launched before the density halo. The interior passes run on the GPU
 * while the host does the exchanges (cuda_step.cu). Collective. 0 or -1. */
static int ghosts_and_density(sim_t *sim, int keep_forces) {
  cuda_sim_t *g = sim->gpu;
  particles_t *hb = &sim->halo_b;
  int rc = pstore_reserve(hb, cuda_sim_count(g) + 1) || cuda_halo_boundary(g, hb) ||
           cuda_halo_density_early(g);
  if (rc) hb->n_local = hb->n_ghost = 0;
  /* ghosts_build is collective: every rank enters it even after a local failure. */
  rc |= ghosts_build(&sim->ghosts, &sim->halo_dc, hb, sim->plan.rcut, sim->plan.ghost_v);
  rc = rc || cuda_halo_set_ghosts(g, hb) || cuda_halo_density(g);
  if (!sim->plan.density)
    return rc || cuda_halo_forces_early(g, sim->step, sim->want_virial, keep_forces) ? -1 : 0;
  const int nh = hb->n_local + hb->n_ghost;
  if (nh + 1 > sim->halo_rho_cap) {
    double *f = realloc(sim->halo_rho, (size_t)(nh + 1) * sizeof(double));
    if (f) {
      sim->halo_rho = f;
      sim->halo_rho_cap = nh + 1;
    } else {
      rc = 1;
    }
  }
  if (!rc) rc = cuda_halo_rho_out(g, sim->halo_rho);
  if (!rc) rc = cuda_halo_forces_early(g, sim->step, sim->want_virial, keep_forces);
  rc |= ghosts_sync_scalar(&sim->ghosts, &sim->halo_dc, sim->halo_rho); /* collective */
  return rc || cuda_halo_rho_in(g, sim->halo_rho + hb->n_local) ? -1 : 0;
}

int sim_cuda_halo_setup(sim_t *sim) {
  cuda_problem_t cp;
  memset(&cp, 0, sizeof cp);
  cuda_sim_t *g = sim->gpu;
  int rc =
      ready(sim) || cuda_sim_upload(g, &sim->p) || cuda_halo_resort(g) || cuda_halo_predict(g, 1);
  rc |= ghosts_and_density(sim, sim->forces_loaded);
  if (!rc) rc = cuda_halo_forces(g, sim->step, sim->want_virial, sim->forces_loaded, 0, &cp);
  sim->host_stale = 1;
  return sim_cuda_check(sim, rc, &cp, NULL);
}

int sim_cuda_halo_step(sim_t *sim) {
  cuda_problem_t cp;
  memset(&cp, 0, sizeof cp);
  cuda_sim_t *g = sim->gpu;
  migrate_report_t mr = {0};
  particles_t *m = &sim->halo_m;
  sim->step++;
  int n_stay = 0;
  int rc = cuda_halo_kick_drift(g) || cuda_halo_sort_owned(g, &n_stay) ||
           pstore_reserve(m, cuda_sim_count(g) - n_stay + 1) ||
           cuda_halo_take_leavers(g, n_stay, m);
  if (rc) m->n_local = 0;
  migrate_particles(&sim->dc, m, &sim->sbuf, &sim->rbuf, &mr); /* collective */
  rc = rc || mr.out_of_memory || cuda_halo_add_owned(g, m) || cuda_halo_resort(g) ||
       cuda_halo_predict(g, 0);
  rc |= ghosts_and_density(sim, 0);
  if (!rc) rc = cuda_halo_forces(g, sim->step, sim->want_virial, 0, 1, &cp);
  sim->host_stale = 1;
  return sim_cuda_check(sim, rc, &cp, &mr);
}

#else

void sim_cuda_halo_free(sim_t *sim) {
  (void)sim;
}
int sim_cuda_halo_setup(sim_t *sim) {
  (void)sim;
  return -1;
}
int sim_cuda_halo_step(sim_t *sim) {
  (void)sim;
  return -1;
}

#endif
