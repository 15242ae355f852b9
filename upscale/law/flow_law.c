/* Flow laws q(G) (see flow_law.h; physics.md section 5 and 6). */
#include "flow_law.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const char *const flow_law_names[LAW_COUNT + 1] = {"darcy", "threshold", "forchheimer", "power",
                                                   NULL};

const char *flow_law_name(flow_law_kind kind) {
  return (kind >= 0 && kind < LAW_COUNT) ? flow_law_names[kind] : "unknown";
}

int flow_law_from_name(const char *name) {
  for (int i = 0; i < LAW_COUNT; i++)
    if (!strcmp(name, flow_law_names[i])) return i;
  return -1;
}

int flow_law_nparams(flow_law_kind kind) {
  return kind == LAW_DARCY ? 1 : 2;
}

/* x - (1 - exp(-x)) = x + expm1(-x) for x >= 0 without the cancellation of the two terms when x is
 * small: the alternating series x^2/2 - x^3/6 + ... below x = 0.5 (terms fall by x/n, so 25 of them
 * reach double precision), expm1 above. */
static double threshold_excess(double x) {
  if (x >= 0.5) return x + expm1(-x);
  double term = x * x / 2.0, sum = 0.0;
  for (int n = 3; n < 28 && term != 0.0; n++) {
    sum += term;
    term *= -x / n;
  }
  return sum;
}

/* Forchheimer solved for q: a q + b q|q| = G  ->  q = 2G / (a + sqrt(a^2 + 4 b |G|)) (stable root).
 */
static double forchheimer_q(double a, double b, double G) {
  return 2.0 * G / (a + sqrt(a * a + 4.0 * b * fabs(G)));
}

double flow_law_q_exact(const flow_law *law, const fluid_props *fl, double G) {
  double s = G < 0 ? -1.0 : 1.0, aG = fabs(G);
  switch (law->kind) {
  case LAW_DARCY:
    return law->k / fl->mu * G;
  case LAW_THRESHOLD:
    return aG > law->g0 ? s * law->k / fl->mu * (aG - law->g0) : 0.0;
  case LAW_FORCHHEIMER:
    return forchheimer_q(fl->mu / law->k, law->beta * fl->rho, G);
  case LAW_POWER:
    return s * law->K * pow(aG, law->n);
  default:
    return 0.0;
  }
}

double flow_law_q(const flow_law *law, const fluid_props *fl, double g_lin, double G,
                  double *dqdG) {
  double s = G < 0 ? -1.0 : 1.0, aG = fabs(G), q = 0.0, d = 0.0;
  switch (law->kind) {
  case LAW_DARCY:
    d = law->k / fl->mu;
    q = d * G;
    break;
  case LAW_THRESHOLD: {
    /* Swartzendruber (1962): q = (k/mu)[G - G0(1 - exp(-G/G0))]; tends to (k/mu)(G - G0) for G >>
     * G0 and to (k/mu) G^2/(2 G0) near zero, so it is smooth where the hinge law has a kink. */
    double c = law->k / fl->mu, x = aG / law->g0;
    q = s * c * law->g0 * threshold_excess(x);
    d = -c * expm1(-x);
    break;
  }
  case LAW_FORCHHEIMER: {
    double a = fl->mu / law->k, b = law->beta * fl->rho;
    q = forchheimer_q(a, b, G);
    d = 1.0 / (a + 2.0 * b * fabs(q));
    break;
  }
  case LAW_POWER:
    if (aG < g_lin) { /* linear continuation below g_lin, continuous in value at g_lin */
      d = law->K * pow(g_lin, law->n - 1.0);
      q = d * G;
    } else {
      q = s * law->K * pow(aG, law->n);
      d = law->n * law->K * pow(aG, law->n - 1.0);
    }
    break;
  default:
    break;
  }
  if (dqdG) *dqdG = d;
  return q;
}

double flow_law_gradient_forchheimer(const flow_law *law, const fluid_props *fl, double q) {
  double beta = law->kind == LAW_FORCHHEIMER ? law->beta : 0.0;
  return fl->mu / law->k * q + beta * fl->rho * q * fabs(q);
}

int flow_law_check(const flow_law *law, char *why, int why_len) {
  const char *bad = NULL;
  switch (law->kind) {
  case LAW_DARCY:
    if (!(law->k > 0 && isfinite(law->k))) bad = "darcy law needs k > 0";
    break;
  case LAW_THRESHOLD:
    if (!(law->k > 0 && isfinite(law->k)))
      bad = "threshold law needs k > 0";
    else if (!(law->g0 > 0 && isfinite(law->g0)))
      bad = "threshold law needs G0 > 0 (a fitted G0 <= 0 is no threshold: use darcy)";
    break;
  case LAW_FORCHHEIMER:
    if (!(law->k > 0 && isfinite(law->k)))
      bad = "forchheimer law needs k > 0";
    else if (!(law->beta >= 0 && isfinite(law->beta)))
      bad = "forchheimer law needs beta >= 0";
    break;
  case LAW_POWER:
    if (!(law->K > 0 && isfinite(law->K)))
      bad = "power law needs K > 0";
    else if (!(law->n > 0 && isfinite(law->n)))
      bad = "power law needs n > 0";
    break;
  default:
    bad = "unknown law";
  }
  if (bad) {
    snprintf(why, why_len, "%s", bad);
    return -1;
  }
  return 0;
}
