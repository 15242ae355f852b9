/* Whether a run's data can enter the Darcy range (campaign.h). A flow rate measured in a liquid that
 * has cavitated or been compressed by the forcing, or that the forcing has heated, or that never
 * settled, is not the linear response that k = mu q / G needs; such a run is reported and left out:
 *   the flux's steady state (MSER-5, meso/analysis/steady_state.c) was found, after 3x the
 *     liquid's pressure-diffusion time (meso/run/run_flux.c): a run that ended sooner still
 *     reads q high by the same fraction at every forcing;
 *   with --require-target, the run met its target error (off by default: most healthy runs of
 *     short campaigns stop at their step budget a little above it, with a larger error bar that the
 *     weighted fits already account for);
 *   temperature T: |T / kT - 1| <= temperature_tol (viscous heating the thermostat does not remove:
 *     the weakest run of a campaign reads 1.000 to 1.015, the CI slit's strongest 1.046,
 *     Berea crops at the strongest auto gradients 1.03 to 1.05; a run below kT by as much is not
 *     heated but its thermostat or integration is off, and is left out too);
 *   pore-core density n_core against the fill n_fill: |n_core / n_fill - 1| <= cavitation_tol. A
 *     core far below the fill has cavitated (a Berea crop at 0.5 rc per voxel: 4.0 to 4.8 against
 *     6.2). n_fill is the liquid's density the pores were filled to: an IMAGE's template adds what
 *     the walls adsorb (campaign_template.c), so its core sits at n_fill at rest; a scene's uniform
 *     fill leaves the core below it by that much (2-3% at wall density 4: 6.0-6.1 in the CI slit,
 *     6.02-6.03 in Berea crops at 1 rc per voxel), so this bound is looser than the next;
 *   pore-core density against the liquid at rest n_rest (the core of the axis's weakest admissible
 *     run): |n_core / n_rest - 1| <= density_tol: the forcing compresses the liquid ahead of
 *     constrictions and expands it behind them (Berea at 1 rc per voxel: 6.03 at rest, 5.81 at the
 *     strongest auto gradient). */
#include <math.h>
#include <stdio.h>

#include "campaign.h"

static int left_out(camp_flag *flag, const char *check, double measured) {
  flag->check = check;
  flag->measured = measured;
  return 0;
}

int camp_run_admissible(const camp_run *r, const camp_checks *lim, double n_rest, camp_flag *flag) {
  flag->check = "";
  flag->measured = NAN;
  flag->why[0] = 0;
  char *why = flag->why;
  const int len = (int)sizeof flag->why;
  if (r->steady == 0 && r->before_pressure) {
    snprintf(why, len,
             "the run ended at step %lld, within 3x the liquid's pressure-diffusion time (%.0f "
             "steps), while its flux still relaxes from above (give more --max-steps)",
             r->steps, r->pressure_steps);
    return left_out(flag, "unsteady", (double)r->steps);
  }
  if (r->steady == 0) {
    snprintf(why, len, "the flux reached no steady state in %lld steps", r->steps);
    return left_out(flag, "unsteady", (double)r->steps);
  }
  if (lim->require_target && r->reached == 0) {
    snprintf(
        why, len,
        "target error %g not met: relative error of q %.3g after %lld steps%s (--require-target)",
        r->target_error, r->rel_err, r->steps,
        r->plateau == 0 ? "; its blocked error found no plateau, so q_err is a lower bound" : "");
    return left_out(flag, "target_missed", r->rel_err);
  }
  if (isfinite(r->temperature) && lim->kT > 0 &&
      fabs(r->temperature / lim->kT - 1) > lim->temperature_tol) {
    const double off_kT = r->temperature / lim->kT - 1;
    snprintf(why, len, "temperature %.4g is %+.1f%% off kT = %g (%s; tolerance %.0f%%)",
             r->temperature, 100 * off_kT, lim->kT,
             off_kT > 0 ? "viscous heating" : "colder than the thermostat's kT",
             100 * lim->temperature_tol);
    return left_out(flag, off_kT > 0 ? "heated" : "cooled", r->temperature);
  }
  if (!isfinite(r->core_density)) return 1;
  const double off_fill = r->core_density / lim->fill_density - 1;
  if (lim->fill_density > 0 && fabs(off_fill) > lim->cavitation_tol) {
    snprintf(why, len,
             "pore-core density %.4g is %+.1f%% off the liquid's density %.4g that the pores "
             "were filled to (%s; tolerance %.0f%%)",
             r->core_density, 100 * off_fill, lim->fill_density,
             off_fill < 0 ? "the liquid cavitated" : "the liquid is compressed",
             100 * lim->cavitation_tol);
    return left_out(flag, off_fill < 0 ? "cavitated" : "compressed", r->core_density);
  }
  const double off_rest = n_rest > 0 ? r->core_density / n_rest - 1 : 0;
  if (fabs(off_rest) > lim->density_tol) {
    snprintf(why, len,
             "pore-core density %.4g is %+.1f%% off the liquid at rest %.4g (the weakest run's; "
             "the forcing %s it; tolerance %.0f%%)",
             r->core_density, 100 * off_rest, n_rest, off_rest < 0 ? "expanded" : "compressed",
             100 * lim->density_tol);
    return left_out(flag, off_rest < 0 ? "expanded_by_forcing" : "compressed_by_forcing",
                    r->core_density);
  }
  return 1;
}

void camp_checks_of(const camp_opts *o, const campaign *c, camp_checks *lim) {
  *lim = (camp_checks){
      .fill_density = c->fluid_density,
      .kT = c->kT,
      .density_tol = o ? o->density_tolerance : CAMP_DEFAULT_DENSITY_TOLERANCE,
      .cavitation_tol = o ? o->cavitation_tolerance : CAMP_DEFAULT_CAVITATION_TOLERANCE,
      .temperature_tol = o ? o->temperature_tolerance : CAMP_DEFAULT_TEMPERATURE_TOLERANCE,
      .require_target = o ? o->require_target : 0};
}

int camp_admit_rows(camp_run **rows, int n, const camp_checks *lim, camp_run **out,
                    camp_flag *flags, int *n_out) {
  double n_rest = 0; /* the liquid at rest: the core of the weakest run that passes the others */
  camp_flag flag;
  for (int i = 0; i < n && !(n_rest > 0); i++)
    if (camp_run_admissible(rows[i], lim, 0, &flag) && isfinite(rows[i]->core_density))
      n_rest = rows[i]->core_density;
  int kept = 0;
  *n_out = 0;
  for (int i = 0; i < n; i++) {
    if (camp_run_admissible(rows[i], lim, n_rest, &flag)) {
      rows[kept++] = rows[i];
      continue;
    }
    if (out && *n_out < CAMP_MAX_GRADIENTS) {
      out[*n_out] = rows[i];
      flags[*n_out] = flag;
      (*n_out)++;
    }
  }
  return kept;
}
