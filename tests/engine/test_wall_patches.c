/* The wall patch database (meso/populate/wall_patches.h), CI-sized: short equilibration runs
 * (TEST_STEPS instead of WALL_PATCHES_STEPS) of the edge-1 box at density 8. Checks the patches
 * (count, bounds, density, no overlapping particles), determinism, the file round trip, the cache
 * (into this test's working directory, never $HOME) and its in-memory fallback, the refusal of
 * mismatching or corrupt files, and the 24 cube rotations. */
#include "common/mpi_singleton.h"
#include "populate/wall_patches.h"

#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CHECK(cond, ...)                                                                           \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);                                         \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fprintf(stderr, "\n");                                                                       \
      return 1;                                                                                    \
    }                                                                                              \
  } while (0)

/* 300 steps: kT and the pressure of the random start settle within ~150 steps (the full build
 * runs WALL_PATCHES_STEPS; wall_patches.c has the measurements). */
#define TEST_STEPS 300L
/* Smallest pair distance inside a patch, measured over 10 seeds: 0.18-0.26 rc after 2000 steps,
 * 0.22-0.29 after 300 (0.287 for seed 1); the random start has pairs at ~ 0.01 rc. */
#define MIN_PAIR_DISTANCE 0.1

static long n_of(const wall_patches_t *p) {
  return p->start[p->count];
}

static int same(const wall_patches_t *a, const wall_patches_t *b) {
  return a->count == b->count && a->edge == b->edge && a->density == b->density &&
         a->seed == b->seed &&
         !memcmp(a->start, b->start, ((size_t)a->count + 1) * sizeof *a->start) &&
         !memcmp(a->x, b->x, (size_t)n_of(a) * 3 * sizeof *a->x);
}

static int file_bytes(const char *path, char **buf, long *len) {
  FILE *fp = fopen(path, "rb");
  if (!fp) return -1;
  fseek(fp, 0, SEEK_END);
  *len = ftell(fp);
  rewind(fp);
  *buf = malloc((size_t)*len);
  const int ok = *buf && fread(*buf, 1, (size_t)*len, fp) == (size_t)*len;
  fclose(fp);
  return ok ? 0 : -1;
}

/* (1) and (2): count, bounds, mean particles per patch, smallest pair distance in a patch. */
static int check_patches(const wall_patches_t *p, const wall_patches_run_t *run) {
  CHECK(p->count >= 24, "%d patches, expected >= 24", p->count);
  CHECK(p->start[0] == 0, "start[0] = %ld", p->start[0]);
  for (int k = 0; k < p->count; k++)
    CHECK(p->start[k + 1] >= p->start[k], "start decreases at patch %d", k);
  for (long i = 0; i < 3 * n_of(p); i++)
    CHECK(p->x[i] >= 0.0 && p->x[i] < p->edge, "particle %ld: %c = %.17g outside [0, %g)", i / 3,
          "xyz"[i % 3], p -> x[i], p -> edge);
  const double mean = (double)n_of(p) / p->count, want = p->density * pow(p->edge, 3);
  CHECK(fabs(mean - want) <= 0.1 * want, "%.3f particles per patch, expected %g +- 10%%", mean,
        want);
  double dmin = 1e300;
  for (int k = 0; k < p->count; k++)
    for (long i = p->start[k]; i < p->start[k + 1]; i++)
      for (long j = i + 1; j < p->start[k + 1]; j++) {
        double r2 = 0;
        for (int d = 0; d < 3; d++) r2 += pow(p->x[3 * i + d] - p->x[3 * j + d], 2);
        if (r2 < dmin * dmin) dmin = sqrt(r2);
      }
  CHECK(dmin > MIN_PAIR_DISTANCE, "smallest pair distance in a patch %.4f, expected > %g", dmin,
        MIN_PAIR_DISTANCE);
  CHECK(fabs(run->temperature_mean - 1.0) < 0.05, "mean kT over the second half %.4f",
        run->temperature_mean);
  printf("%d patches, %.3f particles per patch (want %g), smallest pair distance %.4f, kT last "
         "%.4f, mean over the second half %.4f\n",
         p->count, mean, want, dmin, run->temperature, run->temperature_mean);
  return 0;
}

/* (5): the 24 rotations about the cube's centre. */
static int check_orientations(void) {
  const double edge = 0.75, c = edge / 2;
  const double q[3] = {0.1234, 0.3456, 0.6789}; /* generic: no two coordinates alike */
  double img[24][3], R[24][3][3];
  for (int o = 0; o < 24; o++) {
    wall_patch_orient(o, edge, q, img[o]);
    for (int d = 0; d < 3; d++)
      CHECK(img[o][d] >= 0.0 && img[o][d] < edge, "orientation %d: image outside the cube", o);
    /* the linear part: images of c + 0.25 e_k about the centre */
    for (int k = 0; k < 3; k++) {
      double in[3] = {c, c, c}, out[3];
      in[k] += 0.25;
      wall_patch_orient(o, edge, in, out);
      for (int d = 0; d < 3; d++) R[o][d][k] = (out[d] - c) / 0.25;
    }
    const double det = R[o][0][0] * (R[o][1][1] * R[o][2][2] - R[o][1][2] * R[o][2][1]) -
                       R[o][0][1] * (R[o][1][0] * R[o][2][2] - R[o][1][2] * R[o][2][0]) +
                       R[o][0][2] * (R[o][1][0] * R[o][2][1] - R[o][1][1] * R[o][2][0]);
    CHECK(fabs(det - 1.0) < 1e-12, "orientation %d: determinant %g, expected +1", o, det);
    double r0 = 0, r1 = 0;
    for (int d = 0; d < 3; d++) {
      r0 += pow(q[d] - c, 2);
      r1 += pow(img[o][d] - c, 2);
    }
    CHECK(fabs(r0 - r1) < 1e-12, "orientation %d does not keep the distance to the centre", o);
  }
  for (int d = 0; d < 3; d++) CHECK(img[0][d] == q[d], "orientation 0 is not the identity");
  for (int a = 0; a < 24; a++)
    for (int b = a + 1; b < 24; b++) {
      double dd = 0;
      for (int d = 0; d < 3; d++) dd += fabs(img[a][d] - img[b][d]);
      CHECK(dd > 1e-9, "orientations %d and %d give the same image", a, b);
    }
  /* the corner and a point just below the far face stay inside [0, edge) */
  const double corner[3] = {0, 0, 0}, far[3] = {nextafter(edge, 0), 0.5, nextafter(edge, 0)};
  for (int o = 0; o < 24; o++) {
    double out[3], out2[3];
    wall_patch_orient(o, edge, corner, out);
    wall_patch_orient(o, edge, far, out2);
    for (int d = 0; d < 3; d++)
      CHECK(out[d] >= 0 && out[d] < edge && out2[d] >= 0 && out2[d] < edge,
            "orientation %d: a face point leaves [0, edge)", o);
  }
  return 0;
}

/* (6) and corrupt files: refused with a message naming the file and the key. */
static int check_refused(const char *path, double edge, double density, uint64_t seed,
                         const char *key) {
  wall_patches_t p;
  char err[1024] = "";
  const int rc =
      wall_patches_load_or_build(path, edge, density, seed, MPI_COMM_WORLD, &p, err, sizeof err);
  CHECK(rc != 0, "%s was accepted (expected a refusal naming '%s')", path, key);
  CHECK(strstr(err, path) && strstr(err, key), "message '%s' does not name %s and '%s'", err, path,
        key);
  printf("refused as expected: %s\n", err);
  return 0;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  char cwd[1024], cache[1100], path[1200], other[1300];
  if (!getcwd(cwd, sizeof cwd)) return 1;
  snprintf(cache, sizeof cache, "%s/wall_patches_cache", cwd);
  setenv("MDPORE_CACHE_DIR", cache, 1); /* never $HOME */
  char err[1024];
  int rc = check_orientations();

  char name[2400];
  wall_patches_cache_path(1.0, 8.0, 1, name, sizeof name);
  snprintf(path, sizeof path, "%s/wall-patches-e1-d8-s1.h5", cache);
  CHECK(!strcmp(name, path), "cache path %s, expected %s", name, path);
  wall_patches_cache_path(0.5, 6.2, 42, name, sizeof name);
  snprintf(path, sizeof path, "%s/wall-patches-e0.5-d6.2-s42.h5", cache);
  CHECK(!strcmp(name, path), "cache path %s, expected %s", name, path);

  /* (1), (2): one build */
  const double t0 = MPI_Wtime();
  wall_patches_t a, b, c, f;
  wall_patches_run_t ra, rb;
  CHECK(!wall_patches_build(1.0, 8.0, 1, TEST_STEPS, &a, &ra, err, sizeof err), "%s", err);
  printf("build of %ld particles, %ld steps: %.2f s\n", n_of(&a), TEST_STEPS, MPI_Wtime() - t0);
  if (!rc) rc = check_patches(&a, &ra);
  /* (3): the same seed gives the same bits, another seed other ones */
  CHECK(!wall_patches_build(1.0, 8.0, 1, TEST_STEPS, &b, &rb, err, sizeof err), "%s", err);
  CHECK(same(&a, &b), "two builds with seed 1 differ");
  CHECK(rb.temperature == ra.temperature, "two builds with seed 1: different temperatures");
  CHECK(!wall_patches_build(1.0, 8.0, 2, TEST_STEPS, &c, &rb, err, sizeof err), "%s", err);
  CHECK(c.count == a.count, "seed 2: %d patches, seed 1: %d", c.count, a.count);
  CHECK(n_of(&c) != n_of(&a) || memcmp(a.x, c.x, (size_t)n_of(&a) * 3 * sizeof *a.x) ||
            memcmp(a.start, c.start, ((size_t)a.count + 1) * sizeof *a.start),
        "seeds 1 and 2 give the same database");

  /* (4): the file gives exactly the built arrays; the same database, the same bytes */
  snprintf(path, sizeof path, "%s/wall_patches_e1_s1.h5", cwd);
  snprintf(other, sizeof other, "%s/wall_patches_e1_s1_again.h5", cwd);
  CHECK(!wall_patches_write(path, &a, &ra, err, sizeof err), "%s", err);
  CHECK(!wall_patches_write(other, &b, &ra, err, sizeof err), "%s", err);
  char *b1 = NULL, *b2 = NULL;
  long l1 = 0, l2 = 0;
  CHECK(!file_bytes(path, &b1, &l1) && !file_bytes(other, &b2, &l2), "cannot read the files back");
  CHECK(l1 == l2 && !memcmp(b1, b2, (size_t)l1), "the same database wrote different bytes");
  free(b1);
  free(b2);
  CHECK(!wall_patches_load_or_build(path, 1.0, 8.0, 1, MPI_COMM_WORLD, &f, err, sizeof err), "%s",
        err);
  CHECK(same(&a, &f), "%s does not give the built arrays back", path);
  wall_patches_free(&f);

  /* the cache: built into MDPORE_CACHE_DIR (created), then read from it */
  wall_patches_cache_path(1.0, 8.0, 1, name, sizeof name);
  remove(name);
  wall_patches_run_t rf;
  CHECK(!wall_patches_load_or_build_steps("", 1.0, 8.0, 1, TEST_STEPS, MPI_COMM_WORLD, &f, &rf, err,
                                          sizeof err),
        "%s", err);
  CHECK(access(name, F_OK) == 0, "%s was not written", name);
  CHECK(same(&a, &f) && rf.steps == TEST_STEPS && rf.runs == 1 && rf.cubes == 4,
        "the cached database differs from the built one");
  wall_patches_free(&f);
  CHECK(!wall_patches_load_or_build_steps("", 1.0, 8.0, 1, 1, MPI_COMM_WORLD, &f, &rf, err,
                                          sizeof err),
        "%s", err);
  CHECK(same(&a, &f) && rf.steps == TEST_STEPS, "the cache file was not reused");
  wall_patches_free(&f);
  /* a cache directory that cannot be created: built in memory, not failed */
  snprintf(other, sizeof other, "%s/sub", path); /* below a regular file */
  setenv("MDPORE_CACHE_DIR", other, 1);
  fprintf(stderr, "(a message about the cache directory follows, as expected)\n");
  CHECK(!wall_patches_load_or_build_steps("", 1.0, 8.0, 1, TEST_STEPS, MPI_COMM_WORLD, &f, NULL,
                                          err, sizeof err),
        "no in-memory fallback: %s", err);
  CHECK(same(&a, &f), "the in-memory database differs from the built one");
  wall_patches_free(&f);
  setenv("MDPORE_CACHE_DIR", cache, 1);

  /* (6): a file for another request, and corrupt files */
  if (!rc) rc = check_refused(path, 0.5, 8.0, 1, "edge");
  if (!rc) rc = check_refused(path, 1.0, 6.2, 1, "density");
  if (!rc) rc = check_refused(path, 1.0, 8.0, 3, "seed");
  snprintf(other, sizeof other, "%s/wall_patches_corrupt.h5", cwd);
  const double x5 = a.x[5];
  a.x[5] = a.edge; /* a position on the far face */
  CHECK(!wall_patches_write(other, &a, &ra, err, sizeof err), "%s", err);
  if (!rc) rc = check_refused(other, 1.0, 8.0, 1, "/x");
  a.x[5] = x5;
  const long keep = a.start[3];
  a.start[3] = a.start[4] + 1; /* decreasing */
  CHECK(!wall_patches_write(other, &a, &ra, err, sizeof err), "%s", err);
  if (!rc) rc = check_refused(other, 1.0, 8.0, 1, "/start");
  a.start[3] = keep;
  a.density = NAN;
  CHECK(!wall_patches_write(other, &a, &ra, err, sizeof err), "%s", err);
  if (!rc) rc = check_refused(other, 1.0, 8.0, 1, "density");
  FILE *fp = fopen(other, "w");
  CHECK(fp && fputs("not a database\n", fp) >= 0 && !fclose(fp), "cannot write %s", other);
  if (!rc) rc = check_refused(other, 1.0, 8.0, 1, other);

  wall_patches_free(&a);
  wall_patches_free(&b);
  wall_patches_free(&c);
  printf("%s (%.2f s)\n", rc ? "FAILED" : "all wall patch checks passed", MPI_Wtime() - t0);
  MPI_Finalize();
  return rc;
}
