/* The options of dpd_thermostat (effects/dpd_thermostat.c), for scenes built in code:
 *   SCENE_EFFECT_OPTIONS(&scene, EFFECT_DPD_THERMOSTAT, dpd_thermostat_options_t)->rng = ...
 * after effect_name_in_scene(&scene, EFFECT_DPD_THERMOSTAT) (which sets the defaults). */
#ifndef MESO_EFFECTS_DPD_THERMOSTAT_H
#define MESO_EFFECTS_DPD_THERMOSTAT_H

/* Options as parsed; hashed bytewise into the physics hash (scene_physics_hash). rng = 0
 * (PAIR_RNG_PHILOX) leaves the bytes of a scene without the key as they were (the options start
 * zeroed), so its hash and its checkpoints are unchanged. */
typedef struct {
  double exponent; /* s of w_R = (1 - r/rc)^s (1) */
  int rng;         /* generator of xi_ij: enum pair_rng (physics/pair_random.h; 0 = philox) */
} dpd_thermostat_options_t;

#endif
