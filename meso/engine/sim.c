/* Simulation lifecycle and the step (sim.h). The step follows the plan (plan.h, printed by
 * sim_explain): kick + drift, walls, migration, ghosts, density, rho sync, pair forces, particle
 * forces, kick. */
#include "sim_internal.h"
#include "backend/cpu/cpu_passes.h"
#include "physics/pair_random.h"
#include "effects/effect.h"
#include "integrate.h"
#include "migrate.h"
#include "particle_store.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void report(MPI_Comm comm, const char *msg) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0) fprintf(stderr, "mdpore: %s\n", msg);
}

sim_t *sim_create(const scene_t *scene, MPI_Comm comm) {
  sim_t *sim = calloc(1, sizeof *sim);
  if (!sim) {
    fprintf(stderr, "mdpore: out of memory creating the simulation\n");
    return NULL;
  }
  sim->scene = *scene;
  sim->dc.cart = MPI_COMM_NULL;
  if (plan_build(&sim->plan, scene, sim->err, sizeof sim->err) ||
      decomp_create(&sim->dc, scene, comm, sim->plan.rcut, sim->err, sizeof sim->err)) {
    report(comm, sim->err);
    sim_destroy(sim);
    return NULL;
  }
  if (pstore_init(&sim->p, sim->plan.density, sim->plan.use_vpred)) {
    fprintf(stderr, "mdpore: out of memory creating the particle storage\n");
    sim_destroy(sim);
    return NULL;
  }
  if (scene->backend == SCENE_BACKEND_CUDA && sim_cuda_create(sim)) {
    report(comm, sim->err);
    sim_destroy(sim);
    return NULL;
  }
  return sim;
}

void sim_destroy(sim_t *sim) {
  if (!sim) return;
  if (sim->gpu) sim_cuda_destroy(sim);
  pstore_free(&sim->p);
  cell_list_free(&sim->cells);
  cpu_neighbours_free(&sim->neighbours);
  ghosts_free(&sim->ghosts);
  xbuf_free(&sim->sbuf);
  xbuf_free(&sim->rbuf);
  sort_scratch_free(&sim->sort);
  decomp_free(&sim->dc);
  free(sim);
}

int sim_add_particle(sim_t *sim, int64_t id, int species, const double x[3], const double v[3]) {
  if (id < 0 || id > PAIR_RANDOM_MAX_ID) {
    fprintf(stderr,
            "mdpore: particle id %lld: expected 0 to %lld (the pair random numbers of this build "
            "are keyed on the ids; %s)\n",
            (long long)id, (long long)PAIR_RANDOM_MAX_ID, sim->scene.file);
    return -1;
  }
  if (species < 0 || species >= sim->plan.n_species) {
    fprintf(stderr, "mdpore: particle %lld: species %d: expected 0 to %d (%s)\n", (long long)id,
            species, sim->plan.n_species - 1, sim->scene.file);
    return -1;
  }
  double pos[3] = {x[0], x[1], x[2]};
  for (int d = 0; d < 3; d++)
    if (!isfinite(pos[d]) ||
        (!sim->dc.periodic[d] && (pos[d] < sim->dc.box_lo[d] || pos[d] >= sim->dc.box_hi[d]))) {
      if (sim->dc.rank == 0)
        fprintf(stderr,
                "mdpore: particle %lld at (%g, %g, %g): outside the box along the non-periodic "
                "axis %c [%g, %g) (%s)\n",
                (long long)id, x[0], x[1], x[2], "xyz"[d], sim -> dc.box_lo[d], sim->dc.box_hi[d],
                sim->scene.file);
      return -1;
    }
  decomp_wrap(&sim->dc, pos);
  if (!decomp_owns(&sim->dc, pos)) return 0;
  particles_t *p = &sim->p;
  p->n_ghost = 0; /* ghosts are rebuilt at setup */
  if (pstore_reserve(p, p->n_local + 1)) return -1;
  const int i = p->n_local++;
  const int mobile = sim->plan.mobile[species];
  p->id[i] = id;
  p->species[i] = species;
  for (int d = 0; d < 3; d++) {
    p->x[d][i] = pos[d];
    p->v[d][i] = mobile ? v[d] : 0.0; /* frozen particles are at rest */
    p->f[d][i] = 0.0;
  }
  return 1;
}

int sim_compute_forces(sim_t *sim) {
  particles_t *p = &sim->p;
  const plan_t *plan = &sim->plan;
  memset(sim->virial, 0, sizeof sim->virial);
  if (plan->pair_terms) {
    if (ghosts_build(&sim->ghosts, &sim->dc, p, plan->rcut, plan->ghost_v)) return -1;
    if (cell_list_build(&sim->cells, p, sim->dc.lo, sim->dc.hi, plan->rcut)) return -1;
    if (cpu_neighbours_build(&sim->neighbours, plan, p, &sim->cells)) return -1;
    if (plan->density) {
      cpu_density_pass(plan, p, &sim->cells, &sim->neighbours);
      if (ghosts_sync_scalar(&sim->ghosts, &sim->dc, p->rho)) return -1;
    }
    force_pass_args_t args = {.seed = sim->scene.seed,
                              .step = (uint64_t)sim->step,
                              .dt = sim->scene.dt,
                              .per_particle_virial = sim->want_virial};
    cpu_force_pass(plan, p, &sim->cells, &sim->neighbours, &args);
    memcpy(sim->virial, args.virial, sizeof sim->virial);
  } else {
    for (int d = 0; d < 3; d++) memset(p->f[d], 0, (size_t)p->n_local * sizeof(double));
    if (p->virial) memset(p->virial, 0, (size_t)p->n_local * 6 * sizeof(double));
  }
  for (int e = 0; e < EFFECT_COUNT; e++) {
    const effect_t *eff = effect_get(e);
    if (plan->named[e] && eff->particle_force) eff->particle_force(&sim->scene, p);
  }
  return 0;
}

int sim_setup(sim_t *sim) {
  particles_t *p = &sim->p;
  long n = p->n_local;
  MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_LONG, MPI_SUM, sim->dc.cart);
  sim->n_total = n;
  if (n == 0) {
    snprintf(sim->err, sizeof sim->err, "%s: no particles in the box", sim->scene.file);
    report(sim->dc.cart, sim->err);
    return -1;
  }
  if (sim->gpu) { /* CUDA path: the device sorts, evaluates and checks (sim_cuda.c) */
    if (sim_cuda_setup(sim)) return -1;
    sim->is_setup = 1;
    return 0;
  }
  /* Forces at the current step use the current velocities (v~ = v). Forces loaded from a checkpoint
   * are kept: they were evaluated with the predicted velocities of the step that produced them; the
   * pass still runs for the densities, the ghosts and the pair virial. */
  /* Spatial order first (idempotent on an already sorted set: restarts keep their order). */
  if (sort_owned_by_bin(p, sim->dc.lo, sim->dc.hi, sim->plan.rcut, &sim->sort)) return -1;
  double *saved = NULL;
  if (sim->forces_loaded) {
    saved = malloc((size_t)(3 * p->n_local + 1) * sizeof(double));
    if (!saved) return -1;
    for (int d = 0; d < 3; d++)
      memcpy(saved + (size_t)d * p->n_local, p->f[d], p->n_local * sizeof(double));
  }
  if (p->vpred[0])
    for (int d = 0; d < 3; d++) memcpy(p->vpred[d], p->v[d], p->n_local * sizeof(double));
  int rc = sim_compute_forces(sim);
  if (saved) {
    for (int d = 0; d < 3; d++)
      memcpy(p->f[d], saved + (size_t)d * p->n_local, p->n_local * sizeof(double));
    free(saved);
  }
  step_problem_t pr = {0};
  if (rc) step_problem_note(&pr, STEP_NO_MEMORY, -1, NULL, 0);
  for (int i = 0; i < p->n_local; i++)
    if (!isfinite(p->f[0][i] + p->f[1][i] + p->f[2][i])) {
      const double x[3] = {p->x[0][i], p->x[1][i], p->x[2][i]};
      step_problem_note(&pr, STEP_NONFINITE, p->id[i], x, 0);
      pr.field = "force";
    }
  if (step_check_collective(&pr, sim->dc.cart, sim->step, p->n_local, -1, sim->err,
                            sizeof sim->err))
    return -1;
  sim->is_setup = 1;
  return 0;
}

int sim_step(sim_t *sim) {
  if (sim->gpu) return sim_cuda_step(sim);
  particles_t *p = &sim->p;
  const plan_t *plan = &sim->plan;
  const double dt = sim->scene.dt;
  step_problem_t pr = {0};
  MPI_Comm comm = sim->dc.cart;
  /* 1. first half kick + drift, then the walls */
  integrate_kick_drift(plan, p, dt, &pr);
  for (int e = 0; e < EFFECT_COUNT; e++) {
    const effect_t *eff = effect_get(e);
    if (!plan->named[e] || !eff->after_drift) continue;
    effect_violation_t bad;
    const long n_bad = eff->after_drift(&sim->scene, plan, p, &bad);
    if (n_bad) step_problem_note(&pr, STEP_LOST, bad.id, bad.x, (double)n_bad);
  }
  int rc =
      step_check_collective(&pr, comm, sim->step + 1, p->n_local, -1, sim->err, sizeof sim->err);
  if (rc) return rc;
  sim->step++;
  /* 2. migration; predicted velocities; ghosts, densities, forces */
  migrate_report_t mr = {0};
  migrate_particles(&sim->dc, p, &sim->sbuf, &sim->rbuf, &mr);
  if (mr.n_lost) step_problem_note(&pr, STEP_LOST, mr.lost_id, mr.lost_x, (double)mr.n_lost);
  if (sort_owned_by_bin(p, sim->dc.lo, sim->dc.hi, plan->rcut, &sim->sort))
    step_problem_note(&pr, STEP_NO_MEMORY, -1, NULL, 0);
  integrate_predict(plan, p, dt, sim->scene.vv_lambda);
  if (mr.out_of_memory || sim_compute_forces(sim))
    step_problem_note(&pr, STEP_NO_MEMORY, -1, NULL, 0);
  /* 3. second half kick */
  integrate_kick(plan, p, dt, &pr);
  return step_check_collective(&pr, comm, sim->step, p->n_local, sim->n_total, sim->err,
                               sizeof sim->err);
}

int sim_check_count(sim_t *sim) {
  step_problem_t pr = {0};
  return step_check_collective(&pr, sim->dc.cart, sim->step, sim->p.n_local, sim->n_total, sim->err,
                               sizeof sim->err);
}

particles_t *sim_particles(sim_t *sim) {
  sim_cuda_sync_host(sim); /* no-op on the CPU path */
  return &sim->p;
}
const scene_t *sim_scene(const sim_t *sim) {
  return &sim->scene;
}
MPI_Comm sim_comm(const sim_t *sim) {
  return sim->dc.cart;
}
long sim_step_index(const sim_t *sim) {
  return sim->step;
}
void sim_set_step_index(sim_t *sim, long step) {
  sim->step = step;
}
const char *sim_last_error(const sim_t *sim) {
  return sim->err;
}

void sim_subdomain(const sim_t *sim, double lo[3], double hi[3]) {
  for (int d = 0; d < 3; d++) {
    lo[d] = sim->dc.lo[d];
    hi[d] = sim->dc.hi[d];
  }
}

void sim_request_virial(sim_t *sim, int on) {
  sim->want_virial = on != 0;
  if (pstore_set_virial(&sim->p, sim->want_virial)) {
    fprintf(stderr, "mdpore: out of memory for the per-particle virial\n");
    sim->want_virial = 0;
  }
}

void sim_announce_thermo(sim_t *sim, int on) {
  if (sim->gpu) sim_cuda_want_pressure(sim, on);
}

void sim_rebuild_lists(sim_t *sim) {
  if (sim->gpu) sim_cuda_rebuild_lists(sim);
}

void sim_forces_loaded(sim_t *sim) {
  sim->forces_loaded = 1;
}
