/* Two-point face flux for any pair of laws (see face_flux.h). */
#include "face_flux.h"

#include <math.h>

static int darcy_like(const flow_law *l) {
  return l->kind == LAW_DARCY || l->kind == LAW_FORCHHEIMER;
}
static double beta_of(const flow_law *l) {
  return l->kind == LAW_FORCHHEIMER ? l->beta : 0.0;
}

/* Series of Darcy/Forchheimer halves (physics.md section 6): with a = mu (d_a/k_a + d_b/k_b) and
 * b = rho (d_a beta_a + d_b beta_b), a q + b q|q| = dp gives q = 2 dp / (a + sqrt(a^2 + 4 b |dp|))
 * and dq/d(dp) = 1 / (a + 2 b |q|). For beta = 0 this is the harmonic-mean transmissibility
 * exactly. */
static face_flux_result closed_form(const flow_law *la, double da, const flow_law *lb, double db,
                                    const fluid_props *fl, double dp) {
  double a = fl->mu * da / la->k, b = fl->rho * da * beta_of(la);
  if (lb) {
    a += fl->mu * db / lb->k;
    b += fl->rho * db * beta_of(lb);
  }
  face_flux_result r;
  r.q = 2.0 * dp / (a + sqrt(a * a + 4.0 * b * fabs(dp)));
  r.dq_dp = 1.0 / (a + 2.0 * b * fabs(r.q));
  r.g_a = flow_law_gradient_forchheimer(la, fl, r.q);
  return r;
}

/* General pair: find G_a in [0, |dp|/d_a] with f(G_a) = q_a(G_a) - q_b((|dp| - d_a G_a)/d_b) = 0.
 * f increases monotonically, f(0) <= 0 <= f(|dp|/d_a): Newton steps kept inside a shrinking
 * bracket. */
static face_flux_result series_solve(const flow_law *la, double da, const flow_law *lb, double db,
                                     const fluid_props *fl, double g_lin, double dp) {
  double s = dp < 0 ? -1.0 : 1.0, adp = fabs(dp);
  double lo = 0.0, hi = adp / da, ga = 0.5 * hi, qa = 0, qb = 0, dqa = 0, dqb = 0;
  for (int it = 0; it < 200; it++) {
    double gb = (adp - da * ga) / db;
    qa = flow_law_q(la, fl, g_lin, ga, &dqa);
    qb = flow_law_q(lb, fl, g_lin, gb, &dqb);
    double f = qa - qb, df = dqa + dqb * da / db;
    if (f > 0)
      hi = ga;
    else
      lo = ga;
    double next = df > 0 ? ga - f / df : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (fabs(f) <= 1e-15 * (fabs(qa) + fabs(qb)) || hi - lo <= 1e-15 * hi) break;
    ga = next;
  }
  face_flux_result r;
  r.q = s * 0.5 * (qa + qb);
  /* q = q_a(G_a) = q_b(G_b), d_a dG_a + d_b dG_b = d(dp)  =>  dq/d(dp) = 1 / (d_a/q_a' + d_b/q_b')
   */
  double den = da * dqb + db * dqa;
  r.dq_dp = den > 0 ? dqa * dqb / den : 0.0;
  r.g_a = s * ga;
  return r;
}

face_flux_result face_flux(const flow_law *law_a, double d_a, const flow_law *law_b, double d_b,
                           const fluid_props *fl, double g_lin, double dp) {
  if (darcy_like(law_a) && (!law_b || darcy_like(law_b)))
    return closed_form(law_a, d_a, law_b, d_b, fl, dp);
  if (!law_b) { /* one half: G = dp / d_a */
    face_flux_result r;
    double d;
    r.q = flow_law_q(law_a, fl, g_lin, dp / d_a, &d);
    r.dq_dp = d / d_a;
    r.g_a = dp / d_a;
    return r;
  }
  if (dp == 0.0) { /* no driving: zero flux; slope from the series formula at G = 0 */
    face_flux_result r = {0.0, 0.0, 0.0};
    double dqa, dqb;
    flow_law_q(law_a, fl, g_lin, 0.0, &dqa);
    flow_law_q(law_b, fl, g_lin, 0.0, &dqb);
    double den = d_a * dqb + d_b * dqa;
    r.dq_dp = den > 0 ? dqa * dqb / den : 0.0;
    return r;
  }
  return series_solve(law_a, d_a, law_b, d_b, fl, g_lin, dp);
}
