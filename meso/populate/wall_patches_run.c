/* The equilibration runs of the wall patch database and the cutting of their boxes into cubes
 * (wall_patches_build; wall_patches.c has how and why, the file and the cache). */
#include "populate/init_random.h"
#include "populate/wall_patches.h"
#include "effects/effect.h"
#include "engine/sim.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { PATCH_STREAM_POSITION = 0x70617401u, PATCH_STREAM_VELOCITY = 0x70617402u };

static int fail(char *err, size_t errlen, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, errlen, fmt, ap);
  va_end(ap);
  return -1;
}

/* The seed of run r of a database: splitmix64 of (seed, r), so runs are independent streams. */
static uint64_t run_seed(uint64_t seed, int r) {
  uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (uint64_t)(r + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/* The periodic one-species mDPD box of side L: the water model of physics.md (A = -40, B = 25,
 * rd = 0.75, gamma = 4.5, kT = 1, rc = 1), dt = 0.01, CPU backend. */
static void patch_scene(scene_t *s, double L, uint64_t seed) {
  memset(s, 0, sizeof *s);
  s->neighbour_skin = -1.0;
  snprintf(s->file, sizeof s->file, "(wall patch run)");
  snprintf(s->name, sizeof s->name, "wall-patches");
  for (int d = 0; d < 3; d++) {
    s->box_lo[d] = 0.0;
    s->box_hi[d] = L;
    s->periodic[d] = 1;
    s->procs[d] = 1;
  }
  s->n_species = 1;
  snprintf(s->species[0].name, SCENE_NAME_LEN, "wall");
  s->species[0].mass = 1.0;
  s->pair[0][0] = (scene_pair_t){.A = -40, .B = 25, .gamma = 4.5, .rc = 1.0, .rd = 0.75};
  s->density_kernel = 0;
  s->kT = 1.0;
  s->vv_lambda = 0.5;
  s->dt = 0.01;
  s->seed = seed;
  s->backend = SCENE_BACKEND_CPU;
  s->progress = 0;
  effect_name_in_scene(s, EFFECT_MDPD_ATTRACTION);
  effect_name_in_scene(s, EFFECT_MDPD_REPULSION);
  effect_name_in_scene(s, EFFECT_DPD_THERMOSTAT);
}

/* One run: n particles at random positions with Maxwell-Boltzmann velocities (zero total momentum),
 * `steps` steps; the final positions by particle id into xs[3 n]. Temperatures: the last one, and
 * the sum and number of samples (every 10 steps) over the second half. */
static int equilibrate(double L, long n, uint64_t seed, long steps, double *xs, double *t_last,
                       double *t_sum, long *t_samples, char *err, size_t errlen) {
  scene_t s;
  patch_scene(&s, L, seed);
  sim_t *sim = sim_create(&s, MPI_COMM_SELF);
  if (!sim) return fail(err, errlen, "wall patches: cannot create the equilibration run");
  double vsum[3] = {0, 0, 0};
  double *v = malloc((size_t)n * 3 * sizeof *v);
  if (!v) {
    sim_destroy(sim);
    return fail(err, errlen, "wall patches: out of memory (%ld particles)", n);
  }
  for (long i = 0; i < n; i++) {
    init_normal3(seed, PATCH_STREAM_VELOCITY, (uint64_t)i, v + 3 * i);
    for (int d = 0; d < 3; d++) vsum[d] += v[3 * i + d];
  }
  int rc = 0;
  for (long i = 0; i < n && !rc; i++) {
    double u[4], x[3], vi[3];
    init_uniform4(seed, PATCH_STREAM_POSITION, (uint64_t)i, u);
    for (int d = 0; d < 3; d++) {
      x[d] = u[d] * L;
      if (!(x[d] < L)) x[d] = 0.0; /* u < 1, but u * L may round up to L */
      vi[d] = v[3 * i + d] - vsum[d] / (double)n;
    }
    if (sim_add_particle(sim, i, 0, x, vi) != 1) rc = -1;
  }
  free(v);
  if (rc || sim_setup(sim)) {
    fail(err, errlen, "wall patches: the equilibration run could not start (%s)",
         sim_last_error(sim)[0] ? sim_last_error(sim) : "see the message above");
    sim_destroy(sim);
    return -1;
  }
  *t_sum = 0.0;
  *t_samples = 0;
  thermo_t th;
  for (long k = 1; k <= steps; k++) {
    if (sim_step(sim)) {
      snprintf(err, errlen, "wall patches: the equilibration run failed at step %ld: %s", k,
               sim_last_error(sim));
      sim_destroy(sim);
      return -1;
    }
    if (k % 10 == 0 || k == steps) {
      sim_thermo(sim, &th);
      if (2 * k > steps && k % 10 == 0) {
        *t_sum += th.temperature;
        (*t_samples)++;
      }
    }
  }
  if (steps == 0) sim_thermo(sim, &th);
  *t_last = th.temperature;
  const particles_t *p = sim_particles(sim);
  if (p->n_local != n) {
    sim_destroy(sim);
    return fail(err, errlen, "wall patches: %ld particles after the run, expected %ld",
                (long)p->n_local, n);
  }
  for (int i = 0; i < p->n_local; i++) {
    const int64_t id = p->id[i];
    if (id < 0 || id >= n) {
      sim_destroy(sim);
      return fail(err, errlen, "wall patches: particle id %lld after the run", (long long)id);
    }
    for (int d = 0; d < 3; d++) xs[3 * id + d] = p->x[d][i];
  }
  sim_destroy(sim);
  return 0;
}

/* The cube index (0..m-1) of coordinate x of a box of side m * edge, and x relative to the cube's
 * lower face in [0, edge). */
static int cube_of(double x, double edge, int m, double L, double *rel) {
  if (x < 0.0) x += L; /* the box wrap leaves [0, L), these two are for rounding only */
  if (x >= L) x -= L;
  int c = (int)floor(x / edge);
  if (c < 0) c = 0;
  if (c > m - 1) c = m - 1;
  double r = x - c * edge;
  const double top = nextafter(edge, 0.0);
  *rel = r < 0.0 ? 0.0 : r > top ? top : r;
  return c;
}

int wall_patches_build(double edge, double density, uint64_t seed, long steps, wall_patches_t *out,
                       wall_patches_run_t *run, char *err, size_t errlen) {
  memset(out, 0, sizeof *out);
  if (!(edge >= WALL_PATCHES_EDGE_MIN && edge <= WALL_PATCHES_EDGE_MAX))
    return fail(err, errlen, "wall patches: edge %g: expected %g to %g rc", edge,
                WALL_PATCHES_EDGE_MIN, WALL_PATCHES_EDGE_MAX);
  if (!(density > 0.0 && density <= WALL_PATCHES_DENSITY_MAX))
    return fail(err, errlen, "wall patches: density %g: expected > 0 and <= %g per rc^3", density,
                WALL_PATCHES_DENSITY_MAX);
  if (steps < 0) return fail(err, errlen, "wall patches: steps %ld: expected >= 0", steps);
  /* m: the smallest number of cubes per edge with a box of side >= 4 rc (cell lists need 3). */
  int m = (int)ceil(4.0 / edge);
  while (m > 1 && (m - 1) * edge >= 4.0) m--;
  while (m * edge < 4.0) m++;
  const double L = m * edge;
  const long cubes = (long)m * m * m;
  const int runs = cubes >= 24 ? 1 : (int)((64 + cubes - 1) / cubes);
  const long n = llround(density * L * L * L);
  if (n < 2) return fail(err, errlen, "wall patches: density %g gives %ld particles", density, n);
  out->edge = edge;
  out->density = density;
  out->seed = seed;
  out->count = (int)(cubes * runs);
  out->start = calloc((size_t)out->count + 1, sizeof *out->start);
  out->x = malloc((size_t)n * runs * 3 * sizeof *out->x);
  double *xs = malloc((size_t)n * 3 * sizeof *xs);
  int *cube = malloc((size_t)n * sizeof *cube);
  long *fill = malloc((size_t)cubes * sizeof *fill);
  double *rel = malloc((size_t)n * 3 * sizeof *rel);
  int rc = 0;
  if (!out->start || !out->x || !xs || !cube || !fill || !rel)
    rc = fail(err, errlen, "wall patches: out of memory (%ld patches, %ld particles)", cubes * runs,
              n * runs);
  double t_last = 0.0, t_sum = 0.0;
  long t_samples = 0;
  for (int r = 0; r < runs && !rc; r++) {
    double sum = 0.0;
    long samples = 0;
    rc = equilibrate(L, n, run_seed(seed, r), steps, xs, &t_last, &sum, &samples, err, errlen);
    if (rc) break;
    t_sum += sum;
    t_samples += samples;
    /* Each particle to the cube containing it; within a cube in id order (a counting sort). */
    long *start = out->start + (long)r * cubes;
    memset(fill, 0, (size_t)cubes * sizeof *fill);
    for (long i = 0; i < n; i++) {
      int c[3];
      for (int d = 0; d < 3; d++) c[d] = cube_of(xs[3 * i + d], edge, m, L, &rel[3 * i + d]);
      cube[i] = (c[2] * m + c[1]) * m + c[0];
      fill[cube[i]]++;
    }
    for (long c = 0; c < cubes; c++) {
      start[c + 1] = start[c] + fill[c];
      fill[c] = start[c];
    }
    for (long i = 0; i < n; i++) {
      const long k = fill[cube[i]]++;
      memcpy(out->x + 3 * k, rel + 3 * i, 3 * sizeof *rel);
    }
  }
  free(xs);
  free(cube);
  free(fill);
  free(rel);
  if (rc) {
    wall_patches_free(out);
    return -1;
  }
  if (run) {
    run->steps = steps;
    run->runs = runs;
    run->cubes = m;
    run->temperature = t_last;
    run->temperature_mean = t_samples ? t_sum / (double)t_samples : t_last;
  }
  return 0;
}
