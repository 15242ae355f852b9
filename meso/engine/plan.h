/* The step plan: what the engine does each step, built from the effects a scene names.
 * An effect that is not named contributes nothing: no array, no pass, no pair term, no message. */
#ifndef MESO_ENGINE_PLAN_H
#define MESO_ENGINE_PLAN_H

#include "io/scene.h"

#include <stddef.h>

/* Pair terms the fused force kernel can evaluate (meso/backend/cpu/force_pass.c). */
enum plan_pair_term {
  PAIR_TERM_CONSERVATIVE = 1, /* A w_c(r): mdpd_attraction (A < 0) or dpd_conservative (a > 0) */
  PAIR_TERM_MANYBODY = 2,     /* B (rho_i + rho_j) w_d(r): mdpd_repulsion                       */
  PAIR_TERM_THERMOSTAT = 4    /* -gamma w_R^2 (e.v) + sigma w_R xi / sqrt(dt): dpd_thermostat     */
};

/* Constants of one species pair, precomputed once so the pair loop has no division or pow (s = 1).
 */
typedef struct {
  double A;            /* conservative amplitude (0 when no conservative term is named) */
  double B;            /* many-body amplitude                                           */
  double gamma, sigma; /* sigma^2 = 2 gamma kT (fluctuation-dissipation)                 */
  double rc, inv_rc, rc2;
  double rd, inv_rd, rd2;
  double wnorm; /* density-kernel normalisation for this rd (w_rho_norm) */
  double cut2;  /* square of the largest cutoff any named pair term uses for this pair */
} pair_coef_t;

typedef struct {
  int named[EFFECT_COUNT]; /* copy of scene.effect */
  int pair_terms;          /* OR of enum plan_pair_term */
  int density;             /* 1: density pass + rho ghost sync (mdpd_repulsion) */
  int density_kernel;      /* enum meso_density_kernel */
  int ghost_v;             /* ghosts carry (predicted) velocities (dpd_thermostat) */
  int use_vpred;       /* a separate predicted-velocity array (thermostat and vv_lambda != 0.5) */
  int particle_forces; /* per-particle forces (body_force) */
  int walls;           /* reflecting box walls (box_walls) */
  double rcut;         /* ghost-layer width = largest cutoff in use */
  double max_disp;     /* largest safe displacement per step (0.5 rcut) */
  double weight_exp;   /* s of w_R = (1 - r/rc)^s */
  int weight_exp_is_one;
  int n_species;
  double mass[SCENE_MAX_SPECIES], inv_mass[SCENE_MAX_SPECIES];
  int mobile[SCENE_MAX_SPECIES];
  pair_coef_t coef[SCENE_MAX_SPECIES][SCENE_MAX_SPECIES];
} plan_t;

/* Build and validate the plan. Returns 0, or -1 with a message in err (names the scene file). */
int plan_build(plan_t *plan, const scene_t *scene, char *err, size_t errlen);

#endif
