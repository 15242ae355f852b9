/* The flux output's definitions (see flux.h). */
#include "analysis/flux.h"
#include "effects/effect_list.h"
#include "effects/inlet_force.h"

#include <math.h>
#include <stdio.h>

static double fill_volume(const scene_t *s, int species) {
  double v = 0;
  for (int k = 0; k < s->init.n_fill; k++) {
    const scene_fill_t *f = &s->init.fill[k];
    if (f->species != species) continue;
    double w = 1;
    for (int d = 0; d < 3; d++) w *= f->hi[d] - f->lo[d];
    v += w;
  }
  return v;
}

int flux_def_init(flux_def_t *d, const scene_t *s, const double count[SCENE_MAX_SPECIES], char *err,
                  size_t errlen) {
  *d = (flux_def_t){.axis = s->flux.axis, .mask = s->flux.species_mask, .G = 0};
  d->volume = 1;
  for (int k = 0; k < 3; k++) d->volume *= s->box_hi[k] - s->box_lo[k];
  d->length = s->box_hi[d->axis] - s->box_lo[d->axis];
  d->area = d->volume / d->length;
  d->density_source = s->flux.density > 0 ? FLUX_DENSITY_GIVEN
                      : s->geometry.on    ? FLUX_DENSITY_GEOMETRY
                                          : FLUX_DENSITY_FILL;
  double fluid_volume = 0, force = 0, mass = 0;
  for (int sp = 0; sp < s->n_species; sp++) {
    if (!(d->mask >> sp & 1u)) continue;
    if (!(count[sp] > 0)) {
      snprintf(err, errlen,
               "key 'output.flux.species': expected particles of species '%s' to count (got none)",
               s->species[sp].name);
      return -1;
    }
    d->count[sp] = count[sp];
    d->n_counted += count[sp];
    switch (d->density_source) {
    case FLUX_DENSITY_GIVEN:
      d->n[sp] = s->flux.density;
      break;
    case FLUX_DENSITY_GEOMETRY:
      d->n[sp] = s->geometry.fluid_density;
      break;
    default: {
      const double v = fill_volume(s, sp);
      if (!(v > 0)) {
        snprintf(err, errlen,
                 "key 'output.flux.density': expected the fluid number density of species '%s' "
                 "(no initial.fill region holds it)",
                 s->species[sp].name);
        return -1;
      }
      d->n[sp] = count[sp] / v; /* the realised fill density (lattice fills round it) */
    }
    }
    fluid_volume += count[sp] / d->n[sp];
    mass += count[sp] * s->species[sp].mass;
    if (s->effect[EFFECT_BODY_FORCE]) {
      const body_force_params_t *b =
          SCENE_EFFECT_OPTIONS(s, EFFECT_BODY_FORCE, const body_force_params_t);
      force += count[sp] * b->g[sp][d->axis];
    }
  }
  d->n_phases = s->flux.n_phases;
  for (int k = 0; k < d->n_phases; k++) d->phase[k] = s->flux.phase_species[k];
  d->fluid_fraction = fluid_volume / d->volume;
  d->mass_density = fluid_volume > 0 ? mass / fluid_volume : 0;
  /* G: the body force per fluid volume. A pressure-driven run (reservoir pistons)
   * adds its source here and measures G per sample in flux_sample. */
  if (s->effect[EFFECT_BODY_FORCE]) {
    const body_force_params_t *b =
        SCENE_EFFECT_OPTIONS(s, EFFECT_BODY_FORCE, const body_force_params_t);
    d->gradient_source = b->reverse_axis >= 0 ? FLUX_G_REVERSE : FLUX_G_BODY_FORCE;
    d->G = b->reverse_axis >= 0 ? NAN : force / fluid_volume;
  }
  if (s->effect[EFFECT_INLET_FORCE] &&
      SCENE_EFFECT_OPTIONS(s, EFFECT_INLET_FORCE, const inlet_force_options_t)->has_sample) {
    d->gradient_source = FLUX_G_PRESSURE; /* measured per sample: run/run_flux.c */
    d->G = NAN;
  }
  return 0;
}

void flux_sample(const flux_def_t *d, long step, double time, const double count[SCENE_MAX_SPECIES],
                 const double vsum[SCENE_MAX_SPECIES], flux_sample_t *out) {
  double vol_flux = 0, n = 0, v = 0; /* sum_s vsum_s / n_s = int u dV */
  for (int sp = 0; sp < SCENE_MAX_SPECIES; sp++) {
    if (!(d->mask >> sp & 1u)) continue;
    vol_flux += vsum[sp] / d->n[sp];
    n += count[sp];
    v += vsum[sp];
  }
  out->step = step;
  out->time = time;
  out->Q = vol_flux / d->length;
  out->q = out->Q / d->area;
  out->G = d->G; /* constant for a body force; a pressure-driven run measures it here */
  out->u = n > 0 ? v / n : 0;
  out->N = n;
  for (int k = 0; k < d->n_phases; k++) { /* the same terms as q's sum, one species each */
    const int sp = d->phase[k];
    out->q_phase[k] = vsum[sp] / d->n[sp] / d->length / d->area;
    out->N_phase[k] = count[sp];
  }
}

const char *flux_density_source_name(int source) {
  switch (source) {
  case FLUX_DENSITY_GIVEN:
    return "output.flux.density";
  case FLUX_DENSITY_GEOMETRY:
    return "geometry.fluid_density";
  default:
    return "initial.fill (realised: N / fill volume)";
  }
}

const char *flux_gradient_source_name(int source) {
  switch (source) {
  case FLUX_G_BODY_FORCE:
    return "body_force: G = sum_s N_s F_s / V_fluid = n F";
  case FLUX_G_REVERSE:
    return "body_force with reverse_along: no net gradient";
  case FLUX_G_PRESSURE:
    return "inlet_force: G = (P_in - P_out) / L_sample, measured per sample between probe slabs "
           "outside the sample faces";
  default:
    return "none: no driving effect";
  }
}
