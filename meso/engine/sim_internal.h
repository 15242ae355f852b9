/* The simulation object behind sim.h (engine-internal). */
#ifndef MESO_ENGINE_SIM_INTERNAL_H
#define MESO_ENGINE_SIM_INTERNAL_H

#include "backend/cpu/cpu_passes.h"
#include "cell_list.h"
#include "decomp.h"
#include "exchange.h"
#include "ghosts.h"
#include "particles.h"
#include "plan.h"
#include "sim.h"
#include "sort_owned.h"
#include "step_check.h"

struct sim {
  scene_t scene;
  plan_t plan;
  decomp_t dc;
  particles_t p;
  cell_list_t cells;
  nlist_t neighbours;
  ghost_plan_t ghosts;
  xbuf_t sbuf, rbuf; /* migration buffers */
  sort_scratch_t sort;
  long step;
  long n_total; /* global particle count fixed at sim_setup; checked every step */
  int forces_loaded, want_virial, is_setup;
  double virial[6];     /* local pair virial of the last force pass: 1/2 sum r_ij (x) F_ij */
  char err[2048];       /* last error message on this rank */
  struct cuda_sim *gpu; /* CUDA backend state (scene.backend == SCENE_BACKEND_CUDA), else NULL */
  int host_stale;       /* the device holds a newer state than p */
  /* CUDA on several ranks (sim_cuda_halo.c): host copies of the boundary set + its ghosts, of the
   * leavers/arrivals, and the densities of the boundary set + ghosts. */
  particles_t halo_b, halo_m;
  decomp_t halo_dc; /* dc without the self-exchange along axes not cut between ranks */
  double *halo_rho;
  int halo_rho_cap, halo_ready;
};

/* CUDA backend glue (sim_cuda.c; errors when the build has no CUDA). 0 or -1 (message in err). */
int sim_cuda_create(sim_t *sim);
void sim_cuda_destroy(sim_t *sim);
int sim_cuda_setup(sim_t *sim);
int sim_cuda_step(sim_t *sim);
int sim_cuda_thermo_sums(sim_t *sim, double sums[17]);
void sim_cuda_sync_host(sim_t *sim);
void sim_cuda_want_pressure(sim_t *sim, int on);
void sim_cuda_rebuild_lists(sim_t *sim);
#ifdef MDPORE_HAVE_CUDA
#include "backend/cuda/cuda_backend.h"
#include "migrate.h"
/* Collective end-of-phase check of the CUDA path: allocation failure (rc), the device's problem
 * report and, on several ranks, particles lost in the host-side migration (mr may be NULL). */
int sim_cuda_check(sim_t *sim, int rc, const cuda_problem_t *cp, const migrate_report_t *mr);
#endif
/* Several ranks: setup and step with the halo through the host (sim_cuda_halo.c). */
int sim_cuda_halo_setup(sim_t *sim);
int sim_cuda_halo_step(sim_t *sim);
void sim_cuda_halo_free(sim_t *sim);

/* Ghosts, densities, pair and particle forces at the current positions for step index sim->step. */
int sim_compute_forces(sim_t *sim);

#endif
