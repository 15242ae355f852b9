/* The conservative mDPD force is minus the gradient of the many-body potential (Warren kernel,
 * physics.md section 1):
 *   U = sum_pairs (A rc / 2) (1 - r/rc)^2 + sum_i (pi rd^4 B / 30) rho_i^2
 * Engine forces on a random periodic configuration (200 particles in 4^3) are compared with central
 * finite differences of U computed here by brute force; the relative error must be < 1e-6. */
#include "common/mpi_singleton.h"
#include "test_engine_common.h"

typedef struct {
  int n;
  double L, A, B, rc, rd;
  double *x; /* 3n */
} config_t;

/* Nearest-image separation (test-side brute force; L > 2 rc). */
static double sep(const config_t *c, int i, int j) {
  double r2 = 0;
  for (int d = 0; d < 3; d++) {
    double dx = c->x[3 * i + d] - c->x[3 * j + d];
    dx -= c->L * round(dx / c->L);
    r2 += dx * dx;
  }
  return sqrt(r2);
}

static double potential(const config_t *c) {
  double u = 0;
  const double wnorm = 15.0 / (2.0 * M_PI * c->rd * c->rd * c->rd);
  for (int i = 0; i < c->n; i++) {
    double rho = 0;
    for (int j = 0; j < c->n; j++) {
      if (j == i) continue;
      const double r = sep(c, i, j);
      if (r < c->rd) rho += wnorm * (1 - r / c->rd) * (1 - r / c->rd);
      if (j > i && r < c->rc) u += 0.5 * c->A * c->rc * (1 - r / c->rc) * (1 - r / c->rc);
    }
    u += M_PI * pow(c->rd, 4) * c->B / 30.0 * rho * rho;
  }
  return u;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  scene_t s;
  const double L = 4.0;
  test_scene_mdpd(&s, L, L, L);
  effect_name_in_scene(&s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(&s, EFFECT_MDPD_REPULSION);
  sim_t *sim = sim_create(&s, MPI_COMM_SELF);
  CHECK(sim, "sim_create failed");
  const int n = 200;
  CHECK(test_fill_random(sim, &s, n, 0.0, 2024) == 0, "fill failed");
  CHECK(sim_setup(sim) == 0, "sim_setup failed");
  particles_t *p = sim_particles(sim);
  CHECK(p->n_local == n, "owned %d, expected %d", p->n_local, n);

  config_t c = {.n = n, .L = L, .A = -40, .B = 25, .rc = 1.0, .rd = 0.75};
  c.x = malloc(3 * n * sizeof(double));
  double *f = malloc(3 * n * sizeof(double));
  for (int i = 0; i < n; i++) {
    const int k = (int)p->id[i];
    for (int d = 0; d < 3; d++) {
      c.x[3 * k + d] = p->x[d][i];
      f[3 * k + d] = p->f[d][i];
    }
  }
  const double h = 1e-6;
  double max_err = 0, max_f = 0;
  for (int k = 0; k < 3 * n; k++) {
    const double x0 = c.x[k];
    c.x[k] = x0 + h;
    const double up = potential(&c);
    c.x[k] = x0 - h;
    const double um = potential(&c);
    c.x[k] = x0;
    const double f_fd = -(up - um) / (2 * h);
    if (fabs(f_fd - f[k]) > max_err) max_err = fabs(f_fd - f[k]);
    if (fabs(f[k]) > max_f) max_f = fabs(f[k]);
  }
  const double rel = max_err / max_f;
  printf("finite-difference check: max |F - F_fd| = %.3e, max |F| = %.3e, relative %.3e\n", max_err,
         max_f, rel);
  CHECK(rel < 1e-6, "relative error %.3e >= 1e-6", rel);
  free(c.x);
  free(f);
  sim_destroy(sim);
  MPI_Finalize();
  return 0;
}
