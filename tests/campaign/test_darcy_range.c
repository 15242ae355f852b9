/* The Darcy range of a flow table (campaign/campaign_linear.c): rows that follow q = (k / mu) G up
 * to some gradient and rise above it are cut where the rise starts, and k is the slope of the kept
 * rows; rows that all follow the law are all kept; a table that never fits is flagged (at least 3
 * rows are kept where there are 3), rows that are not monotone in G included. */
#include <math.h>
#include <stdio.h>

#include "campaign.h"

static int failures;

static void check(int ok, const char *what) {
  printf("%s %s\n", ok ? "ok  " : "FAIL", what);
  if (!ok) failures++;
}

int main(void) {
  const double mu = 5.0, k = 0.2; /* q = (k / mu) G in the linear range */
  double G[6], q[6], sigma[6];
  for (int i = 0; i < 6; i++) {
    G[i] = 0.1 * (i + 1);
    sigma[i] = 0.005 * k / mu * G[i]; /* 0.5% errors */
    /* +-0.4 sigma noise, then above G = 0.3 a rise of 3%, 6%, 9% (the fluid heating) */
    q[i] = k / mu * G[i] * (1.0 + 0.002 * ((i % 2) ? 1 : -1) + (i >= 3 ? 0.03 * (i - 2) : 0.0));
  }
  camp_linear L;
  check(camp_darcy_range(G, q, sigma, 6, mu, &L) == 0 && L.accepted && L.rows == 3,
        "a rise of 3% from the 4th gradient on: the 3 lowest rows kept");
  check(fabs(L.k / k - 1) < 0.002 && L.k_err > 0 && fabs(L.G_max - 0.3) < 1e-12,
        "k of the kept rows within 0.2% of the true 0.2, G_max 0.3");
  printf("  k = %.5f +- %.2g (rows %d, chi2/dof %.3g)\n", L.k, L.k_err, L.rows, L.chi2_dof);

  for (int i = 0; i < 6; i++) q[i] = k / mu * G[i] * (1.0 + 0.002 * ((i % 2) ? 1 : -1));
  check(camp_darcy_range(G, q, sigma, 6, mu, &L) == 0 && L.accepted && L.rows == 6 &&
            fabs(L.k / k - 1) < 0.002,
        "linear rows: all 6 kept, k within 0.2%");

  for (int i = 0; i < 6; i++) q[i] = k / mu * G[i] * (1.0 + 0.1 * i); /* never linear */
  check(camp_darcy_range(G, q, sigma, 6, mu, &L) == 0 && !L.accepted && L.rows == 3,
        "a table that leaves the law from the start: the 3 lowest rows, flagged not accepted");
  /* q not monotone in G (lower at the 3rd gradient than the 2nd's line allows, higher at the 5th)
   * with 0.1% error bars: no prefix of 3 or more fits, so no Darcy range (k not defined) */
  const double wobble[5] = {1.0, 0.90, 1.12, 0.88, 1.10};
  for (int i = 0; i < 5; i++) {
    q[i] = k / mu * G[i] * wobble[i];
    sigma[i] = 0.001 * q[i];
  }
  check(camp_darcy_range(G, q, sigma, 5, mu, &L) == 0 && !L.accepted && L.rows == 3 &&
            L.chi2_dof > 1.0 + 3.0 * sqrt(2.0 / 2),
        "rows not monotone in G, 0.1% errors: not accepted (chi2/dof above 1 + 3 sqrt(2/dof))");
  printf("  chi2/dof %.3g over the 3 lowest rows\n", L.chi2_dof);
  check(camp_darcy_range(G, q, sigma, 2, mu, &L) == 0 && L.rows == 2, "two rows: both");
  check(camp_darcy_range(G, q, sigma, 1, mu, &L) == -1, "one row: no range (-1)");
  return failures ? 1 : 0;
}
