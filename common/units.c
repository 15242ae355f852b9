/* Reduced -> SI factors (units.h). */
#include "common/units.h"

#include <math.h>
#include <stdio.h>

double units_water_rc(double n_molecules, double n) {
  return cbrt(n_molecules * n * UNITS_M_WATER / UNITS_RHO_WATER);
}

double units_water_mass(double rc_m, double n) {
  return UNITS_RHO_WATER * rc_m * rc_m * rc_m / n;
}

void units_make(double rc_m, double energy_J, double mass_kg, units_si_t *u) {
  u->rc_m = rc_m;
  u->kT_J = energy_J;
  u->mass_kg = mass_kg;
  u->tau_s = rc_m * sqrt(mass_kg / energy_J);
  u->q_m_per_s = rc_m / u->tau_s;
  u->p_Pa = energy_J / (rc_m * rc_m * rc_m);
  u->G_Pa_per_m = u->p_Pa / rc_m;
  u->mu_Pa_s = mass_kg / (rc_m * u->tau_s);
  u->k_m2 = rc_m * rc_m;
  u->k_nD = u->k_m2 * UNITS_NANODARCY_PER_M2;
  u->n_molecules = mass_kg / UNITS_M_WATER;
}

void units_mapping_describe(const units_mapping_t *m, char *out, int len) {
  const units_si_t *u = &m->si;
  char energy[128], mass[160];
  if (isfinite(m->temperature_K))
    snprintf(energy, sizeof energy, "e = kB T / kT, T = %g K", m->temperature_K);
  else
    snprintf(energy, sizeof energy, "e = %.4g J (units.energy)", u->kT_J);
  if (m->mapping == UNITS_MAPPING_WATER)
    snprintf(mass, sizeof mass, "m = N_m m_water = %.4g kg", u->mass_kg);
  else if (m->mass_given)
    snprintf(mass, sizeof mass, "m = %.4g kg (units.mass)", u->mass_kg);
  else if (m->tau_given)
    snprintf(mass, sizeof mass, "m = e tau^2 / rc^2 = %.4g kg (units.tau)", u->mass_kg);
  else
    snprintf(mass, sizeof mass, "m = rho_water / n = %.4g kg (the water of a particle's volume)",
             u->mass_kg);
  snprintf(out, len,
           "%s: rc = %.4g m (%s), %s, %s (%.3g water molecules), tau = rc sqrt(m / e) = %.4g s. "
           "Dimensional mapping, not viscosity-matched: 1 reduced viscosity = %.4g Pa s, so the "
           "standard mDPD water's mu = %g maps to %.3g Pa s vs real water's %.2g Pa s "
           "(physics.md section 4); k in m^2 needs only rc",
           m->mapping == UNITS_MAPPING_WATER ? "mDPD water mapping" : "own units", u->rc_m,
           m->length_source, energy, mass, u->n_molecules, u->tau_s, u->mu_Pa_s,
           UNITS_MDPD_WATER_MU, UNITS_MDPD_WATER_MU * u->mu_Pa_s, UNITS_WATER_VISCOSITY);
}
