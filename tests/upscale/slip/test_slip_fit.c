/* ctest upscale_slip_fit: the slip fit of `mdpore slip` (upscale/fit/slip_fit.c) on synthetic
 * permeabilities k_i = k_noslip(h_i) F(b / h_i) (1 + noise), seeded Gaussian noise of known size:
 *   - a known b = -0.3 rc is recovered within 3 sigma (slit and tube, navier and shift models, and
 *     with a free scale a = 0.93), chi2/dof near 1;
 *   - a zero-slip set gives b within 3 sigma of 0;
 *   - exact data: navier b to 1e-10 (the closed form), one point: b solved, chi2 undefined;
 *   - bad inputs are refused with a message naming the point, the key and what was expected. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../synthetic_rng.h"
#include "slip_fit.h"

static int failures = 0;

#define CHECK(cond, ...)                                                                           \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      printf("FAIL %s:%d: ", __FILE__, __LINE__);                                                  \
      printf(__VA_ARGS__);                                                                         \
      printf("\n");                                                                                \
      failures++;                                                                                  \
    }                                                                                              \
  } while (0)

/* n sizes from h0 to h1 (geometric), relative noise rel, porosity phi, scale a. */
static void make_points(slip_point *p, int n, const slip_setup *s, double b, double a, double rel,
                        double phi, uint64_t seed) {
  uint64_t st = seed;
  for (int i = 0; i < n; i++) {
    memset(&p[i], 0, sizeof p[i]);
    p[i].h = 3.0 * pow(16.0 / 3.0, i / (double)(n > 1 ? n - 1 : 1));
    p[i].porosity = phi;
    const double k =
        a * slip_k_noslip(s->shape, p[i].h, phi) * slip_factor(s->shape, s->model, p[i].h, b, NULL);
    p[i].k_err = rel * k;
    p[i].k = k + p[i].k_err * gaussian(&st);
    p[i].rc_m = NAN;
    snprintf(p[i].source, sizeof p[i].source, "synthetic point %d", i);
  }
}

static void recovery(slip_shape shape, slip_model model, int free_scale, double b, double a) {
  const slip_setup s = {shape, model, free_scale};
  int within = 0, trials = 20;
  double chi2 = 0;
  for (int t = 0; t < trials; t++) {
    slip_point p[8];
    slip_result r;
    char err[512];
    make_points(p, 8, &s, b, a, 0.02, 0.5, 1000 + 17 * t);
    if (slip_fit(p, 8, &s, &r, err, sizeof err)) {
      CHECK(0, "%s %s: fit failed: %s", slip_shape_names[shape], slip_model_names[model], err);
      return;
    }
    within += fabs(r.b - b) <= 3 * r.b_err;
    chi2 += r.chi2_dof / trials;
    if (t == 0)
      printf("%s %-6s free %d: b = %+.4f +- %.4f (true %+.2f), a = %.4f +- %.4f, chi2/dof %.2f\n",
             slip_shape_names[shape], slip_model_names[model], free_scale, r.b, r.b_err, b, r.a,
             r.a_err, r.chi2_dof);
    CHECK(r.dof == 8 - (free_scale ? 2 : 1), "dof %d", r.dof);
  }
  /* 3 sigma covers 99.7%: allow one miss in 20 seeds */
  CHECK(within >= trials - 1, "%s %s free %d: b within 3 sigma in %d of %d seeds",
        slip_shape_names[shape], slip_model_names[model], free_scale, within, trials);
  CHECK(chi2 > 0.6 && chi2 < 1.5, "mean chi2/dof %.2f (expected about 1)", chi2);
}

static void exact(void) {
  const slip_setup s = {SLIP_SLIT, SLIP_NAVIER, 0};
  slip_point p[4];
  slip_result r;
  char err[512];
  make_points(p, 4, &s, -0.3, 1.0, 0.0, 0.4, 1);
  for (int i = 0; i < 4; i++) p[i].k_err = 0.01 * p[i].k;
  CHECK(!slip_fit(p, 4, &s, &r, err, sizeof err), "%s", err);
  CHECK(fabs(r.b + 0.3) < 1e-10, "exact navier b = %.15g", r.b);
  CHECK(r.chi2 < 1e-16, "exact chi2 %g", r.chi2);
  /* one point: b solved, error propagated, chi2 undefined */
  CHECK(!slip_fit(p + 1, 1, &s, &r, err, sizeof err), "%s", err);
  const double want_err = 0.01 * p[1].k / slip_k_noslip(SLIP_SLIT, p[1].h, 0.4) * p[1].h / 6.0;
  CHECK(fabs(r.b + 0.3) < 1e-10 && fabs(r.b_err - want_err) < 1e-12 && r.dof == 0 &&
            isnan(r.chi2_dof),
        "one point: b = %g +- %g (want -0.3 +- %g), dof %d, chi2/dof %g", r.b, r.b_err, want_err,
        r.dof, r.chi2_dof);
  /* model ratio at a size: the law */
  double e;
  const double m = slip_model_ratio(&s, &r, 6.0, &e);
  CHECK(fabs(m - (1 - 0.3)) < 1e-10, "model ratio at h = 6: %g", m);
}

static void refused(const char *what, slip_point *p, int n, slip_setup s, const char *frag1,
                    const char *frag2) {
  slip_result r;
  char err[512] = "";
  const int rc = slip_fit(p, n, &s, &r, err, sizeof err);
  CHECK(rc != 0, "%s: accepted", what);
  CHECK(strstr(err, frag1) && strstr(err, frag2), "%s: message '%s' lacks '%s' / '%s'", what, err,
        frag1, frag2);
  if (rc) printf("refused (%s): %s\n", what, err);
}

static void bad_inputs(void) {
  const slip_setup s = {SLIP_SLIT, SLIP_NAVIER, 0}, sf = {SLIP_SLIT, SLIP_NAVIER, 1};
  slip_point p[3];
  make_points(p, 3, &s, -0.2, 1.0, 0.02, 1.0, 5);
  refused("no points", p, 0, s, "0 point(s) for 1 parameter", "at least 1");
  refused("one point, free scale", p, 1, sf, "1 point(s) for 2 parameter", "at least 2");
  slip_point q[3];
  memcpy(q, p, sizeof q);
  q[1].h = -4;
  refused("h <= 0", q, 3, s, "synthetic point 1: key 'h'", "pore size > 0, got -4");
  memcpy(q, p, sizeof q);
  q[2].k = NAN;
  refused("non-finite k", q, 3, s, "synthetic point 2: key 'k'", "finite permeability");
  memcpy(q, p, sizeof q);
  q[0].k_err = -0.01;
  refused("negative error", q, 3, s, "synthetic point 0: key 'k_err'", "positive standard error");
  memcpy(q, p, sizeof q);
  q[0].porosity = 1.5;
  refused("porosity", q, 3, s, "key 'porosity'", "(0, 1]");
  memcpy(q, p, sizeof q);
  q[1].h = q[2].h = q[0].h;
  refused("free scale, one size", q, 3, sf, "--free-scale", "2 distinct pore sizes");
}

int main(void) {
  for (int shape = 0; shape < SLIP_SHAPE_COUNT; shape++)
    for (int model = 0; model < SLIP_MODEL_COUNT; model++) {
      recovery(shape, model, 0, -0.3, 1.0);
      recovery(shape, model, 0, 0.0, 1.0); /* zero slip: b ~ 0 */
    }
  recovery(SLIP_SLIT, SLIP_NAVIER, 1, -0.3, 0.93);
  recovery(SLIP_TUBE, SLIP_SHIFT, 1, 0.2, 1.05);
  exact();
  bad_inputs();
  printf("%s (%d failure(s))\n", failures ? "FAIL" : "pass", failures);
  return failures ? 1 : 0;
}
