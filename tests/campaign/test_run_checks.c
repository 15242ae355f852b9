/* The checks that leave a run out of the Darcy range (campaign/campaign_checks.c): a cavitated core
 * (the Berea crop at 0.5 rc per voxel: 4.0-4.8 against a fill of 6.2), a heated liquid, an unsteady
 * flux and a core the forcing expanded are left out with a reason naming the value; a run at rest,
 * 2-3% below the fill as the walls leave it, and a run within 3% of the liquid at rest are kept. */
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
  r.steps = 12000;
  return r;
}

int main(void) {
  const camp_checks lim = {.fill_density = 6.2,
                           .kT = 1.0,
                           .density_tol = CAMP_DEFAULT_DENSITY_TOLERANCE,
                           .cavitation_tol = CAMP_DEFAULT_CAVITATION_TOLERANCE,
                           .temperature_tol = CAMP_DEFAULT_TEMPERATURE_TOLERANCE};
  const double rest = 6.025; /* a Berea crop's core at rest, 1 rc per voxel */
  char why[256];
  camp_run r = run_with(rest, 1.005, 1);
  check(camp_run_admissible(&r, &lim, rest, why, sizeof why) == 1 && !why[0],
        "at rest (2.8% below the fill, 0.5% warm): kept", why);
  r = run_with(4.4, 1.01, 1);
  check(!camp_run_admissible(&r, &lim, rest, why, sizeof why) && strstr(why, "cavitated") &&
            strstr(why, "4.4"),
        "a core of 4.4 against the fill 6.2: left out as cavitated", why);
  r = run_with(4.4, 1.01, 1);
  check(!camp_run_admissible(&r, &lim, 0, why, sizeof why) && strstr(why, "cavitated"),
        "cavitation is found without a liquid at rest too", why);
  r = run_with(rest, 1.06, 1);
  check(!camp_run_admissible(&r, &lim, rest, why, sizeof why) && strstr(why, "heating") &&
            strstr(why, "1.06"),
        "T = 1.06: left out as heated", why);
  r = run_with(rest, 1.045, 1);
  check(camp_run_admissible(&r, &lim, rest, why, sizeof why) == 1,
        "T = 1.045 (the CI slit's strongest run): kept", why);
  r = run_with(rest, 1.0, 0);
  check(!camp_run_admissible(&r, &lim, rest, why, sizeof why) && strstr(why, "steady"),
        "no steady state: left out", why);
  r = run_with(5.81, 1.01, 1);
  check(!camp_run_admissible(&r, &lim, rest, why, sizeof why) && strstr(why, "expanded"),
        "5.81 against 6.025 at rest (-3.6%): left out as expanded by the forcing", why);
  r = run_with(5.9, 1.01, 1);
  check(camp_run_admissible(&r, &lim, rest, why, sizeof why) == 1,
        "5.9 against 6.025 at rest (-2.1%): kept", why);
  r = run_with(NAN, NAN, -1);
  check(camp_run_admissible(&r, &lim, rest, why, sizeof why) == 1,
        "no core, no temperature, steadiness unknown (a scene without geometry): kept", why);
  printf("%d failures\n", failures);
  return failures ? 1 : 0;
}
