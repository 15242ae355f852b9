/* The ladder of forcings (docs/permeability.md, "The gradient ladder").
 *
 * auto: N body forces g whose estimated mean pore velocity u runs log-spaced from u_lo to u_hi
 * (default 0.02 to 0.2, N = 5). The estimate is the slit law with the hydraulic size of the pore
 * space, h = 2 V_pore / S_pore from the image (the slit width for a slit):
 *     u = n g h^2 / (12 mu)   ->   g(u) = 12 mu u / (n h^2).
 * It is exact for a no-slip slit, 1.5x high for a tube (R^2/8 with h = R), and ignores the wall slip;
 * a factor of this size only shifts the ladder along its log-spaced range. u = 0.02 is about where a
 * run of ~10^4 steps still resolves the mean flow against the thermal noise (particle velocities of
 * order 1); u = 0.2 keeps the wall shear rate and the Reynolds number small (Re = u h / nu < 1 for
 * h < 5 rc) and the viscous heating negligible, so the ladder stays in linear response, where Darcy
 * must hold; a law beyond Darcy fitted on it is a finding to check, not an assumption. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign.h"

int camp_parse_gradient_list(const char *text, double *grads, int *n, char *err, int errlen) {
  *n = 0;
  const char *p = text;
  while (1) {
    char *end;
    errno = 0;
    double v = strtod(p, &end);
    if (end == p || errno || !isfinite(v) || (*end && *end != ',')) {
      snprintf(err, errlen,
               "expected auto or a comma-separated list of body forces g (finite numbers, e.g. "
               "0.05,0.1,0.2), got '%s'",
               text);
      return -1;
    }
    if (v == 0) {
      snprintf(err, errlen, "'%s': g = 0 drives no flow and determines no law: expected non-zero g",
               text);
      return -1;
    }
    if (*n >= CAMP_MAX_GRADIENTS) {
      snprintf(err, errlen, "'%s': expected at most %d gradients", text, CAMP_MAX_GRADIENTS);
      return -1;
    }
    for (int i = 0; i < *n; i++)
      if (grads[i] == v) {
        snprintf(err, errlen, "'%s': g = %g given twice: expected distinct gradients", text, v);
        return -1;
      }
    grads[(*n)++] = v;
    if (!*end) break;
    p = end + 1;
  }
  if (*n < 2) {
    snprintf(err, errlen,
             "'%s': expected at least 2 distinct gradients (a law beyond Darcy needs 2 or more; "
             "5 or more recommended)",
             text);
    return -1;
  }
  return 0;
}

/* g to 4 significant digits: short numbers in folders and tables. */
static double round4(double g) {
  char b[32];
  snprintf(b, sizeof b, "%.4g", g);
  return atof(b);
}

int camp_gradients(camp_opts *o, const campaign *c) {
  if (!o->grad_auto) return 0;
  double h = c->h_hydraulic;
  if (!(h > 0)) {
    fprintf(stderr,
            "mdpore permeability: --gradients auto: %s has %s, so the pore size that sets "
            "the forcing cannot be estimated: expected --gradients LIST (body forces g)\n",
            o->input, c->image[0] ? "no pore-solid interface" : "no geometry image");
    return -1;
  }
  int n = o->n_grads;
  double mu = c->viscosity, rho = c->fluid_density;
  for (int i = 0; i < n; i++) {
    double u = o->u_lo * pow(o->u_hi / o->u_lo, (double)i / (n - 1));
    double g = 12.0 * mu * u / (rho * h * h);
    o->grads[i] = round4(g);
  }
  fprintf(
      stderr,
      "mdpore permeability: auto gradients: h = 2 V_pore / S = %.4g rc, n = %g, mu = %g: g = 12 "
      "mu u / (n h^2) for mean pore velocities u = %g .. %g (%d log-spaced):",
      h, rho, mu, o->u_lo, o->u_hi, n);
  for (int i = 0; i < n; i++) fprintf(stderr, " %g", o->grads[i]);
  fprintf(stderr, "\n");
  return 0;
}
