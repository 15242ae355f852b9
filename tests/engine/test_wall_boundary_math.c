/* wall_boundary's per-particle math (meso/physics/wall_boundary.h; Li et al. 2018, physics.md
 * section 3), on a wall of frozen particles at uniform random positions, density 8, filling
 * z in [-3, 0) of a 6 x 6 periodic patch, one per 0.5 rc cube (the builder's walls are patches of
 * an equilibrated frozen fluid; a uniform wall is the continuum limit the formulas are written for):
 *  - phi averaged over the plane z = 0 (and over 8 independent walls) is 1/2 (the surface), 1 deep inside (z = -1.5), 0 at r_phi
 *    above the wall; its gradient points into the wall (n = -grad phi / |grad phi| along +z);
 *  - Li's dissipation ratio is 1 at phi = 0, rises monotonically and saturates at phi >= 1/2; the
 *    stability cap keeps dt ratio S <= 1 (S = sum of the wall pairs' gamma w_D) and ratio >= 1;
 *  - a particle whose drift takes its predicted phi past phi_c is reflected: normal velocity into
 *    the fluid, tangential velocity reversed, on the path x_old + dt v'; a particle moving away from
 *    the wall is left alone. */
#include "physics/wall_boundary.h"

#include "test_engine_common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#define NW 864 /* 8 per rc^3 in 6 x 6 x 3 */
static double wall[NW][3];

static wall_boundary_params_t params(void) {
  wall_boundary_params_t w = {0};
  const double h = 1.0, norm = 105.0 / (16.0 * MESO_PI);
  w.r_phi2 = h * h;
  w.inv_h = 1.0 / h;
  w.w_norm = norm / 8.0;
  w.g_norm = 12.0 * norm / 8.0;
  w.phi_c = 0.5;
  w.dt = 0.01;
  return w;
}

/* The field at x from every wall particle (periodic in x and y, L = 6). */
static wall_field_t field_at(const wall_boundary_params_t *w, const double x[3]) {
  meso_real acc[WALL_FIELD_ACC] = {0, 0, 0, 0, 0};
  for (int j = 0; j < NW; j++) {
    double d[3];
    for (int k = 0; k < 3; k++) d[k] = x[k] - wall[j][k];
    for (int k = 0; k < 2; k++) d[k] -= 6.0 * rint(d[k] / 6.0);
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (r2 < w->r_phi2) wall_field_add(w->inv_h, r2, d[0], d[1], d[2], acc);
  }
  return wall_field_finish(w, acc);
}

/* One particle at a uniform position in each 0.5 rc cube (a jittered lattice: density 8 in every
 * layer, no lattice order). */
static void make_wall(uint64_t *st) {
  for (int j = 0; j < NW; j++) {
    const int cx = j % 12, cy = (j / 12) % 12, cz = j / 144;
    wall[j][0] = 0.5 * (cx + test_rng_uniform(st));
    wall[j][1] = 0.5 * (cy + test_rng_uniform(st));
    wall[j][2] = -0.5 * (cz + test_rng_uniform(st));
  }
}

int main(void) {
  uint64_t st = 2024;
  const wall_boundary_params_t w = params();
  const double zs[3] = {0.0, -1.5, 1.0}, expect[3] = {0.5, 1.0, 0.0};
  double sum[3] = {0, 0, 0}, gz[3] = {0, 0, 0};
  const int walls = 8, m = 500; /* one wall's mean varies by ~0.03: average 8 independent walls */
  for (int r = 0; r < walls; r++) {
    make_wall(&st);
    for (int c = 0; c < 3; c++)
      for (int k = 0; k < m; k++) {
        const double x[3] = {6.0 * test_rng_uniform(&st), 6.0 * test_rng_uniform(&st), zs[c]};
        const wall_field_t f = field_at(&w, x);
        sum[c] += f.phi / (walls * m);
        gz[c] += f.gz / (walls * m);
      }
  }
  for (int c = 0; c < 3; c++) {
    printf("z = %4.1f: mean phi %.4f (continuum %.1f), mean grad_z %.4f\n", zs[c], sum[c],
           expect[c], gz[c]);
    CHECK(fabs(sum[c] - expect[c]) < 0.03, "mean phi %.4f at z = %g: expected %.2f", sum[c], zs[c],
          expect[c]);
  }
  CHECK(gz[0] < -0.5, "grad phi at the surface does not point into the wall");
  /* Li's ratio: 1 without wall, increasing, saturating at phi = 1/2 (h = 0.025 rc: 8.2) */
  CHECK(fabs(wall_dissipation_ratio(0.0) - 1.0) < 1e-12, "ratio(0) != 1");
  double prev = 1.0;
  for (int k = 1; k <= 50; k++) {
    const double r = wall_dissipation_ratio(0.01 * k);
    CHECK(r >= prev, "ratio not monotonic at phi %.2f", 0.01 * k);
    prev = r;
  }
  const double sat = 1 + 0.187 * (1 / 0.025 - 1) - 0.093 * pow(0.975, 3);
  CHECK(fabs(wall_dissipation_ratio(0.5) - sat) < 1e-9 && wall_dissipation_ratio(0.9) == prev,
        "ratio at phi >= 1/2: %g, expected %g", wall_dissipation_ratio(0.5), sat);
  /* The stability cap: dt ratio S <= 1 (ratio >= 1), untouched where dt ratio S < 1 */
  for (int k = 0; k <= 40; k++) {
    const meso_real acc[WALL_FIELD_ACC] = {2.0, 0, 0, 0.5, (meso_real)k}; /* phi = 0.52 */
    const wall_field_t f = wall_field_finish(&w, acc);
    const double li = wall_dissipation_ratio(f.phi), dts = w.dt * k;
    const double want = li * dts <= 1.0 ? li : (dts < 1.0 ? 1.0 / dts : 1.0);
    CHECK(fabs(f.ratio - want) < 1e-5 * want && fabs(f.sqrt_ratio - sqrt(want)) < 1e-5,
          "capped ratio %g at S = %d: expected %g", f.ratio, k, want);
    CHECK(f.ratio >= 1.0f && (f.ratio * dts <= 1.0 + 1e-6 || f.ratio == 1.0f),
          "cap violated at S = %d", k);
  }
  /* Reflection: find a point just outside the surface, drift into the wall. */
  wall_field_t f0 = {0};
  double x_old[3] = {0, 0, 0};
  for (int k = 0; k < 1000; k++) {
    x_old[0] = 6.0 * test_rng_uniform(&st), x_old[1] = 6.0 * test_rng_uniform(&st);
    x_old[2] = 0.05;
    f0 = field_at(&w, x_old);
    if (f0.phi > 0.45 && f0.phi < 0.5 && f0.gz < 0) break;
  }
  CHECK(f0.phi > 0.45 && f0.phi < 0.5, "no point with 0.45 < phi < 0.5 at z = 0.05");
  wall_field_t fields[1] = {f0};
  wall_boundary_params_t wr = w;
  wr.field = fields;
  const double v_in[3] = {0.7, -0.4, -8.0}; /* into the wall: z drops 0.08 in one step */
  double x[3], v[3];
  for (int d = 0; d < 3; d++) {
    v[d] = v_in[d];
    x[d] = x_old[d] + wr.dt * v[d];
  }
  const double pred =
      f0.phi + f0.gx * (x[0] - x_old[0]) + f0.gy * (x[1] - x_old[1]) + f0.gz * (x[2] - x_old[2]);
  CHECK(pred > 0.5, "the test drift does not cross phi_c (predicted %.3f)", pred);
  CHECK(wall_boundary_after_drift(&wr, 0, x, v, x_old) == 0, "reflection reports a lost particle");
  const double g = sqrt((double)f0.gx * f0.gx + (double)f0.gy * f0.gy + (double)f0.gz * f0.gz);
  const double n[3] = {-f0.gx / g, -f0.gy / g, -f0.gz / g};
  const double vn_in = v_in[0] * n[0] + v_in[1] * n[1] + v_in[2] * n[2];
  const double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
  printf("reflection: phi %.3f -> predicted %.3f; v.n %.3f -> %.3f; v_t reversed\n", f0.phi, pred,
         vn_in, vn);
  CHECK(vn_in < 0 && fabs(vn + vn_in) < 1e-9, "normal velocity not reversed into the fluid");
  for (int d = 0; d < 3; d++) {
    const double vt_in = v_in[d] - vn_in * n[d], vt = v[d] - vn * n[d];
    CHECK(fabs(vt + vt_in) < 1e-9, "tangential velocity not reversed");
    CHECK(fabs(x[d] - (x_old[d] + wr.dt * v[d])) < 1e-12, "not on the path from the old position");
  }
  /* moving away: untouched */
  const double v_out[3] = {0.3, 0.1, 2.0};
  for (int d = 0; d < 3; d++) {
    v[d] = v_out[d];
    x[d] = x_old[d] + wr.dt * v[d];
  }
  wall_boundary_after_drift(&wr, 0, x, v, x_old);
  for (int d = 0; d < 3; d++) CHECK(v[d] == v_out[d], "a particle leaving the wall was reflected");
  printf("wall_boundary math: pass\n");
  return 0;
}
