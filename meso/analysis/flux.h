/* The flux output's definitions (output.flux; docs/scene-format.md): from the per-species sums of
 * sim_flux_sums to the superficial (Darcy) velocity q, the volumetric flow rate Q and the driving
 * gradient G of one sample. The conventions, stated in every output:
 *
 *   A_total = V / L            the WHOLE box cross-section normal to the axis, solid included
 *   Q = (1/L) sum_s (1/n_s) sum_{i in s} v_axis,i      volumetric flow rate (volume per time)
 *   q = Q / A_total = (1/V) sum_s (1/n_s) sum_{i in s} v_axis,i   superficial (Darcy) velocity
 *
 * over the mobile particles of the counted species s (physics.md section 4). Q is the flow rate
 * through a cross-section averaged over the length L: (1/L) int u dV, each particle standing for the
 * fluid volume 1/n_s. n_s is the number density the scene fills the fluid at: N_s / (volume of the
 * initial.fill regions of s), the realised fill density; geometry.fluid_density for a geometry
 * scene; output.flux.density when given (required for other initial configurations). So
 * q = phi u_mean with phi = sum_s N_s / (n_s V) the fluid fraction of the box and u_mean the mean
 * particle velocity (one species).
 *
 * Per phase (output.flux.phases): each listed species' own share of the same sum,
 *   q_p = (1/V) (1/n_p) sum_{i in p} v_axis,i,    so q = sum_p q_p when the phases are the counted
 * species (the superficial velocity of each liquid; relative permeabilities, docs/relperm.md).
 *
 * G = -dp/dx, the driving gradient: with body_force, the body force per fluid volume,
 * G = sum_s N_s F_s,axis / V_fluid, V_fluid = sum_s N_s / n_s (one species: G = n F = n m g with g
 * the acceleration); NaN with reverse_along (no net gradient); 0 without a driving effect.
 * With inlet_force and its `sample` (pressure-driven) G is measured per sample from
 * the pressure drop across the sample (analysis/pressure_drop.h; the run's flux hook sets it): NaN
 * here. */
#ifndef MESO_ANALYSIS_FLUX_H
#define MESO_ANALYSIS_FLUX_H

#include "scene/scene.h"

enum flux_density_source { FLUX_DENSITY_GIVEN, FLUX_DENSITY_FILL, FLUX_DENSITY_GEOMETRY };
enum flux_gradient_source { FLUX_G_NONE, FLUX_G_BODY_FORCE, FLUX_G_REVERSE, FLUX_G_PRESSURE };

typedef struct {
  int axis;
  unsigned mask;                    /* counted species */
  double volume, length, area;      /* V, L_axis, A_total = V / L_axis */
  double n[SCENE_MAX_SPECIES];      /* number density of each counted species */
  double count[SCENE_MAX_SPECIES];  /* mobile particles of each counted species (at set-up) */
  double n_counted, fluid_fraction; /* sum N_s; phi = sum_s N_s / (n_s V) */
  double mass_density;              /* rho = sum_s N_s m_s / V_fluid */
  int density_source;               /* enum flux_density_source */
  int gradient_source;              /* enum flux_gradient_source */
  double G;                         /* driving gradient (NaN: none defined) */
  int n_phases;                     /* output.flux.phases (0: none) */
  int phase[SCENE_MAX_SPECIES];     /* their species */
} flux_def_t;

typedef struct {
  long step;
  double time, q, Q, G, u, N;        /* u: mean v_axis of the counted particles; N: their number */
  double q_phase[SCENE_MAX_SPECIES]; /* q_p of each of def.phase (output.flux.phases) */
  double N_phase[SCENE_MAX_SPECIES]; /* its mobile particles */
} flux_sample_t;

/* The definitions for a scene with output.flux, from the global counts of sim_flux_sums. 0, or -1
 * with the reason in err (a counted species without particles). */
int flux_def_init(flux_def_t *d, const scene_t *s, const double count[SCENE_MAX_SPECIES], char *err,
                  size_t errlen);
/* One sample from the global sums of sim_flux_sums. */
void flux_sample(const flux_def_t *d, long step, double time, const double count[SCENE_MAX_SPECIES],
                 const double vsum[SCENE_MAX_SPECIES], flux_sample_t *out);
/* Text of the sources, for headers and summaries. */
const char *flux_density_source_name(int source);
const char *flux_gradient_source_name(int source);

#endif
