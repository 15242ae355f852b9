/* The Darcy range of an axis (campaign.h): the permeability is the zero-forcing limit, so the runs
 * whose flow has left the linear law (the fluid heats, or a strong body force compresses it ahead of
 * the obstacles: docs/permeability.md, "The forcing range where Darcy holds") must not pull it.
 * From the flow table's rows in
 * increasing G: the largest m >= 3 (2 with 2 rows) such that Darcy's q = (k / mu) G through the origin, weighted
 * least squares over the m lowest rows, fits with chi2/dof <= 1 + 3 sqrt(2 / dof) (three standard
 * deviations of chi2/dof for Gaussian errors). */
#include <math.h>

#include "campaign.h"

static void darcy_prefix(const double *G, const double *q, const double *sigma, int m, double mu,
                         camp_linear *out) {
  double sgq = 0, sgg = 0;
  for (int i = 0; i < m; i++) {
    const double w = 1.0 / (sigma[i] * sigma[i]);
    sgq += w * G[i] * q[i];
    sgg += w * G[i] * G[i];
  }
  const double slope = sgq / sgg;
  double chi2 = 0;
  for (int i = 0; i < m; i++) {
    const double r = (q[i] - slope * G[i]) / sigma[i];
    chi2 += r * r;
  }
  out->rows = m;
  out->k = mu * slope;
  out->chi2_dof = m > 1 ? chi2 / (m - 1) : NAN;
  /* the error scaled up by sqrt(chi2/dof) when the scatter exceeds the error bars */
  out->k_err = mu / sqrt(sgg) * (out->chi2_dof > 1 ? sqrt(out->chi2_dof) : 1.0);
  out->G_max = G[m - 1];
}

int camp_darcy_range(const double *G, const double *q, const double *sigma, int n, double mu,
                     camp_linear *out) {
  out->rows = 0;
  out->accepted = 0;
  out->k = out->k_err = out->chi2_dof = out->G_max = NAN;
  if (n < 2) return -1;
  /* at least 3 rows where there are 3: two rows through the origin test a law with one degree of
   * freedom, and the lowest rows carry the largest relative errors (thermal noise), which a
   * block-averaged error can understate (a 20 rc sphere array at 0.25 rc voxels: its lowest row 2.9
   * sigma below the others' line, and a 2-row range would have kept it) */
  const int min_rows = n >= 3 ? 3 : 2;
  for (int m = n; m >= min_rows; m--) {
    darcy_prefix(G, q, sigma, m, mu, out);
    if (out->chi2_dof <= 1.0 + 3.0 * sqrt(2.0 / (m - 1))) {
      out->accepted = 1;
      return 0;
    }
  }
  return 0; /* the min_rows lowest rows, not accepted: reported as such */
}
