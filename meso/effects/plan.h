/* The step plan: what the engine does each step, built once from the effects a scene names.
 * An effect that is not named contributes nothing: no array, no pass, no pair term, no message.
 * The plan is an ordered list of phases (enum step_phase) for the set-up and for every step; each
 * backend implements the phases behind one ops table (meso/backend/backend.h), the engine runs the
 * list (engine/step.c) and `mdpore run --explain` prints the same list (engine/explain.c). */
#ifndef MESO_EFFECTS_PLAN_H
#define MESO_EFFECTS_PLAN_H

#include "effects/effect_list.h"
#include "scene/scene.h"

#include <stddef.h>
#include <stdint.h>

/* Pair terms the fused force kernel can evaluate (meso/backend/cpu/force_pass.c). */
enum plan_pair_term {
  PAIR_TERM_CONSERVATIVE = 1, /* A w_c(r): mdpd_attraction (A < 0) or dpd_conservative (a > 0) */
  PAIR_TERM_MANYBODY = 2,     /* B (rho_i + rho_j) w_d(r): mdpd_repulsion                       */
  PAIR_TERM_THERMOSTAT = 4,   /* -gamma w_R^2 (e.v) + sigma w_R xi / sqrt(dt): dpd_thermostat     */
  PAIR_TERM_WALL_NO_SLIP = 8  /* thermostat of wall pairs x Li's ratio(phi_i): wall_boundary      */
};

/* Constants of one species pair, precomputed once so the pair loop has no division or pow (s = 1).
 */
typedef struct {
  double A;            /* conservative amplitude (0 when no conservative term is named) */
  double B;            /* many-body amplitude                                           */
  double gamma, sigma; /* sigma^2 = 2 gamma kT (fluctuation-dissipation)                 */
  double rc, inv_rc, rc2;
  double rd, inv_rd, rd2;
  double wnorm;     /* density-kernel normalisation for this rd (w_rho_norm) */
  double cut2;      /* square of the largest cutoff any named pair term uses for this pair */
  double wall_phi2; /* wall_boundary: r_phi^2 for a mobile-frozen pair (its wall field), else 0 */
  double s_exp;     /* exponent s of the thermostat weight w_R = (1 - r/rc)^s of this pair */
  int s_one;        /* s_exp == 1: w_R = 1 - r/rc without pow (the standard weight)      */
} pair_coef_t;

/* The phases of a step, in the order they run (a plan lists those its effects need). */
enum step_phase {
  PHASE_KICK_DRIFT,      /* v += dt/2 f/m, x += dt v; displacement and finiteness noted     */
  PHASE_AFTER_DRIFT,     /* position constraints of the named effects (box_walls)           */
  PHASE_CHECK_DRIFT,     /* collective check after the drift; the step index advances       */
  PHASE_MIGRATE,         /* periodic wrap, particles to the rank that owns them             */
  PHASE_SORT,            /* owned particles in cell order                                   */
  PHASE_PREDICT,         /* v~ = v + (lambda - 1/2) dt f/m (v~ = v at set-up)               */
  PHASE_GHOSTS,          /* ghost layer of width rcut (x, and v~ with the thermostat)      */
  PHASE_NEIGHBOURS,      /* cell and neighbour lists                                        */
  PHASE_DENSITY,         /* rho_i over r < rd (self term excluded)                          */
  PHASE_RHO_SYNC,        /* ghosts get the densities of their owners                        */
  PHASE_WALL_FIELD,      /* wall fraction phi and its gradient per mobile particle          */
  PHASE_PAIR_FORCES,     /* the fused pair pass of the named pair terms (f = 0 without any) */
  PHASE_PARTICLE_FORCES, /* per-particle forces of the named effects (body_force)           */
  PHASE_KICK,            /* v += dt/2 f/m                                                   */
  PHASE_CHECK,           /* collective check: non-finite values, lost particles, count      */
  PHASE_COUNT
};
extern const char *const step_phase_names[PHASE_COUNT];

#define PLAN_MAX_ARRAYS 8

typedef struct {
  int named[EFFECT_COUNT]; /* copy of scene.effect */
  int pair_terms;          /* OR of enum plan_pair_term */
  int density;             /* 1: density pass + rho ghost sync (mdpd_repulsion) */
  int density_kernel;      /* enum meso_density_kernel */
  int ghost_v;             /* ghosts carry (predicted) velocities (dpd_thermostat) */
  int use_vpred;       /* a separate predicted-velocity array (thermostat and vv_lambda != 0.5) */
  int particle_forces; /* per-particle forces (body_force) */
  int walls;           /* position constraints after the drift (box_walls) */
  int wall_field;      /* the wall-field pass (wall_boundary) */
  double rcut;         /* ghost-layer width = largest cutoff of the named effects */
  double max_disp;     /* largest safe displacement per step (0.5 rcut) */
  double weight_exp;   /* dpd_thermostat's exponent: the s of w_R = (1 - r/rc)^s of every pair
                          that does not set its own (pair_coef_t.s_exp is what the loops use) */
  int weight_exp_is_one;
  /* The time step and the constants derived from it, computed once. */
  double dt, half_dt; /* dt / 2: the half kicks */
  double inv_sqrt_dt; /* 1 / sqrt(dt): the random force */
  double vv_lambda;   /* Groot-Warren lambda */
  double predict_c;   /* (lambda - 1/2) dt: v~ = v + predict_c f / m */
  uint64_t seed;      /* of the pair random numbers */
  int pair_rng;       /* their generator: enum pair_rng (physics/pair_random.h; dpd_thermostat's
                         option rng, 0 = Philox4x32-10) */
  int n_species;
  double mass[SCENE_MAX_SPECIES], inv_mass[SCENE_MAX_SPECIES];
  int mobile[SCENE_MAX_SPECIES];
  /* Moving frozen species (species[].velocity, plane Couette): never integrated from forces, but
   * translated by wall_u dt every step with v = wall_u (the thermostat's wall velocity). */
  int moving[SCENE_MAX_SPECIES];
  double wall_u[SCENE_MAX_SPECIES][3];
  int any_moving;
  /* Densities of static frozen particles computed once (backend/cpu/density_pass.c,
   * backend/cuda/cuda_density.cu): their part from other static frozen particles is kept per
   * particle and each step adds only the mobile (and moving) neighbours' part. On when the plan has
   * a density pass and a static frozen species, unless MDPORE_DENSITY_CACHE=0 (comparisons); the
   * CUDA backend uses it only with MDPORE_DENSITY_CACHE=1 (there it cost more than it saved). */
  int density_cache;
  int static_frozen[SCENE_MAX_SPECIES]; /* frozen and not moving: its density part is cached */
  pair_coef_t coef[SCENE_MAX_SPECIES][SCENE_MAX_SPECIES];
  particle_effects_t particle; /* parameters of the per-particle effects (both backends) */
  /* Arrays the per-particle effects read (a pointer field inside `particle`, at byte `offset`,
   * allocated by the effect's configure with malloc and owned by the plan): a device backend copies
   * them and points its copy of `particle` at its own. */
  int n_arrays;
  struct {
    size_t offset, bytes;
  } arrays[PLAN_MAX_ARRAYS];
  /* The phase lists: set-up (forces of the first configuration) and every step. */
  int n_setup, n_step;
  unsigned char setup[PHASE_COUNT], step[PHASE_COUNT];
} plan_t;

#ifdef __cplusplus
extern "C" { /* the CUDA backend reads the plan */
#endif

/* Build and validate the plan. Returns 0, or -1 with a message in err (names the scene file). */
int plan_build(plan_t *plan, const scene_t *scene, char *err, size_t errlen);

/* Register the array whose pointer sits at byte `offset` of plan->particle (bytes long): 0 or -1
 * when the table is full. */
int plan_add_array(plan_t *plan, size_t offset, size_t bytes);
/* The host pointer of registered array k. */
void *plan_array(const plan_t *plan, int k);
/* Free the registered arrays (sim_destroy, and whoever builds a plan and drops it). */
void plan_release(plan_t *plan);

/* 1 when the plan's step (or set-up, setup = 1) list holds the phase. */
int plan_has_phase(const plan_t *plan, int setup, int phase);

#ifdef __cplusplus
}
#endif

#endif
