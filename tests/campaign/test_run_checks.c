/* The checks that leave a run out of the Darcy range (campaign/campaign_checks.c): a cavitated core
 * (the Berea crop at 0.5 rc per voxel: 4.0-4.8 against a fill of 6.2), a compressed one, a heated
 * or too cold liquid, an unsteady flux, a core the forcing expanded and (with --require-target) a
 * missed target are left out with the check's name, the measured value and a reason naming it; a
 * run at rest, 2-3% below the fill as the walls leave it, a run within 3% of the liquid at rest and
 * (by default) a run that missed its target are kept. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "campaign.h"

static int failures;

static void check(int ok, const char *what, const char *why) {
  printf("%s %s%s%s\n", ok ? "ok  " : "FAIL", what, why[0] ? ": " : "", why);
  if (!ok) failures++;
}

static camp_run run_with(double core, double T, int steady) {
  camp_run r;
  memset(&r, 0, sizeof r);
  r.core_density = core;
  r.temperature = T;
  r.steady = steady;
  r.reached = -1;
  r.plateau = -1;
  r.target_error = NAN;
  r.steps = 12000;
  return r;
}

/* Left out by the named check with the measured value. */
static int out_by(int admissible, const camp_flag *f, const char *name, double measured) {
  return !admissible && !strcmp(f->check, name) && fabs(f->measured - measured) < 1e-12;
}

int main(void) {
  const camp_checks lim = {.fill_density = 6.2,
                           .kT = 1.0,
                           .density_tol = CAMP_DEFAULT_DENSITY_TOLERANCE,
                           .cavitation_tol = CAMP_DEFAULT_CAVITATION_TOLERANCE,
                           .temperature_tol = CAMP_DEFAULT_TEMPERATURE_TOLERANCE};
  const double rest = 6.025; /* a Berea crop's core at rest, 1 rc per voxel */
  camp_flag f;
  const char *why = f.why;
  camp_run r = run_with(rest, 1.005, 1);
  check(camp_run_admissible(&r, &lim, rest, &f) == 1 && !why[0],
        "at rest (2.8% below the fill, 0.5% warm): kept", why);
  r = run_with(4.4, 1.01, 1);
  check(!camp_run_admissible(&r, &lim, rest, &f) && strstr(why, "cavitated") && strstr(why, "4.4"),
        "a core of 4.4 against the fill 6.2: left out as cavitated", why);
  r = run_with(4.4, 1.01, 1);
  check(!camp_run_admissible(&r, &lim, 0, &f) && strstr(why, "cavitated"),
        "cavitation is found without a liquid at rest too", why);
  r = run_with(rest, 1.06, 1);
  check(!camp_run_admissible(&r, &lim, rest, &f) && strstr(why, "heating") && strstr(why, "1.06"),
        "T = 1.06: left out as heated", why);
  r = run_with(rest, 1.045, 1);
  check(camp_run_admissible(&r, &lim, rest, &f) == 1,
        "T = 1.045 (the CI slit's strongest run): kept", why);
  r = run_with(rest, 1.0, 0);
  check(!camp_run_admissible(&r, &lim, rest, &f) && strstr(why, "steady"),
        "no steady state: left out", why);
  r = run_with(5.81, 1.01, 1);
  check(!camp_run_admissible(&r, &lim, rest, &f) && strstr(why, "expanded"),
        "5.81 against 6.025 at rest (-3.6%): left out as expanded by the forcing", why);
  r = run_with(5.9, 1.01, 1);
  check(camp_run_admissible(&r, &lim, rest, &f) == 1, "5.9 against 6.025 at rest (-2.1%): kept",
        why);
  r = run_with(NAN, NAN, -1);
  check(camp_run_admissible(&r, &lim, rest, &f) == 1,
        "no core, no temperature, steadiness unknown (a scene without geometry): kept", why);
  r = run_with(4.4, 1.01, 1);
  check(out_by(camp_run_admissible(&r, &lim, rest, &f), &f, "cavitated", 4.4),
        "cavitated: check 'cavitated', measured 4.4", why);
  r = run_with(6.9, 1.01, 1);
  check(out_by(camp_run_admissible(&r, &lim, 0, &f), &f, "compressed", 6.9) &&
            strstr(why, "compressed") && strstr(why, "+11.3%"),
        "a core of 6.9 against the fill 6.2 (+11.3%): left out as compressed", why);
  r = run_with(rest, 1.06, 1);
  check(out_by(camp_run_admissible(&r, &lim, rest, &f), &f, "heated", 1.06),
        "T = 1.06: check 'heated', measured 1.06", why);
  r = run_with(rest, 0.93, 1);
  check(out_by(camp_run_admissible(&r, &lim, rest, &f), &f, "cooled", 0.93) &&
            strstr(why, "colder") && !strstr(why, "heating"),
        "T = 0.93: left out as colder than kT, not as heated", why);
  r = run_with(rest, 1.0, 0);
  check(out_by(camp_run_admissible(&r, &lim, rest, &f), &f, "unsteady", 12000),
        "unsteady: check 'unsteady', measured the 12000 steps run", why);
  r = run_with(5.81, 1.01, 1);
  check(out_by(camp_run_admissible(&r, &lim, rest, &f), &f, "expanded_by_forcing", 5.81),
        "expanded by the forcing: its check and core density", why);
  r = run_with(rest, 1.005, 1);
  r.reached = 0;
  r.target_error = 0.05;
  r.rel_err = 0.09;
  r.plateau = 0;
  check(camp_run_admissible(&r, &lim, rest, &f) == 1,
        "a missed target (relative error 0.09 > 0.05): kept by default", why);
  camp_checks strict = lim;
  strict.require_target = 1;
  check(out_by(camp_run_admissible(&r, &strict, rest, &f), &f, "target_missed", 0.09) &&
            strstr(why, "0.09") && strstr(why, "lower bound"),
        "a missed target with --require-target: left out, its relative error and no plateau named",
        why);
  r.reached = 1;
  check(camp_run_admissible(&r, &strict, rest, &f) == 1, "a met target with --require-target: kept",
        why);
  r = run_with(rest, 1.005, 1);
  check(camp_run_admissible(&r, &lim, rest, &f) == 1 && !f.check[0] && isnan(f.measured),
        "admissible: no check named, no value", why);
  printf("%d failures\n", failures);
  return failures ? 1 : 0;
}
