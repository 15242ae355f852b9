/* The threshold (Swartzendruber) law evaluated without cancellation: far below G0 the flux is
 * (k/mu) G^2 / (2 G0), so at G = 1e-10 a G0 twice as large halves q and the slope dq/dG; around the
 * switch between the series and expm1 (G/G0 = 0.5) q is continuous; far above G0 it tends to
 * (k/mu)(G - G0); q is odd in G. */
#include <math.h>
#include <stdio.h>

#include "law/flow_law.h"

static int failures = 0;
static void check_rel(const char *what, double got, double want, double tol) {
  double rel = fabs(got - want) / fabs(want);
  if (!(rel <= tol)) {
    failures++;
    fprintf(stderr, "FAIL %s: got %.17g, want %.17g (relative error %.3g > %.3g)\n", what, got,
            want, rel, tol);
  }
}

int main(void) {
  fluid_props fl = {.mu = 2.0, .rho = 1.0};
  const double G = 1e-10, g0s[2] = {0.01, 0.02};
  double q[2];
  for (int i = 0; i < 2; i++) {
    flow_law law = {.kind = LAW_THRESHOLD, .k = 3.0, .g0 = g0s[i]};
    double dq = 0.0;
    q[i] = flow_law_q(&law, &fl, 0.0, G, &dq);
    double c = law.k / fl.mu, x = G / law.g0;
    check_rel("q far below G0", q[i], c * law.g0 * (x * x / 2 - x * x * x / 6), 1e-12);
    check_rel("dq/dG far below G0", dq, c * (x - x * x / 2), 1e-12);
    check_rel("q odd in G", flow_law_q(&law, &fl, 0.0, -G, NULL), -q[i], 1e-15);
  }
  /* the ratio is 2 to O(G/G0) = 1e-8; 1 - exp(-x) in double gave one q for both */
  check_rel("q(G0 = 0.01) / q(G0 = 0.02)", q[0] / q[1], 2.0, 1e-7);

  flow_law law = {.kind = LAW_THRESHOLD, .k = 1.0, .g0 = 1.0};
  double below = flow_law_q(&law, &fl, 0.0, 0.5 - 1e-12, NULL);
  double above = flow_law_q(&law, &fl, 0.0, 0.5 + 1e-12, NULL);
  double at = (0.5 - (1.0 - exp(-0.5))) / fl.mu; /* no cancellation at x = 0.5 */
  check_rel("q just below the series switch", below, at, 1e-10);
  check_rel("q just above the series switch", above, at, 1e-10);
  check_rel("q far above G0", flow_law_q(&law, &fl, 0.0, 50.0, NULL), (50.0 - 1.0) / fl.mu, 1e-15);

  if (failures)
    fprintf(stderr, "%d failure(s)\n", failures);
  else
    printf("threshold law: q and dq/dG accurate from G/G0 = 1e-8 to 50\n");
  return failures ? 1 : 0;
}
