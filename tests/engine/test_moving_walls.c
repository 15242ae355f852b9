/* Moving wall species (species[].velocity, plane Couette) and the density cache of static frozen
 * particles (plan.density_cache), on a slit image written here: 8 x 16 x 6 voxels of 0.5 rc, the
 * lower 4 y layers organic (species `bottom`, at rest), the upper 4 inorganic (species `top`,
 * velocity [0.5, 0, 0]), 8 pore layers between; loaded through a scene file (parser + builder),
 * mDPD fluid, bounce_back. The wall thickness keeps every solid layer, so across the periodic y face
 * the moving wall slides along the static one (static particles with moving neighbours). Asserts:
 *  - the densities of every particle (mobile, static wall, moving wall) equal a brute-force sum over
 *    all particle pairs (minimum image, gathered from every rank) to 1e-10 relative (1e-5 on the
 *    CUDA backend, single-precision pair math) at set-up and after steps 1, 2, 50, 200 and 400 with
 *    the cache on, and at set-up with MDPORE_DENSITY_CACHE=0;
 *  - after 400 steps every `top` particle has moved by U t along x (wrapped; the wall crossed the
 *    rank boundary on 2 ranks), not along y or z, and carries v = U; every `bottom` particle is
 *    where it started with v = 0; the particle count is kept;
 *  - no fluid particle inside a solid voxel at any checked step (bounce_back relative to the wall);
 *  - the moving wall drags the fluid: the fluid's mean v_x averaged over steps 200-400 (every 10;
 *    the start-up time h^2 n / (pi^2 mu) is 1.9) is above U / 5 (no slip: U / 2; the thermal error
 *    of one sample is sqrt(kT / N) = 0.058) and below U;
 *  - the reflections relative to a moving wall: bounce_back gives v' = 2u - v, wall_boundary's
 *    reflection keeps the wall's velocity and reverses the relative one (unit checks).
 * With the argument "cuda" the run part on the CUDA backend (one rank; skipped without a GPU). */
#include "common/mpi_singleton.h"
#include "test_cuda_common.h"

#include "populate/init_config.h"
#include "effects/scene_load.h"
#include "physics/density_kernels.h"

/* EXPECT(cond): counts a failure and goes on (every check is reported). */
static int failures = 0;
#define EXPECT(c)                                                                                  \
  do {                                                                                             \
    if (!(c)) {                                                                                    \
      fprintf(stderr, "FAIL %s:%d: %s\n", __FILE__, __LINE__, #c);                                 \
      failures++;                                                                                  \
    }                                                                                              \
  } while (0)

#define NX 8
#define NY 16
#define NZ 6
#define U_TOP 0.5
static const char *IMG = "moving_walls_slit.raw";
static const char *SCENE = "moving_walls.yaml";

static int use_cuda = 0;

static int write_files(int nranks) {
  FILE *f = fopen(IMG, "wb");
  if (!f) return -1;
  for (int k = 0; k < NZ; k++)
    for (int j = 0; j < NY; j++)
      for (int i = 0; i < NX; i++) fputc(j < 4 ? 2 : j >= 12 ? 1 : 0, f);
  fclose(f);
  char hdr[256];
  snprintf(hdr, sizeof hdr, "%s.hdr", IMG);
  if (!(f = fopen(hdr, "w"))) return -1;
  fprintf(f,
          "dims: %d %d %d\ntype: uint8\naxis_order: xyz\nheader_bytes: 0\n"
          "labels: pore=0;inorganic=1;organic=2\n",
          NX, NY, NZ);
  fclose(f);
  if (!(f = fopen(SCENE, "w"))) return -1;
  fprintf(
      f,
      "box: {lo: [0, 0, 0], hi: [4, 8, 3], procs: [%d, 1, 1]}\n"
      "species:\n"
      "  - {name: liquid}\n"
      "  - {name: bottom, frozen: true}\n"
      "  - {name: top, frozen: true, velocity: [%g, 0, 0]}\n"
      "pairs:\n  default: {A: -40, B: 25, gamma: 4.5, rc: 1.0, rd: 0.75}\n"
      "effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}, bounce_back: {}}\n"
      "geometry:\n  image: %s\n  flow_axis: x\n  rc_per_voxel: 0.5\n"
      "  species: {fluid: liquid, organic: bottom, inorganic: top}\n"
      "  wall_thickness: 2.25\n"
      "  patches: {file: moving_walls_patches.h5, seed: 3}\n"
      "initial: {temperature: 1.0}\n"
      "run: {dt: 0.01, steps: 400, seed: 5}\n",
      nranks, U_TOP, IMG);
  fclose(f);
  return 0;
}

typedef struct {
  int n;
  double *x; /* 3 n */
  int *species;
  int64_t *id;
} all_t;

/* Every rank's owned particles on every rank. */
static void gather_all(sim_t *sim, all_t *a) {
  particles_t *p = sim_particles(sim);
  int nr, n = p->n_local;
  MPI_Comm_size(MPI_COMM_WORLD, &nr);
  int *counts = malloc(nr * sizeof(int)), *displ = malloc(nr * sizeof(int));
  MPI_Allgather(&n, 1, MPI_INT, counts, 1, MPI_INT, MPI_COMM_WORLD);
  a->n = 0;
  for (int r = 0; r < nr; r++) displ[r] = a->n, a->n += counts[r];
  double *mx = malloc(3 * (size_t)(n + 1) * sizeof(double));
  int *ms = malloc((size_t)(n + 1) * sizeof(int));
  int64_t *mi = malloc((size_t)(n + 1) * sizeof(int64_t));
  for (int i = 0; i < n; i++) {
    for (int d = 0; d < 3; d++) mx[3 * i + d] = p->x[d][i];
    ms[i] = p->species[i];
    mi[i] = p->id[i];
  }
  a->x = malloc(3 * (size_t)a->n * sizeof(double));
  a->species = malloc((size_t)a->n * sizeof(int));
  a->id = malloc((size_t)a->n * sizeof(int64_t));
  MPI_Allgatherv(ms, n, MPI_INT, a->species, counts, displ, MPI_INT, MPI_COMM_WORLD);
  MPI_Allgatherv(mi, n, MPI_INT64_T, a->id, counts, displ, MPI_INT64_T, MPI_COMM_WORLD);
  for (int r = 0; r < nr; r++) counts[r] *= 3, displ[r] *= 3;
  MPI_Allgatherv(mx, 3 * n, MPI_DOUBLE, a->x, counts, displ, MPI_DOUBLE, MPI_COMM_WORLD);
  free(mx), free(ms), free(mi), free(counts), free(displ);
}

static void all_free(all_t *a) {
  free(a->x), free(a->species), free(a->id);
}

/* Largest relative difference between the owned densities and a brute-force sum over all pairs. */
static double density_error(sim_t *sim) {
  const scene_t *s = sim_scene(sim);
  all_t a;
  gather_all(sim, &a);
  particles_t *p = sim_particles(sim);
  double worst = 0.0;
  const double L[3] = {s->box_hi[0] - s->box_lo[0], s->box_hi[1] - s->box_lo[1],
                       s->box_hi[2] - s->box_lo[2]};
  for (int i = 0; i < p->n_local; i++) {
    const int si = p->species[i];
    double sum = 0.0;
    for (int k = 0; k < a.n; k++) {
      if (a.id[k] == p->id[i]) continue;
      double r2 = 0.0;
      for (int d = 0; d < 3; d++) {
        double dx = p->x[d][i] - a.x[3 * k + d];
        dx -= L[d] * nearbyint(dx / L[d]);
        r2 += dx * dx;
      }
      const double rd = s->pair[si][a.species[k]].rd;
      if (r2 >= rd * rd) continue;
      sum += w_rho_warren_inv(sqrt(r2), 1.0 / rd, w_rho_norm(MESO_KERNEL_WARREN, rd));
    }
    const double e = fabs(p->rho[i] - sum) / (sum > 1.0 ? sum : 1.0);
    if (e > worst) worst = e;
  }
  all_free(&a);
  MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return worst;
}

/* Fluid particles inside a solid voxel (layers y < 4 and y >= 12). */
static long penetrations(sim_t *sim) {
  particles_t *p = sim_particles(sim);
  long n = 0;
  for (int i = 0; i < p->n_local; i++) {
    if (p->species[i] != 0) continue;
    const int j = (int)floor(p->x[1][i] / 0.5);
    n += j < 4 || j >= 12;
  }
  MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
  return n;
}

static sim_t *build(const scene_t *s) {
  sim_t *sim = sim_create(s, MPI_COMM_WORLD);
  if (!sim || init_configuration(sim, s) || sim_setup(sim)) return NULL;
  return sim;
}

static void unit_checks(void) {
  /* bounce_back: a 2 x 2 x 2 grid of 1 rc voxels, the upper y layer solid of species 2 moving */
  uint8_t solid[8];
  for (int k = 0; k < 8; k++) solid[k] = ((k / 2) % 2) ? 3 : 0;
  bounce_back_params_t b;
  memset(&b, 0, sizeof b);
  b.solid = solid;
  b.grid.n[0] = b.grid.n[1] = b.grid.n[2] = 2;
  b.grid.inv_h = 1.0;
  b.wall_u[2][0] = U_TOP;
  const double x_old[3] = {0.5, 0.9, 0.5};
  double x[3] = {0.52, 1.1, 0.5}, v[3] = {0.2, 2.0, -0.3};
  EXPECT(bounce_back_after_drift(&b, 0, x, v, x_old) == 0);
  EXPECT(x[0] == x_old[0] && x[1] == x_old[1] && x[2] == x_old[2]);
  EXPECT(fabs(v[0] - (2 * U_TOP - 0.2)) < 1e-15 && v[1] == -2.0 && v[2] == 0.3);
  /* wall_boundary: a flat wall moving at U along x above, normal -y into the fluid */
  wall_field_t field = {0};
  field.phi = 0.45f, field.gy = 1.0f, field.ux = (float)U_TOP;
  wall_boundary_params_t w;
  memset(&w, 0, sizeof w);
  w.field = &field;
  w.phi_c = 0.5;
  w.dt = 0.01;
  double y[3] = {0.0, 0.1, 0.0}, vw[3] = {0.1, 10.0, 0.0};
  const double y_old[3] = {0.0, 0.0, 0.0};
  wall_boundary_after_drift(&w, 0, y, vw, y_old);
  /* relative velocity (-0.4, 10, 0): tangential part reversed, normal part back into the fluid */
  EXPECT(fabs(vw[0] - (U_TOP + 0.4)) < 1e-6 && fabs(vw[1] + 10.0) < 1e-6 && vw[2] == 0.0);
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  use_cuda = argc > 1 && !strcmp(argv[1], "cuda");
  if (use_cuda) test_cuda_require_gpu();
  int rank, nranks;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &nranks);
  unit_checks();
  int ok = 1;
  if (rank == 0) ok = write_files(nranks) == 0;
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!ok) return 1;
  scene_t s;
  if (scene_load(SCENE, &s)) return 1;
  s.backend = use_cuda ? SCENE_BACKEND_CUDA : SCENE_BACKEND_CPU;
  s.progress = 0;
  const double tol = use_cuda ? 1e-5 : 1e-10;

  /* Cache off: the reference densities at set-up. */
  setenv("MDPORE_DENSITY_CACHE", "0", 1);
  sim_t *sim = build(&s);
  EXPECT(sim != NULL);
  if (!sim) return 1;
  double e = density_error(sim);
  if (rank == 0) printf("cache off, set-up: density error %.3g\n", e);
  EXPECT(e < tol);
  sim_destroy(sim);

  setenv("MDPORE_DENSITY_CACHE", "1", 1); /* on (the CUDA backend's cache is opt-in) */
  sim = build(&s);
  EXPECT(sim != NULL);
  if (!sim) return 1;
  /* where every wall particle started (by id, from every rank) */
  all_t a0;
  gather_all(sim, &a0);
  long n_total = a0.n;
  e = density_error(sim);
  if (rank == 0) printf("cache on, set-up: density error %.3g\n", e);
  EXPECT(e < tol);
  const int steps = 400, check_at[] = {1, 2, 50, 200, 400};
  int next = 0, n_drag = 0;
  double drag = 0.0; /* sum of the fluid's mean v_x over the samples */
  for (int t = 1; t <= steps; t++) {
    if (sim_step(sim)) {
      fprintf(stderr, "step %d: %s\n", t, sim_last_error(sim));
      EXPECT(0);
      break;
    }
    if (t >= 200 && t % 10 == 0) {
      particles_t *p = sim_particles(sim);
      double fl[2] = {0, 0}; /* count, sum v_x */
      for (int i = 0; i < p->n_local; i++)
        if (p->species[i] == 0) fl[0] += 1, fl[1] += p->v[0][i];
      MPI_Allreduce(MPI_IN_PLACE, fl, 2, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
      drag += fl[1] / fl[0];
      n_drag++;
    }
    if (next < 5 && t == check_at[next]) {
      next++;
      e = density_error(sim);
      const long pen = penetrations(sim);
      if (rank == 0) printf("step %d: density error %.3g, penetrations %ld\n", t, e, pen);
      EXPECT(e < tol);
      EXPECT(pen == 0);
    }
  }
  /* the walls: top moved by U t along x (wrapped), bottom at rest */
  all_t a1;
  gather_all(sim, &a1);
  EXPECT(a1.n == n_total);
  const double shift = U_TOP * steps * s.dt, Lx = s.box_hi[0] - s.box_lo[0];
  double worst_top = 0.0, worst_bottom = 0.0;
  long n_top = 0, n_bottom = 0;
  for (int k = 0; k < a1.n; k++) {
    if (a1.species[k] == 0) continue;
    int k0 = -1;
    for (int m = 0; m < a0.n; m++)
      if (a0.id[m] == a1.id[k]) k0 = m;
    EXPECT(k0 >= 0);
    if (k0 < 0) continue;
    double dx = a1.x[3 * k] - a0.x[3 * k0] - (a1.species[k] == 2 ? shift : 0.0);
    dx -= Lx * nearbyint(dx / Lx);
    const double err = fabs(dx) + fabs(a1.x[3 * k + 1] - a0.x[3 * k0 + 1]) +
                       fabs(a1.x[3 * k + 2] - a0.x[3 * k0 + 2]);
    if (a1.species[k] == 2) {
      n_top++;
      if (err > worst_top) worst_top = err;
    } else {
      n_bottom++;
      if (err > worst_bottom) worst_bottom = err;
    }
  }
  if (rank == 0)
    printf("walls after %d steps: top %ld particles off U t by %.3g rc, bottom %ld off by %.3g\n",
           steps, n_top, worst_top, n_bottom, worst_bottom);
  EXPECT(n_top > 0 && n_bottom > 0);
  EXPECT(worst_top < 1e-9 && worst_bottom == 0.0);
  particles_t *p = sim_particles(sim);
  int bad_v = 0;
  for (int i = 0; i < p->n_local; i++) {
    const int sp = p->species[i];
    if (sp == 0) continue;
    const double ux = sp == 2 ? U_TOP : 0.0;
    bad_v += p->v[0][i] != ux || p->v[1][i] != 0.0 || p->v[2][i] != 0.0;
  }
  MPI_Allreduce(MPI_IN_PLACE, &bad_v, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  EXPECT(bad_v == 0);
  const double mean_vx = n_drag ? drag / n_drag : 0.0;
  if (rank == 0)
    printf("fluid mean v_x over steps 200-400: %.4f (wall U %g; no slip: U / 2)\n", mean_vx, U_TOP);
  EXPECT(mean_vx > 0.2 * U_TOP && mean_vx < U_TOP);
  all_free(&a0);
  all_free(&a1);
  sim_destroy(sim);
  if (rank == 0) printf("%s\n", failures ? "FAIL" : "ok");
  MPI_Finalize();
  return failures ? 1 : 0;
}
