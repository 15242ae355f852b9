/* Reduced -> SI units of a campaign (docs/permeability.md, "Conventions and units"). The length
 * unit rc comes from --voxel-size / rc_per_voxel, else a SCENE's `units:` block
 * (common/units_block.h), else the image's own voxel size, else the mDPD water mapping (rc =
 * 0.82 nm for A = -40 with N_m = 3 water molecules per particle, physics.md section 4). Energy
 * kT = kB T (--temperature, else the block's). Mass: the block's, else a particle carries the
 * water of its volume, m = rho_water / n. Time tau = rc sqrt(m / kT). The formulas are
 * common/units.c's (shared with mdpore run). This is the dimensional mapping: it is not tuned to
 * water's viscosity (mDPD water's mu maps about 6x below real water's; physics.md section 4).
 * k = mu q / G is a length squared in any consistent units, so k[m^2] = k* rc^2 does not depend
 * on that choice; G in Pa/m and q in m/s do. */
#include <math.h>

#include "campaign.h"

void camp_units_make(double rc_m, double n, double temperature_K, camp_units *u) {
  units_make(rc_m, UNITS_KB * temperature_K, units_water_mass(rc_m, n), u);
}

void camp_units_of(const campaign *c, camp_units *u) {
  const double rc = c->length_unit_m;
  const double energy = c->energy_J > 0 ? c->energy_J : UNITS_KB * c->temperature_K;
  const double mass =
      c->particle_mass_kg > 0 ? c->particle_mass_kg : units_water_mass(rc, c->fluid_density);
  units_make(rc, energy, mass, u);
}
