/* The engine's CUDA path (issue 5): sim_setup/sim_step/sim_thermo hand over to the device state of
 * meso/backend/cuda when the scene asks for the cuda backend. One rank, one GPU: the particles stay
 * on the device; the host copy is refreshed only when an output asks (sim_particles). */
#include "sim_internal.h"

#include "particle_store.h"

#include <string.h>

#ifdef MDPORE_HAVE_CUDA
#include "backend/cuda/cuda_backend.h"
#endif

int sim_backend_choose(const char *name, int nranks, int *backend, char *err, size_t errlen) {
  char why[256] = "this mdpore was built without CUDA (MDPORE_CUDA=OFF or no nvcc found)";
  int gpus = 0;
#ifdef MDPORE_HAVE_CUDA
  gpus = cuda_device_count(why, sizeof why);
#endif
  if (!name || !strcmp(name, "auto")) {
    /* One GPU per rank: the ranks of a node share its GPUs in turn (cuda_create.cu); every rank
     * must agree, so the choice is collective (a rank that sees no GPU makes all run on CPUs). */
    int cuda = gpus > 0;
    MPI_Allreduce(MPI_IN_PLACE, &cuda, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    *backend = cuda ? SCENE_BACKEND_CUDA : SCENE_BACKEND_CPU;
    (void)nranks;
    return 0;
  }
  if (!strcmp(name, "cpu")) {
    *backend = SCENE_BACKEND_CPU;
    return 0;
  }
  if (strcmp(name, "cuda")) {
    snprintf(err, errlen, "--backend: expected cpu, cuda or auto (got '%s')", name);
    return -1;
  }
  if (gpus < 1) {
    snprintf(err, errlen, "--backend cuda: no GPU available: %s", why);
    return -1;
  }
  *backend = SCENE_BACKEND_CUDA;
  return 0;
}

#ifdef MDPORE_HAVE_CUDA

int sim_cuda_create(sim_t *sim) {
  sim->gpu = cuda_sim_create(&sim->plan, &sim->scene, sim->dc.lo, sim->dc.hi, sim->dc.dims,
                             sim->err, sizeof sim->err);
  if (!sim->gpu) return -1;
  if (sim->dc.rank == 0)
    printf("mdpore: backend cuda on %s (%s-precision pair math), %d rank(s)\n",
           cuda_sim_device_name(sim->gpu), cuda_sim_double_precision() ? "double" : "single",
           sim->dc.nranks);
  return 0;
}

void sim_cuda_destroy(sim_t *sim) {
  sim_cuda_halo_free(sim);
  cuda_sim_destroy(sim->gpu);
  sim->gpu = NULL;
}

int sim_cuda_check(sim_t *sim, int rc, const cuda_problem_t *cp, const migrate_report_t *mr) {
  step_problem_t pr = {0};
  if (rc) step_problem_note(&pr, STEP_NO_MEMORY, -1, NULL, 0);
  if (mr && mr->n_lost)
    step_problem_note(&pr, STEP_LOST, mr->lost_id, mr->lost_x, (double)mr->n_lost);
  if (cp->kind) {
    step_problem_note(&pr, cp->kind, cp->id, cp->x, cp->value);
    if (cp->kind == CUDA_TOO_FAST) pr.limit = sim->plan.max_disp;
    if (cp->kind == CUDA_NONFINITE) pr.field = cp->at_drift ? "velocity or position" : "force";
    if (cp->kind == CUDA_LOST) pr.value = (double)cp->count;
  }
  return step_check_collective(&pr, sim->dc.cart, sim->step, cuda_sim_count(sim->gpu), sim->n_total,
                               sim->err, sizeof sim->err);
}

int sim_cuda_setup(sim_t *sim) {
  if (sim->dc.nranks > 1) return sim_cuda_halo_setup(sim);
  cuda_problem_t cp;
  memset(&cp, 0, sizeof cp);
  int rc = cuda_sim_upload(sim->gpu, &sim->p);
  if (!rc)
    rc = cuda_sim_setup_forces(sim->gpu, sim->step, sim->forces_loaded, sim->want_virial, &cp);
  sim->host_stale = 1;
  return sim_cuda_check(sim, rc, &cp, NULL);
}

int sim_cuda_step(sim_t *sim) {
  if (sim->dc.nranks > 1) return sim_cuda_halo_step(sim);
  cuda_problem_t cp;
  memset(&cp, 0, sizeof cp);
  sim->step++;
  const int rc = cuda_sim_step(sim->gpu, sim->step, sim->want_virial, &cp);
  sim->host_stale = 1;
  return sim_cuda_check(sim, rc, &cp, NULL);
}

int sim_cuda_thermo_sums(sim_t *sim, double sums[17]) {
  return cuda_sim_thermo_sums(sim->gpu, sums);
}

void sim_cuda_want_pressure(sim_t *sim, int on) {
  cuda_sim_want_pressure(sim->gpu, on);
}

void sim_cuda_rebuild_lists(sim_t *sim) {
  cuda_sim_rebuild_lists(sim->gpu);
}

void sim_cuda_sync_host(sim_t *sim) {
  if (!sim->gpu || !sim->host_stale) return;
  if (pstore_reserve(&sim->p, cuda_sim_count(sim->gpu) + 1) == 0 &&
      cuda_sim_download(sim->gpu, &sim->p) == 0)
    sim->host_stale = 0;
}

#else

int sim_cuda_create(sim_t *sim) {
  snprintf(sim->err, sizeof sim->err,
           "%s: CUDA backend asked for, but this mdpore was built without CUDA", sim->scene.file);
  return -1;
}
void sim_cuda_destroy(sim_t *sim) {
  (void)sim;
}
int sim_cuda_setup(sim_t *sim) {
  (void)sim;
  return -1;
}
int sim_cuda_step(sim_t *sim) {
  (void)sim;
  return -1;
}
int sim_cuda_thermo_sums(sim_t *sim, double sums[17]) {
  (void)sim;
  (void)sums;
  return -1;
}
void sim_cuda_sync_host(sim_t *sim) {
  (void)sim;
}
void sim_cuda_want_pressure(sim_t *sim, int on) {
  (void)sim;
  (void)on;
}
void sim_cuda_rebuild_lists(sim_t *sim) {
  (void)sim;
}

#endif
