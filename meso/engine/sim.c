/* Simulation lifecycle (sim.h): the plan and the decomposition are built once from the scene, the
 * backend chosen by scene.backend gets its ops table; set-up and steps run the plan's phase lists
 * (engine/step.c). */
#include "domain/particle_store.h"
#include "engine/sim_internal.h"
#include "physics/pair_random.h"

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
  sim_state_t *st = &sim->st;
  st->scene = *scene;
  st->dc.cart = MPI_COMM_NULL;
  st->hist.dt = scene->dt;
  /* the cost cuts' frozen weight: the scene's, else the backend's default */
  st->scene.balance.frozen_weight = scene_frozen_weight(scene);
  st->frozen_weight = st->scene.balance.frozen_weight;
  if (plan_build(&st->plan, scene, st->err, sizeof st->err) ||
      decomp_create(&st->dc, scene, comm, st->plan.rcut, st->err, sizeof st->err)) {
    report(comm, st->err);
    sim_destroy(sim);
    return NULL;
  }
  if (pstore_init(&st->p, st->plan.density, st->plan.use_vpred)) {
    fprintf(stderr, "mdpore: out of memory creating the particle storage\n");
    sim_destroy(sim);
    return NULL;
  }
  sim->ops = sim_backend_ops(scene->backend, st->dc.nranks);
  if (!sim->ops) {
    snprintf(st->err, sizeof st->err,
             "%s: CUDA backend asked for, but this mdpore was built without CUDA", scene->file);
    report(comm, st->err);
    sim_destroy(sim);
    return NULL;
  }
  if (sim->ops->create(st)) {
    report(comm, st->err);
    sim_destroy(sim);
    return NULL;
  }
  return sim;
}

void sim_destroy(sim_t *sim) {
  if (!sim) return;
  sim_state_t *st = &sim->st;
  if (sim->ops && st->impl) sim->ops->destroy(st);
  pstore_free(&st->p);
  ghosts_free(&st->ghosts);
  xbuf_free(&st->sbuf);
  xbuf_free(&st->rbuf);
  decomp_free(&st->dc);
  plan_release(&st->plan);
  free(sim);
}

int sim_add_particle(sim_t *sim, int64_t id, int species, const double x[3], const double v[3]) {
  sim_state_t *st = &sim->st;
  const int64_t max_id = pair_random_max_id(st->plan.pair_rng);
  if (id < 0 || id > max_id) {
    fprintf(stderr,
            "mdpore: particle id %lld: expected 0 to %lld (the pair random numbers, generator "
            "%s, are keyed on the ids; %s)\n",
            (long long)id, (long long)max_id, pair_rng_word(st->plan.pair_rng), st->scene.file);
    return -1;
  }
  if (species < 0 || species >= st->plan.n_species) {
    fprintf(stderr, "mdpore: particle %lld: species %d: expected 0 to %d (%s)\n", (long long)id,
            species, st->plan.n_species - 1, st->scene.file);
    return -1;
  }
  double pos[3] = {x[0], x[1], x[2]};
  for (int d = 0; d < 3; d++)
    if (!isfinite(pos[d]) ||
        (!st->dc.periodic[d] && (pos[d] < st->dc.box_lo[d] || pos[d] >= st->dc.box_hi[d]))) {
      if (st->dc.rank == 0)
        fprintf(stderr,
                "mdpore: particle %lld at (%g, %g, %g): outside the box along the non-periodic "
                "axis %c [%g, %g) (%s)\n",
                (long long)id, x[0], x[1], x[2], "xyz"[d], st -> dc.box_lo[d], st->dc.box_hi[d],
                st->scene.file);
      return -1;
    }
  decomp_wrap(&st->dc, pos);
  if (!decomp_owns(&st->dc, pos)) return 0;
  particles_t *p = &st->p;
  p->n_ghost = 0; /* ghosts are rebuilt at setup */
  if (pstore_reserve(p, p->n_local + 1)) return -1;
  const int i = p->n_local++;
  const int mobile = st->plan.mobile[species];
  p->id[i] = id;
  p->species[i] = species;
  for (int d = 0; d < 3; d++) {
    p->x[d][i] = pos[d];
    /* frozen particles are at rest, or move with their species' fixed velocity (plan.wall_u) */
    p->v[d][i] = mobile ? v[d] : st->plan.wall_u[species][d];
    p->f[d][i] = 0.0;
  }
  return 1;
}

int sim_setup(sim_t *sim) {
  sim_state_t *st = &sim->st;
  long n = st->p.n_local;
  MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_LONG, MPI_SUM, st->dc.cart);
  st->n_total = n;
  if (n == 0) {
    snprintf(st->err, sizeof st->err, "%s: no particles in the box", st->scene.file);
    report(st->dc.cart, st->err);
    return -1;
  }
  memset(&st->pr, 0, sizeof st->pr);
  st->failed = 0;
  /* A failure here still runs the list: its collective check reports it on every rank. */
  if (sim->ops->setup_begin && sim->ops->setup_begin(st)) {
    step_problem_note(&st->pr, STEP_NO_MEMORY, -1, NULL, 0);
    st->failed = 1;
  }
  st->in_setup = 1;
  const int rc = sim_run_phases(sim, st->plan.setup, st->plan.n_setup);
  st->in_setup = 0;
  if (rc) return rc;
  if (!sim->is_setup) st->busy_total = 0; /* the load-balance measures count steps only */
  sim->is_setup = 1;
  st->busy_seconds = 0;
  st->busy_since = st->step;
  return 0;
}

int sim_check_count(sim_t *sim) {
  sim_state_t *st = &sim->st;
  step_problem_t pr = {0};
  return step_check_collective(&pr, st->dc.cart, st->step, st->p.n_local, st->n_total, st->err,
                               sizeof st->err);
}

particles_t *sim_particles(sim_t *sim) {
  if (sim->ops->sync_host) sim->ops->sync_host(&sim->st); /* device backends: a fresh copy */
  return &sim->st.p;
}
const scene_t *sim_scene(const sim_t *sim) {
  return &sim->st.scene;
}
MPI_Comm sim_comm(const sim_t *sim) {
  return sim->st.dc.cart;
}
long sim_step_index(const sim_t *sim) {
  return sim->st.step;
}
void sim_set_step_index(sim_t *sim, long step) {
  sim->st.step = step;
}
const char *sim_last_error(const sim_t *sim) {
  return sim->st.err;
}
const char *sim_backend_name(const sim_t *sim) {
  return sim->ops->name;
}

void sim_subdomain(const sim_t *sim, double lo[3], double hi[3]) {
  for (int d = 0; d < 3; d++) {
    lo[d] = sim->st.dc.lo[d];
    hi[d] = sim->st.dc.hi[d];
  }
}

void sim_request_virial(sim_t *sim, int on) {
  sim->st.want_virial = on != 0;
  if (pstore_set_virial(&sim->st.p, sim->st.want_virial)) {
    fprintf(stderr, "mdpore: out of memory for the per-particle virial\n");
    sim->st.want_virial = 0;
  }
}

void sim_announce_thermo(sim_t *sim, int on) {
  if (sim->ops->want_pressure) sim->ops->want_pressure(&sim->st, on);
}

void sim_rebuild_lists(sim_t *sim) {
  if (sim->ops->rebuild_lists) sim->ops->rebuild_lists(&sim->st);
}

int sim_fault_write(sim_t *sim, int64_t id, int field, int axis, double value, int add) {
  sim_state_t *st = &sim->st;
  if (sim->ops->fault_write) {
    if (sim->ops->fault_write(st, id, field, axis, value, add) == 0) return 0;
    fprintf(stderr, "mdpore: MDPORE_TEST_FAULT: the backend's write failed\n");
    return -1;
  }
  particles_t *p = &st->p;
  double *a = field ? p->v[axis] : p->x[axis];
  for (int i = 0; i < p->n_local; i++)
    if (p->id[i] == id) a[i] = add ? a[i] + value : value;
  return 0;
}

void sim_forces_loaded(sim_t *sim) {
  sim->st.forces_loaded = 1;
}
