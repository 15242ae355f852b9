/* The CPU backend: the phases of the plan (effects/plan.h) on the host particles, with MPI for the
 * exchanges and OpenMP in the pair passes. Per-particle arithmetic comes from meso/physics (the
 * same functions the CUDA kernels call): verlet.h and the per-particle effects of the registry. */
#include "backend/backend.h"
#include "backend/cpu/cpu_passes.h"
#include "domain/cell_list.h"
#include "domain/migrate.h"
#include "domain/particle_store.h"
#include "domain/sort_owned.h"
#include "physics/verlet.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  cell_list_t cells;
  nlist_t neighbours;
  sort_scratch_t sort;
  double *saved_f;          /* set-up after a restart: the loaded forces, kept over the pass */
  wall_field_t *wall_field; /* wall_boundary: phi and grad phi per owned particle */
  int wall_field_cap;
  density_cache_t density_cache; /* static frozen particles' densities (plan.density_cache) */
} cpu_state_t;

static cpu_state_t *cpu(sim_state_t *st) {
  return st->impl;
}

static int create(sim_state_t *st) {
  st->impl = calloc(1, sizeof(cpu_state_t));
  if (!st->impl) snprintf(st->err, sizeof st->err, "out of memory creating the CPU backend");
  return st->impl ? 0 : -1;
}

static void destroy(sim_state_t *st) {
  cpu_state_t *c = cpu(st);
  if (!c) return;
  cell_list_free(&c->cells);
  cpu_neighbours_free(&c->neighbours);
  sort_scratch_free(&c->sort);
  free(c->saved_f);
  free(c->wall_field);
  cpu_density_cache_free(&c->density_cache);
  free(c);
  st->impl = NULL;
}

static void position_of(const particles_t *p, int i, double x[3]) {
  for (int d = 0; d < 3; d++) x[d] = p->x[d][i];
}

/* A particle of a moving frozen species (species[].velocity): x += u dt, v = u; never integrated
 * from forces. The wrap and the move to another rank follow in the migrate phase. */
static void moving_wall_drift(const plan_t *plan, particles_t *p, int i, int s) {
  double x[3], v[3];
  for (int d = 0; d < 3; d++) x[d] = p->x[d][i];
  verlet_moving_wall_drift(x, v, plan->wall_u[s], plan->dt);
  for (int d = 0; d < 3; d++) {
    p->x[d][i] = x[d];
    p->v[d][i] = v[d];
  }
}

/* First half kick + drift (physics/verlet.h), then the position constraints of the named
 * AFTER_DRIFT effects on the same particle while its old position is at hand. */
static int kick_drift(sim_state_t *st) {
  const plan_t *plan = &st->plan;
  particles_t *p = &st->p;
  const double max2 = plan->max_disp * plan->max_disp;
  double step_max2 = 0; /* the step's largest displacement: the dt advice of a later stop */
  long n_lost = 0;
  int64_t lost_id = -1;
  double lost_x[3] = {0, 0, 0};
  for (int i = 0; i < p->n_local; i++) {
    const int s = p->species[i];
    if (!plan->mobile[s]) {
      if (plan->moving[s]) moving_wall_drift(plan, p, i, s);
      continue;
    }
    double x[3], v[3], f[3], x_old[3];
    for (int d = 0; d < 3; d++) {
      x_old[d] = x[d] = p->x[d][i];
      v[d] = p->v[d][i];
      f[d] = p->f[d][i];
    }
    const double d2 = verlet_kick_drift(x, v, f, plan->dt, plan->half_dt, plan->inv_mass[s]);
    if (d2 > step_max2) step_max2 = d2;
    if (!(d2 < max2)) { /* also catches NaN */
      if (isfinite(d2)) {
        step_problem_note(&st->pr, STEP_TOO_FAST, p->id[i], x, sqrt(d2));
        st->pr.limit = plan->max_disp;
      } else {
        step_problem_note(&st->pr, STEP_NONFINITE, p->id[i], x, 0);
        st->pr.field = "velocity or position";
      }
    }
    if (plan->walls && particle_effects_after_drift(&plan->particle, i, x, v, x_old)) {
      if (n_lost++ == 0) {
        lost_id = p->id[i];
        memcpy(lost_x, x, sizeof lost_x);
      }
    }
    /* d2 is the displacement, blind to a position that was already non-finite before the drift
     * or that a wall effect made non-finite after it; such a particle would otherwise stay on a
     * rank with several subdomains along the axis (NaN fails every cut comparison) and out of
     * every pair, silently. */
    if (!isfinite(x[0] + x[1] + x[2] + v[0] + v[1] + v[2])) {
      step_problem_note(&st->pr, STEP_NONFINITE, p->id[i], x, 0);
      st->pr.field = "velocity or position";
    }
    for (int d = 0; d < 3; d++) {
      p->x[d][i] = x[d];
      p->v[d][i] = v[d];
    }
  }
  if (n_lost) step_problem_note(&st->pr, STEP_LOST, lost_id, lost_x, (double)n_lost);
  st->pr.disp_step = sqrt(step_max2);
  return 0;
}

static int check_drift(sim_state_t *st) {
  return step_check_collective(&st->pr, st->dc.cart, st->step + 1, st->p.n_local, -1, st->err,
                               sizeof st->err);
}

static int migrate(sim_state_t *st) {
  migrate_report_t mr = {0};
  migrate_particles(&st->dc, &st->p, &st->sbuf, &st->rbuf, &mr); /* collective */
  if (mr.n_lost) step_problem_note(&st->pr, STEP_LOST, mr.lost_id, mr.lost_x, (double)mr.n_lost);
  return mr.out_of_memory ? -1 : 0;
}

static int sort(sim_state_t *st) {
  if (st->failed) return 0;
  return sort_owned_by_bin(&st->p, st->dc.lo, st->dc.hi, st->plan.rcut, &cpu(st)->sort);
}

static int predict(sim_state_t *st) {
  const plan_t *plan = &st->plan;
  particles_t *p = &st->p;
  if (!p->vpred[0]) return 0;
  for (int i = 0; i < p->n_local; i++) {
    const int s = p->species[i];
    /* set-up: v~ = v (the forces of the first configuration use the current velocities) */
    const double k = (!st->in_setup && plan->mobile[s]) ? plan->predict_c * plan->inv_mass[s] : 0.0;
    double vp[3];
    const double v[3] = {p->v[0][i], p->v[1][i], p->v[2][i]};
    const double f[3] = {p->f[0][i], p->f[1][i], p->f[2][i]};
    verlet_predict(vp, v, f, k);
    for (int d = 0; d < 3; d++) p->vpred[d][i] = vp[d];
  }
  return 0;
}

static int ghosts(sim_state_t *st) {
  /* collective: every rank enters it */
  return ghosts_build(&st->ghosts, &st->dc, &st->p, st->plan.rcut, st->plan.ghost_v);
}

static int neighbours(sim_state_t *st) {
  if (st->failed) return 0;
  cpu_state_t *c = cpu(st);
  if (cell_list_build(&c->cells, &st->p, st->dc.lo, st->dc.hi, st->plan.rcut)) return -1;
  if (cpu_density_cache_prepare(&c->density_cache, &st->plan, &st->p, &c->cells)) return -1;
  return cpu_neighbours_build(&c->neighbours, &st->plan, &st->p, &c->cells, &c->density_cache);
}

static int density(sim_state_t *st) {
  if (st->failed) return 0;
  cpu_state_t *c = cpu(st);
  return cpu_density_pass(&st->plan, &st->p, &c->cells, &c->neighbours, &c->density_cache);
}

/* wall_boundary: the wall field of the owned particles at this step's positions; the next drift's
 * reflection reads it (same particle order: nothing reorders them in between). */
static int wall_field(sim_state_t *st) {
  if (st->failed) return 0;
  cpu_state_t *c = cpu(st);
  const int n = st->p.n_local > 0 ? st->p.n_local : 1;
  if (n > c->wall_field_cap) {
    wall_field_t *f = realloc(c->wall_field, (size_t)n * sizeof *f);
    if (!f) return -1;
    c->wall_field = f;
    c->wall_field_cap = n;
  }
  st->plan.particle.wall_boundary.field = c->wall_field;
  cpu_wall_field_pass(&st->plan, &st->p, &c->cells, &c->neighbours, c->wall_field);
  return 0;
}

static int rho_sync(sim_state_t *st) {
  return ghosts_sync_scalar(&st->ghosts, &st->dc, st->p.rho); /* collective */
}

static int pair_forces(sim_state_t *st) {
  particles_t *p = &st->p;
  cpu_state_t *c = cpu(st);
  memset(st->virial, 0, sizeof st->virial);
  if (st->failed) return 0;
  /* Set-up after a restart: the forces come from the checkpoint (they were evaluated with the
   * predicted velocities of the step that produced them); the pass still runs for the densities,
   * the ghosts and the pair virial. The check phase puts them back. */
  if (st->in_setup && st->forces_loaded) {
    free(c->saved_f);
    c->saved_f = malloc((size_t)(3 * p->n_local + 1) * sizeof(double));
    if (!c->saved_f) return -1;
    for (int d = 0; d < 3; d++)
      memcpy(c->saved_f + (size_t)d * p->n_local, p->f[d], p->n_local * sizeof(double));
  }
  if (st->plan.pair_terms) {
    force_pass_args_t args = {.seed = st->plan.seed,
                              .step = (uint64_t)st->step,
                              .inv_sqrt_dt = st->plan.inv_sqrt_dt,
                              .per_particle_virial = st->want_virial};
    cpu_force_pass(&st->plan, p, &c->cells, &c->neighbours, &args);
    memcpy(st->virial, args.virial, sizeof st->virial);
  } else {
    for (int d = 0; d < 3; d++) memset(p->f[d], 0, (size_t)p->n_local * sizeof(double));
    if (p->virial) memset(p->virial, 0, (size_t)p->n_local * 6 * sizeof(double));
  }
  return 0;
}

/* Per-particle forces of the named PARTICLE_FORCE effects (physics/<effect>.h). */
static int particle_forces(sim_state_t *st) {
  particles_t *p = &st->p;
  for (int i = 0; i < p->n_local; i++) {
    double x[3], f[3];
    for (int d = 0; d < 3; d++) {
      x[d] = p->x[d][i];
      f[d] = p->f[d][i];
    }
    particle_effects_force(&st->plan.particle, p->species[i], x, f);
    for (int d = 0; d < 3; d++) p->f[d][i] = f[d];
  }
  return 0;
}

static int kick(sim_state_t *st) {
  const plan_t *plan = &st->plan;
  particles_t *p = &st->p;
  for (int i = 0; i < p->n_local; i++) {
    const int s = p->species[i];
    const double f[3] = {p->f[0][i], p->f[1][i], p->f[2][i]};
    if (!isfinite(f[0] + f[1] + f[2])) {
      double x[3];
      position_of(p, i, x);
      step_problem_note(&st->pr, STEP_NONFINITE, p->id[i], x, 0);
      st->pr.field = "force";
    }
    if (!plan->mobile[s]) continue;
    double v[3] = {p->v[0][i], p->v[1][i], p->v[2][i]};
    verlet_kick(v, f, plan->half_dt, plan->inv_mass[s]);
    for (int d = 0; d < 3; d++) p->v[d][i] = v[d];
  }
  return 0;
}

static int check(sim_state_t *st) {
  particles_t *p = &st->p;
  cpu_state_t *c = cpu(st);
  if (!st->in_setup)
    return step_check_collective(&st->pr, st->dc.cart, st->step, p->n_local, st->n_total, st->err,
                                 sizeof st->err);
  if (c->saved_f) {
    for (int d = 0; d < 3; d++)
      memcpy(p->f[d], c->saved_f + (size_t)d * p->n_local, p->n_local * sizeof(double));
    free(c->saved_f);
    c->saved_f = NULL;
  }
  for (int i = 0; i < p->n_local; i++)
    if (!isfinite(p->f[0][i] + p->f[1][i] + p->f[2][i])) {
      double x[3];
      position_of(p, i, x);
      step_problem_note(&st->pr, STEP_NONFINITE, p->id[i], x, 0);
      st->pr.field = "force";
    }
  return step_check_collective(&st->pr, st->dc.cart, st->step, p->n_local, -1, st->err,
                               sizeof st->err);
}

static const char *phase_note(const plan_t *plan, int phase) {
  (void)plan;
  switch (phase) {
  case PHASE_AFTER_DRIFT:
    return "in the kick_drift loop, per particle, with its position before the drift";
  case PHASE_NEIGHBOURS:
    return "per-particle neighbour lists, full traversal";
  case PHASE_PAIR_FORCES:
    return "OpenMP over owned particles; each pair evaluated from both sides";
  default:
    return NULL;
  }
}

const backend_ops_t backend_cpu_ops = {
    .name = "cpu",
    .create = create,
    .destroy = destroy,
    .phase =
        {
            [PHASE_KICK_DRIFT] = kick_drift,
            [PHASE_AFTER_DRIFT] = NULL, /* inside kick_drift (phase_note) */
            [PHASE_CHECK_DRIFT] = check_drift,
            [PHASE_MIGRATE] = migrate,
            [PHASE_SORT] = sort,
            [PHASE_PREDICT] = predict,
            [PHASE_GHOSTS] = ghosts,
            [PHASE_NEIGHBOURS] = neighbours,
            [PHASE_DENSITY] = density,
            [PHASE_RHO_SYNC] = rho_sync,
            [PHASE_WALL_FIELD] = wall_field,
            [PHASE_PAIR_FORCES] = pair_forces,
            [PHASE_PARTICLE_FORCES] = particle_forces,
            [PHASE_KICK] = kick,
            [PHASE_CHECK] = check,
        },
    .phase_note = phase_note,
};
