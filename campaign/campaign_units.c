/* Reduced -> SI units of a campaign (docs/permeability.md, "Units"). The length unit rc comes from
 * the voxel size (rc = voxel / rc_per_voxel) or, without one, from the mDPD water mapping (rc =
 * 0.82 nm for A = -40 with N_m = 3 water molecules per particle, physics.md section 4). Energy kT =
 * kB T. Mass: a particle carries the water of its volume, m = rho_water / n (n particles per rc^3),
 * i.e. N_m = m / m_water molecules. Time tau = rc sqrt(m / kT). This is the dimensional mapping: it
 * is not tuned to water's viscosity (mDPD water's mu maps about 5x below real water's; physics.md
 * section 4). k = mu q / G is a length squared in any consistent units, so k[m^2] = k* rc^2 does not
 * depend on that choice; G in Pa/m and q in m/s do. */
#include <math.h>

#include "campaign.h"

#define KB 1.380649e-23        /* J/K */
#define RHO_WATER 997.0        /* kg/m^3 at 25 C */
#define M_WATER 2.99150711e-26 /* kg, 18.015 u */

void camp_units_make(double rc_m, double n, double temperature_K, camp_units *u) {
  u->rc_m = rc_m;
  u->kT_J = KB * temperature_K;
  u->mass_kg = RHO_WATER * rc_m * rc_m * rc_m / n;
  u->n_molecules = u->mass_kg / M_WATER;
  u->tau_s = rc_m * sqrt(u->mass_kg / u->kT_J);
  u->G_Pa_per_m = u->kT_J / (rc_m * rc_m * rc_m * rc_m);
  u->q_m_per_s = rc_m / u->tau_s;
  u->mu_Pa_s = u->mass_kg / (rc_m * u->tau_s);
  u->k_m2 = rc_m * rc_m;
}
