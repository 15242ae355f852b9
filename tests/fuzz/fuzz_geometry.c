/* Fuzz entry: a scene through scene_load and, when it has a `geometry:` block, the image wall build
 * (image_walls_build on MPI_COMM_SELF: the image read under axis_map, the box check, the wall
 * thickness, min_wall_distance and its room, the pore clusters, the fluid count per voxel and its
 * placement away from the walls, the ids). The entry writes the slit image the repository's
 * geometry test scenes name (slit_8x6x4.raw: walls at y = 0 and 5, labels '0' pore and '1'
 * inorganic) beside the scene, and a small patch database for the scene's rc_per_voxel,
 * wall_density and patch seed (so no database is built: 24 patches of three particles; a request
 * outside the database's range is refused by its check before any build). The scene must be
 * accepted, or refused with a message naming the scene file; an accepted build must count what it
 * placed consistently (else abort: a finding). Runs with the fuzzers' 32 MiB memory limit. */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "effects/scene_load.h"
#include "fuzz_util.h"
#include "populate/image_walls.h"
#include "populate/wall_patches.h"

static scene_t *s; /* large: not on the stack */

/* OpenMPI keeps some memory to the end on purpose (docs/fuzzing.md, "Limits"), much of it from
 * plugins it has unloaded by then (no name to suppress): no leak check at exit. libFuzzer's check
 * after each input that allocated more than it freed still runs (MPI starts before the inputs). */
const char *__lsan_default_options(void);
const char *__lsan_default_options(void) {
  return "leak_check_at_exit=0";
}

void fuzz_target_init(void) {
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0); /* as scripts/mpi-env.sh: no daemon */
  setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
  setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);
  int started = 0;
  MPI_Initialized(&started);
  if (started) return;
  MPI_Init(NULL, NULL); /* not finalized: its plugins, unloaded, would hide what they keep */
}

static void write_slit(void) {
  char path[300];
  fuzz_path("slit_8x6x4.raw.hdr", path, sizeof path);
  static const char hdr[] = "dims: 8 6 4\ntype: uint8\naxis_order: xyz\nheader_bytes: 0\n"
                            "labels: pore=48;inorganic=49\n";
  fuzz_write(path, hdr, sizeof hdr - 1);
  char voxels[8 * 6 * 4];
  for (int i = 0; i < 8 * 6 * 4; i++) {
    const int y = i / 8 % 6;
    voxels[i] = y == 0 || y == 5 ? '1' : '0';
  }
  fuzz_path("slit_8x6x4.raw", path, sizeof path);
  fuzz_write(path, voxels, sizeof voxels);
}

/* A database of 24 patches of three particles for the request at path; 0, or -1 when the request
 * is out of the database's range (no file: the build's own check refuses it before building). */
static int write_patches(const scene_geometry_t *geo, char *path, size_t len) {
  fuzz_path("patches.h5", path, len);
  remove(path);
  if (!(geo->rc_per_voxel >= WALL_PATCHES_EDGE_MIN && geo->rc_per_voxel <= WALL_PATCHES_EDGE_MAX &&
        geo->wall_density > 0 && geo->wall_density <= WALL_PATCHES_DENSITY_MAX))
    return -1;
  enum { PATCHES = 24, EACH = 3 }; /* the fewest patches a database holds */
  long start[PATCHES + 1];
  double x[3 * EACH * PATCHES];
  for (int p = 0; p <= PATCHES; p++) start[p] = (long)p * EACH;
  for (int i = 0; i < 3 * EACH * PATCHES; i++)
    x[i] = geo->rc_per_voxel * (0.1 + 0.8 * ((i * 5) % 7) / 7.0);
  wall_patches_t db = {.edge = geo->rc_per_voxel,
                       .density = geo->wall_density,
                       .seed = geo->patch_seed,
                       .count = PATCHES,
                       .start = start,
                       .x = x};
  wall_patches_run_t run = {
      .steps = 1, .runs = 1, .cubes = 1, .temperature = 1, .temperature_mean = 1};
  char err[1024];
  if (wall_patches_write(path, &db, &run, err, sizeof err)) {
    fprintf(stderr, "fuzz: geometry: cannot write the patch database: %s\n", err);
    abort();
  }
  return 0;
}

static void check_build(const char *path, const image_walls_t *g) {
  const image_walls_counts_t *c = &g->count;
  const long long n = (long long)g->n[0] * g->n[1] * g->n[2];
  const int ok = n == 8 * 6 * 4 && c->voxels == n && c->pore + c->organic + c->inorganic == n &&
                 c->fluid_voxels >= 0 && c->fluid_voxels <= c->pore && c->fluid_dropped >= 0 &&
                 c->fluid_particles == c->fluid_target - c->fluid_dropped &&
                 g->n_fluid == c->fluid_particles && g->n_wall >= 0 &&
                 image_walls_total(g) == g->n_wall + g->n_fluid;
  if (!ok) {
    fprintf(stderr,
            "fuzz: %s: the build's counts disagree: %lld voxels (%lld pore, %lld fluid), fluid "
            "target %ld dropped %ld placed %ld (list %ld), walls %ld, total %ld\n",
            path, c->voxels, c->pore, c->fluid_voxels, c->fluid_target, c->fluid_dropped,
            c->fluid_particles, g->n_fluid, g->n_wall, image_walls_total(g));
    abort();
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300], patches[300];
  if (!s && !(s = malloc(sizeof *s))) abort();
  write_slit(); /* every time: the scene may name it as an output */
  fuzz_path("scene.yaml", path, sizeof path);
  fuzz_write(path, data, size);
  fuzz_capture_begin();
  int rc = scene_load(path, s);
  if (!rc && s->geometry.image[0]) {
    write_patches(&s->geometry, patches, sizeof patches); /* out of range: absent, refused */
    snprintf(s->geometry.patches, sizeof s->geometry.patches, "%s", patches);
    image_walls_t g;
    rc = image_walls_build(s, MPI_COMM_SELF, &g);
    if (!rc) {
      check_build(path, &g);
      image_walls_free(&g);
    }
  }
  fuzz_outcome(rc, fuzz_capture_end(), path);
  return 0;
}
