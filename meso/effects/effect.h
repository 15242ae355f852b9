/* An effect: one piece of physics a scene may name (meso/effects/<name>.c, one file each).
 * An effect declares what it needs from the engine (a density pass, per-particle arrays, ghost
 * fields, pair or per-particle work) and provides its work:
 *  - pair effects fill their constants into the per-species-pair table; the pair math itself lives
 * in meso/physics (shared with a GPU backend) and is evaluated by the backend's fused pair kernel
 * for the terms the plan selects (meso/backend/cpu/force_pass.c);
 *  - particle effects provide a per-particle function (body force) or a position constraint applied
 *    after the drift (box walls). */
#ifndef MESO_EFFECTS_EFFECT_H
#define MESO_EFFECTS_EFFECT_H

#include "engine/particles.h"
#include "engine/plan.h"
#include "io/scene.h"

#include <stdint.h>
#include <stdio.h>

enum effect_need {
  NEED_DENSITY_PASS = 1 << 0, /* rho array + density pass over r < rd + ghost sync of rho */
  NEED_GHOST_V = 1 << 1,      /* ghosts carry (predicted) velocities                       */
  NEED_PAIR = 1 << 2,         /* contributes a pair term (pair_term)                       */
  NEED_PARTICLE = 1 << 3,     /* per-particle force after the pair pass (particle_force)   */
  NEED_AFTER_DRIFT = 1 << 4   /* position constraint after the drift (after_drift)         */
};

/* Where a particle broke a constraint (for the error message). */
typedef struct {
  int64_t id;
  double x[3];
} effect_violation_t;

typedef struct effect {
  int id;             /* enum scene_effect */
  const char *name;   /* the scene's name for it */
  unsigned needs;     /* OR of enum effect_need */
  unsigned pair_term; /* enum plan_pair_term it adds (NEED_PAIR) */
  /* Validate the scene for this effect: -1 with a message in err; may print warnings to stderr. */
  int (*check)(const scene_t *scene, char *err, size_t errlen);
  /* NEED_PAIR: fill this effect's constants of species pair (a, b) into c. */
  void (*pair_coef)(const scene_t *scene, int a, int b, pair_coef_t *c);
  /* NEED_PARTICLE: add per-particle forces to the owned particles. */
  void (*particle_force)(const scene_t *scene, particles_t *p);
  /* NEED_AFTER_DRIFT: enforce the constraint on owned particles after x += dt v. Returns the number
   * of particles it could not bring back (first one in *bad). */
  long (*after_drift)(const scene_t *scene, const plan_t *plan, particles_t *p,
                      effect_violation_t *bad);
  /* One line (no newline) for --explain: what this effect does with this scene's numbers. */
  void (*describe)(const scene_t *scene, FILE *out);
} effect_t;

/* The effect with this id (enum scene_effect); never NULL for a valid id. */
const effect_t *effect_get(int id);

/* The effects' descriptors, one per file. */
extern const effect_t effect_mdpd_attraction, effect_mdpd_repulsion, effect_dpd_conservative,
    effect_dpd_thermostat, effect_body_force, effect_box_walls;

/* For describe(): print one pair parameter of every species pair a <= b, e.g. "liquid-liquid -40,
 * liquid-wall -30" (field = offsetof(scene_pair_t, A)), or just the value when all pairs agree. */
void effect_print_pair_param(const scene_t *scene, FILE *out, size_t field);

/* 1 when every species pair has the same value of a parameter (offsetof(scene_pair_t, ...)). */
int effect_pair_param_common(const scene_t *scene, size_t field);

#endif
