/* The scene options of the inlet_force effect (effects/inlet_force.c): the per-particle parameters
 * both backends apply (physics/inlet_force.h) plus the sample faces and the pressure probes that
 * the run's pressure-drop measurement reads (analysis/pressure_drop.h). */
#ifndef MESO_EFFECTS_INLET_FORCE_H
#define MESO_EFFECTS_INLET_FORCE_H

#include "physics/inlet_force.h"

typedef struct {
  inlet_force_params_t force;    /* g per species, axis, slab [lo, hi) (box_* set by the plan)   */
  int has_sample;                /* 1: `sample` given: the summary reports the pressure drop    */
  double sample_lo, sample_hi;   /* the porous sample's faces along the axis                   */
  double probe_gap, probe_width; /* probe slabs [lo - gap - width, lo - gap), [hi + gap, ...) */
} inlet_force_options_t;

#endif
