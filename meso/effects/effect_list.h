/* The registry of effects: THE list every other piece is generated from (ids, names, the descriptor
 * table, the per-particle parameters the device carries and the per-particle calls of both
 * backends). Adding an effect NAME of kind K is its files (effects/NAME.c, and for a per-particle
 * effect physics/NAME.h) plus one line in MESO_EFFECT_LIST below (and, for a per-particle effect,
 * the #include of its physics header). docs/engine-core.md has the recipe.
 *
 * Kinds:
 *   PAIR            a pair term of the fused pair kernel (constants through effect_t.pair_coef)
 *   PARTICLE_FORCE  physics/NAME.h: NAME_params_t, NAME_particle_force(prm, species, x, f)
 *   AFTER_DRIFT     physics/NAME.h: NAME_params_t, NAME_after_drift(prm, i, x, v, x_old) -> 1 if bad
 *                   (i: the particle's index in the backend's current order, for per-particle state)
 * Plain C: included by the CUDA kernels too. */
#ifndef MESO_EFFECTS_EFFECT_LIST_H
#define MESO_EFFECTS_EFFECT_LIST_H

#include "physics/body_force.h"
#include "physics/bounce_back.h"
#include "physics/box_walls.h"
#include "physics/inlet_force.h"
#include "physics/wall_boundary.h"

/* X(name, ID, kind), in the order --explain lists them and the backends apply them (bounce_back
 * after wall_boundary: the voxel guard has the last word). */
#define MESO_EFFECT_LIST(X)                                                                        \
  X(mdpd_attraction, MDPD_ATTRACTION, PAIR)                                                        \
  X(mdpd_repulsion, MDPD_REPULSION, PAIR)                                                          \
  X(dpd_conservative, DPD_CONSERVATIVE, PAIR)                                                      \
  X(dpd_thermostat, DPD_THERMOSTAT, PAIR)                                                          \
  X(body_force, BODY_FORCE, PARTICLE_FORCE)                                                        \
  X(inlet_force, INLET_FORCE, PARTICLE_FORCE)                                                      \
  X(box_walls, BOX_WALLS, AFTER_DRIFT)                                                             \
  X(wall_boundary, WALL_BOUNDARY, AFTER_DRIFT)                                                     \
  X(bounce_back, BOUNCE_BACK, AFTER_DRIFT)

#define MESO_EFFECT_ENUM_(name, ID, kind) EFFECT_##ID,
enum effect_id { MESO_EFFECT_LIST(MESO_EFFECT_ENUM_) EFFECT_COUNT };

/* The parameters of the named per-particle effects, by value (plan_t.particle; the CUDA kernels get
 * a copy in their launch parameters). on[EFFECT_x] = 1 when the effect is named. */
#define MESO_PARAMS_PAIR(name)
#define MESO_PARAMS_PARTICLE_FORCE(name) name##_params_t name;
#define MESO_PARAMS_AFTER_DRIFT(name) name##_params_t name;
#define MESO_PARAMS_(name, ID, kind) MESO_PARAMS_##kind(name)
typedef struct {
  int on[EFFECT_COUNT];
  MESO_EFFECT_LIST(MESO_PARAMS_)
} particle_effects_t;

/* Add the per-particle forces of the named PARTICLE_FORCE effects to f. */
#define MESO_FORCE_PAIR(name, ID)
#define MESO_FORCE_AFTER_DRIFT(name, ID)
#define MESO_FORCE_PARTICLE_FORCE(name, ID)                                                        \
  if (pe->on[EFFECT_##ID]) name##_particle_force(&pe->name, species, x, f);
#define MESO_FORCE_(name, ID, kind) MESO_FORCE_##kind(name, ID)
MESO_HD void particle_effects_force(const particle_effects_t *pe, int species, const double x[3],
                                    double f[3]) {
  (void)pe, (void)species, (void)x, (void)f;
  MESO_EFFECT_LIST(MESO_FORCE_)
}

/* Apply the position constraints of the named AFTER_DRIFT effects; returns 1 when one of them could
 * not bring the particle back (lost). */
#define MESO_DRIFT_PAIR(name, ID)
#define MESO_DRIFT_PARTICLE_FORCE(name, ID)
#define MESO_DRIFT_AFTER_DRIFT(name, ID)                                                           \
  if (pe->on[EFFECT_##ID]) bad |= name##_after_drift(&pe->name, i, x, v, x_old);
#define MESO_DRIFT_(name, ID, kind) MESO_DRIFT_##kind(name, ID)
MESO_HD int particle_effects_after_drift(const particle_effects_t *pe, int i, double x[3],
                                         double v[3], const double x_old[3]) {
  int bad = 0;
  (void)pe, (void)i, (void)x, (void)v, (void)x_old;
  MESO_EFFECT_LIST(MESO_DRIFT_)
  return bad;
}

#endif
