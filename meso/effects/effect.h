/* An effect: one piece of physics a scene may name, in one file (meso/effects/<name>.c) plus, for
 * what runs per particle on both backends, one MESO_HD header (meso/physics/<name>.h). An effect
 * owns everything about itself:
 *  - its scene options (defaults, parse) and its consistency check (scene.*: the scene parser calls
 *    them through the catalog; plan_build runs the check again on scenes built in code);
 *  - its name and what it needs from the engine (needs: a density pass with its rho array and halo,
 *    ghost velocities, a pair term, a per-particle force, a position constraint after the drift);
 *  - its cutoff rule (the ghost-layer width is the largest cutoff of the named effects);
 *  - its constants: per species pair (pair_coef) and per particle (configure: into plan.particle,
 *    which both backends evaluate through particle_effects_force / _after_drift);
 *  - its --explain line (describe).
 * The registry (effect_list.h + effect_registry.c) lists them. */
#ifndef MESO_EFFECTS_EFFECT_H
#define MESO_EFFECTS_EFFECT_H

#include "effects/plan.h"
#include "scene/scene.h"
#include "scene/scene_catalog.h"

#include <stdint.h>
#include <stdio.h>

enum effect_need {
  NEED_DENSITY_PASS = 1 << 0, /* rho array + density pass over r < rd + ghost sync of rho */
  NEED_GHOST_V = 1 << 1,      /* ghosts carry (predicted) velocities                       */
  NEED_PAIR = 1 << 2,         /* contributes a pair term (pair_term)                       */
  NEED_PARTICLE = 1 << 3,     /* per-particle force after the pair pass (PARTICLE_FORCE)   */
  NEED_AFTER_DRIFT = 1 << 4,  /* position constraint after the drift (AFTER_DRIFT)         */
  NEED_WALL_FIELD = 1 << 5    /* wall fraction phi + gradient per mobile particle (lists)   */
};

typedef struct effect {
  scene_effect_entry_t scene; /* name, pair parameters needed, option defaults/parser, check */
  int id;                     /* enum effect_id */
  unsigned needs;             /* OR of enum effect_need */
  unsigned pair_term;         /* enum plan_pair_term it adds (NEED_PAIR) */
  /* The cutoff this effect uses for species pair (a, b) (rc or rd); NULL: no pair range. */
  double (*cutoff)(const scene_t *scene, int a, int b);
  /* NEED_PAIR: fill this effect's constants of species pair (a, b) into c. */
  void (*pair_coef)(const scene_t *scene, int a, int b, pair_coef_t *c);
  /* Put this effect's constants into the plan (its plan.particle parameters, pair-pass globals,
   * arrays it reads per particle: plan_add_array). 0, or -1 with the reason in err. */
  int (*configure)(const scene_t *scene, plan_t *plan, char *err, size_t errlen);
  /* One line (no newline) for --explain: what this effect does with this scene's numbers. */
  void (*describe)(const scene_t *scene, FILE *out);
} effect_t;

/* The effect with this id (enum effect_id), or NULL. */
const effect_t *effect_get(int id);
/* Its name ("?" for an unknown id). */
const char *effect_name(int id);
/* The catalog the scene parser reads (names, pair parameters, option parsers, checks). */
const scene_catalog_t *effect_catalog(void);

/* Name an effect in a scene built in code: sets scene->effect[id] and the effect's option defaults
 * (what naming it in a scene file does before its options are parsed). */
void effect_name_in_scene(scene_t *scene, int id);

/* For describe(): print one pair parameter of every species pair a <= b, e.g. "liquid-liquid -40,
 * liquid-wall -30" (field = offsetof(scene_pair_t, A)), or just the value when all pairs agree. */
void effect_print_pair_param(const scene_t *scene, FILE *out, size_t field);

/* 1 when every species pair has the same value of a parameter (offsetof(scene_pair_t, ...)). */
int effect_pair_param_common(const scene_t *scene, size_t field);

#endif
