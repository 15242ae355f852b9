/* The viscosity a campaign uses in k = mu q / G (campaign.h): for the standard mDPD water, the
 * one at the density the fluid has in the pore core, measured by every run (`pore_core_density`
 * of summary.json, meso/analysis/penetration.h).
 *
 * Why: the builder fills the pores at 6.2 particles per rc^3 of pore, but the first voxel layer at
 * a wall holds ~8% more, so the core's density depends on the geometry: 6.00 in the BCC pack's
 * narrow throats, 6.17 around the dilute sphere array's spheres (validation/permeability/
 * pore_density.py). The mDPD viscosity grows with density by 1.57 per unit (0.28 per cent per
 * 0.01), so one fixed mu is off by up to 3% from pore to pore. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "campaign.h"

/* Reverse Poiseuille (validation/engine/viscosity.py --rho n, box 10 x 20 x 10, 15,000 averaged
 * steps) at 11 densities 5.9-6.4 (9 on an H200, 2 on the CPU), least squares:
 * mu = 5.636 (+- 0.017) + 1.572 (+- 0.121) (n - 6.2), scatter of a point about the line 0.054
 * (validation/results/engine/viscosity_density.md). */
#define WATER_MU_AT_6_2 5.636
#define WATER_MU_SLOPE 1.572
#define WATER_MU_N_LO 5.9
#define WATER_MU_N_HI 6.4

double camp_water_viscosity(double n) {
  return WATER_MU_AT_6_2 + WATER_MU_SLOPE * (n - 6.2);
}

/* No --viscosity: the campaign takes its fluid for the standard mDPD water (an image's template is
 * that water; a scene's is assumed to be, as the note at its planning says). */
static int standard_water(const campaign *c) {
  return !strncmp(c->viscosity_source, "mDPD A=-40", 10);
}

void camp_core_viscosity(campaign *c) {
  if (!standard_water(c)) return;
  /* The gentlest run's core: a strong body force compresses the fluid ahead of the obstacles and
   * thins it behind, so the core's mean density falls with forcing (FCC pack, g = 0.69: 5.42
   * against 5.95 at g = 0.069); Darcy's k belongs to the fluid at rest. */
  const camp_run *gentlest = NULL;
  for (int i = 0; i < c->n_runs; i++) {
    const camp_run *r = &c->runs[i];
    if (r->have && isfinite(r->core_density) && (!gentlest || fabs(r->g) < fabs(gentlest->g)))
      gentlest = r;
  }
  if (!gentlest) {
    printf("viscosity: mu = %g (the bulk liquid's at n = 6.07): no run measured a pore core (pore "
           "voxels >= 1.5 rc from the solid)\n",
           c->viscosity);
    return;
  }
  const double core = gentlest->core_density, core_err = gentlest->core_density_err;
  if (core < WATER_MU_N_LO || core > WATER_MU_N_HI) {
    printf("viscosity: mu = %g (the bulk liquid's at n = 6.07): the pore core's density %.4f is "
           "outside the measured range %g-%g\n",
           c->viscosity, core, WATER_MU_N_LO, WATER_MU_N_HI);
    return;
  }
  c->viscosity = camp_water_viscosity(core);
  snprintf(c->viscosity_source, sizeof c->viscosity_source,
           "mDPD A=-40 B=25 gamma=4.5 rd=0.75 at the pore core's density n = %.4f +- %.1g (the run "
           "of the smallest body force, g = %g): mu = %.3f + %.3f (n - 6.2) "
           "(validation/results/engine/viscosity_density)",
           core, core_err, gentlest->g, WATER_MU_AT_6_2, WATER_MU_SLOPE);
  printf("viscosity: mu = %.4f, the standard mDPD water's at the pore core's density %.4f (the "
         "fluid >= 1.5 rc from the solid in the run of the smallest body force, g = %g; 5.41 is "
         "the bulk liquid's at 6.07)\n",
         c->viscosity, core, gentlest->g);
}
