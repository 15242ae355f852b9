/* The continuum step of `mdpore couple` with a diagonal k per block (campaign.axes: all / auto),
 * driven from given laws (no pore-scale runs): couple_solve on a 2 x 2 x 1 block grid, flow along
 * x, a checkerboard of k_x = a, b so that the flow must turn through the faces between the rows.
 *
 * Closed form of the two-point scheme on that grid (square blocks of edge h, depth h_z; the x face
 * conductances in units of h_z/mu: 2a, 2b at the fixed faces, H = 2ab/(a+b) between A and B; the y
 * faces Hy = 2 a_y b_y/(a_y + b_y)): blocks A (0,0) = D (1,1) = a, B (1,0) = C (0,1) = b. The
 * grid is point-symmetric (p -> P - p), so p_C = P - p_B, p_D = P - p_A, and the balances of A and B
 * read
 *   (2a + H + Hy) p_A + (Hy - H) p_B = (2a + Hy) P
 *   (H - Hy) p_A - (H + 2b + Hy) p_B = -Hy P
 * with k_eff = (2b p_B + 2a (P - p_A)) / P (the outflow of B and D over the drop). Limits: Hy -> 0
 * gives the rows in series, k_eff = H; Hy -> infinity the columns in parallel, (a + b) / 2.
 *
 * Checks: a diagonal law equal along every axis reads bitwise what one scalar law reads; the scalar
 * law (k_y = k_x) and a diagonal law of blocks anisotropic by construction (x slits: k_y = k_x / 20,
 * y channels: k_y = 20 k_x) reproduce the closed form; the diagonal moves k_eff in the predicted
 * direction (down for x slits, up for y channels) by many standard errors of the Monte-Carlo error
 * bars (3% errors on every k); a block whose pore space does not span y is impermeable along y;
 * the cross-flow fractions that campaign.axes: auto reads are large here and zero on a 2 x 1 x 1
 * grid in series. */
#include <math.h>
#include <petscsys.h>
#include <stdio.h>
#include <string.h>

#include "couple.h"

static int failures = 0;

static void check(const char *what, int ok) {
  printf("%-78s %s\n", what, ok ? "ok" : "FAIL");
  if (!ok) failures++;
}

static void set_law(couple_law *L, double k) {
  memset(L, 0, sizeof *L);
  L->law = (flow_law){.kind = LAW_DARCY, .k = k};
  L->chosen = L->law;
  L->n_par = 1;
  L->par[0] = k;
  L->cov[0][0] = (0.03 * k) * (0.03 * k);
  L->k_darcy = k;
  L->k_darcy_err = 0.03 * k;
  L->g_min = 0.5;
  L->g_max = 2.0;
  L->mu = 5.41;
  L->density = 6.2;
  L->percolates = 1;
}

/* The closed form above for k_y = ky_ratio k_x. */
static double closed_form(double a, double b, double ky_ratio) {
  const double H = 2 * a * b / (a + b), ay = ky_ratio * a, by = ky_ratio * b;
  const double Hy = 2 * ay * by / (ay + by), P = 1.0;
  const double m11 = 2 * a + H + Hy, m12 = Hy - H, r1 = (2 * a + Hy) * P;
  const double m21 = H - Hy, m22 = -(H + 2 * b + Hy), r2 = -Hy * P;
  const double det = m11 * m22 - m12 * m21;
  const double pA = (r1 * m22 - m12 * r2) / det, pB = (m11 * r2 - m21 * r1) / det;
  return (2 * b * pB + 2 * a * (P - pA)) / P;
}

/* 2 x 2 x 1 checkerboard of k_x (a, b); ky_ratio < 0: no cross law (one scalar law per block);
 * no_span_y: block (0,0,0) does not span y. */
static int solve(couple_config *c, double a, double b, double ky_ratio, int no_span_y,
                 couple_solution *s) {
  couple_block blocks[4];
  memset(blocks, 0, sizeof blocks);
  for (int i = 0; i < 4; i++) {
    couple_block *B = &blocks[i];
    B->index[0] = i % 2;
    B->index[1] = i / 2;
    B->percolates = 1;
    B->spans[0] = B->spans[1] = B->spans[2] = 1;
    const double kx = (i == 0 || i == 3) ? a : b;
    set_law(&B->law, kx);
    if (ky_ratio >= 0) {
      B->cross_state[1] = CROSS_MEASURED;
      set_law(&B->cross[1], ky_ratio * kx);
    }
  }
  if (no_span_y) blocks[0].cross_state[1] = CROSS_NO_SPAN;
  const double size[3] = {4.0, 4.0, 4.0};
  return couple_solve(c, blocks, size, 1.0, s);
}

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  couple_config c;
  memset(&c, 0, sizeof c);
  c.blocks[0] = c.blocks[1] = 2;
  c.blocks[2] = 1;
  c.axis = 0;
  c.seed = 12345;
  c.error_samples = 64;
  const double a = 1.0, b = 0.1;
  couple_solution scalar, same, slits, channels, tight;
  char what[160];
  if (solve(&c, a, b, -1.0, 0, &scalar) || solve(&c, a, b, 1.0, 0, &same) ||
      solve(&c, a, b, 1.0 / 20, 0, &slits) || solve(&c, a, b, 20.0, 0, &channels) ||
      solve(&c, a, b, 1.0, 1, &tight)) {
    printf("couple_solve failed\n");
    return 1;
  }
  snprintf(what, sizeof what, "diagonal law equal along every axis: k_eff %.17g bitwise = scalar's",
           same.keff);
  check(what, same.keff == scalar.keff && same.flux[1] == scalar.flux[1]);
  const struct {
    const char *name;
    couple_solution *s;
    double ratio;
  } cases[3] = {{"scalar law (k_y = k_x)", &scalar, 1.0},
                {"x slits (k_y = k_x / 20)", &slits, 1.0 / 20},
                {"y channels (k_y = 20 k_x)", &channels, 20.0}};
  for (int i = 0; i < 3; i++) {
    const double want = closed_form(a, b, cases[i].ratio), got = cases[i].s->keff;
    snprintf(what, sizeof what, "%s: k_eff %.9g +- %.2g, closed form %.9g (rel %.1e)",
             cases[i].name, got, cases[i].s->keff_err, want, fabs(got / want - 1));
    check(what, fabs(got / want - 1) < 1e-8 && cases[i].s->converged);
  }
  const double e_slits = hypot(slits.keff_err, scalar.keff_err);
  snprintf(what, sizeof what,
           "x slits lower k_eff: %.5g -> %.5g (%.1f combined standard errors, predicted %.5g)",
           scalar.keff, slits.keff, (scalar.keff - slits.keff) / e_slits, closed_form(a, b, 0.05));
  check(what, slits.keff < scalar.keff && scalar.keff - slits.keff > 5 * e_slits);
  const double e_chan = hypot(channels.keff_err, scalar.keff_err);
  snprintf(what, sizeof what,
           "y channels raise k_eff: %.5g -> %.5g (%.1f combined standard errors)", scalar.keff,
           channels.keff, (channels.keff - scalar.keff) / e_chan);
  check(what, channels.keff > scalar.keff && channels.keff - scalar.keff > 5 * e_chan);
  snprintf(what, sizeof what,
           "limits: harmonic %.5g < x slits %.5g < y channels %.5g < arithmetic %.5g",
           2 * a * b / (a + b), slits.keff, channels.keff, 0.5 * (a + b));
  check(what, 2 * a * b / (a + b) < slits.keff && channels.keff < 0.5 * (a + b));
  snprintf(what, sizeof what, "block (0,0,0) not spanning y: flow along y through it %.2e",
           tight.cross[3 * 0 + 1] * fabs(tight.flux[0]));
  check(what, tight.cross[1] * fabs(tight.flux[0]) < 1e-4 * fabs(scalar.cross[1] * scalar.flux[0]));
  snprintf(what, sizeof what,
           "cross flow (campaign.axes: auto) on the checkerboard: %.3g %.3g %.3g %.3g (> 0.05)",
           scalar.cross[1], scalar.cross[4], scalar.cross[7], scalar.cross[10]);
  check(what, scalar.cross[1] > 0.05 && scalar.cross[4] > 0.05 && scalar.cross[7] > 0.05 &&
                  scalar.cross[10] > 0.05);
  /* 2 x 1 x 1 in series: no face between blocks along y or z, no cross flow */
  c.blocks[1] = 1;
  couple_block two[2];
  memset(two, 0, sizeof two);
  for (int i = 0; i < 2; i++) {
    two[i].index[0] = i;
    two[i].percolates = two[i].spans[0] = two[i].spans[1] = two[i].spans[2] = 1;
    set_law(&two[i].law, i ? b : a);
  }
  couple_solution series;
  if (couple_solve(&c, two, (const double[]){4.0, 4.0, 4.0}, 1.0, &series)) return 1;
  snprintf(what, sizeof what, "2 x 1 x 1 in series: k_eff %.9g = harmonic %.9g, cross flow %g %g",
           series.keff, 2 * a * b / (a + b), series.cross[1], series.cross[2]);
  check(what, fabs(series.keff / (2 * a * b / (a + b)) - 1) < 1e-9 && series.cross[1] == 0 &&
                  series.cross[2] == 0);
  couple_solution *all[] = {&scalar, &same, &slits, &channels, &tight, &series};
  for (int i = 0; i < 6; i++) couple_solution_free(all[i]);
  PetscCall(PetscFinalize());
  printf("%s\n", failures ? "FAILED" : "all diagonal-law coupling checks passed");
  return failures ? 1 : 0;
}
