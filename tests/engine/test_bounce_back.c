/* bounce_back keeps every mobile particle out of the solid voxels of a geometry image, and the
 * penetration count sees it when nothing does:
 *  - a slit image (8 pore layers between solid layers, 0.5 rc voxels) written to a file and named by
 *    a scene built in code (geometry.image), standard DPD fluid at density 3 in the pore voxels, a
 *    strong body force across the slit (g_y = 0.5, pushing everything against one wall);
 *  - with bounce_back: 0 particles inside the solid after every one of 400 steps, the count
 *    conserved, and the explain plan lists bounce_back under after_drift;
 *  - without it (same start): the penetration count becomes > 0 (the counter is not blind).
 * With the argument "cuda" the same on the CUDA backend (the solid map is a device copy of the
 * plan's array); skipped (77) without a GPU. */
#include "common/mpi_singleton.h"
#include "test_cuda_common.h"

#include "analysis/penetration.h"
#include "mdpore_image.h"

static int make_image(const char *path) {
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_t img;
  /* x: 16 voxels, y: 4 solid + 8 pore + 4 solid (periodic: one 4-voxel wall), z: 8 voxels */
  if (mdp_make_slit(&img, 8, 4, 16, 8, err) || mdp_image_write_hdf5(&img, path, err)) {
    fprintf(stderr, "%s\n", err);
    return -1;
  }
  mdp_image_free(&img);
  return 0;
}

static int use_cuda = 0;

static void scene_of(scene_t *s, const char *image, int with_bounce) {
  test_scene_mdpd(s, 8.0, 8.0, 4.0); /* 16 x 16 x 8 voxels of 0.5 rc */
  s->pair[0][0].A = 25.0;            /* standard DPD: robust to a random start */
  effect_name_in_scene(s, EFFECT_DPD_CONSERVATIVE);
  effect_name_in_scene(s, EFFECT_DPD_THERMOSTAT);
  effect_name_in_scene(s, EFFECT_BODY_FORCE);
  SCENE_EFFECT_OPTIONS(s, EFFECT_BODY_FORCE, body_force_params_t)->g[0][1] = 0.5;
  if (with_bounce) effect_name_in_scene(s, EFFECT_BOUNCE_BACK);
  s->dt = 0.01;
  s->backend = use_cuda ? SCENE_BACKEND_CUDA : SCENE_BACKEND_CPU;
  scene_geometry_t *g = &s->geometry;
  g->on = 1;
  snprintf(g->image, sizeof g->image, "%s", image);
  g->rc_per_voxel = 0.5;
  g->axis_map[0] = 0, g->axis_map[1] = 1, g->axis_map[2] = 2;
  g->fluid_species = 0;
  g->organic_species = g->inorganic_species = -1;
}

/* Fluid at density 3 at random positions in the pore voxels (y in [2, 6) rc). */
static sim_t *build(const scene_t *s) {
  sim_t *sim = sim_create(s, MPI_COMM_WORLD);
  if (!sim) return NULL;
  uint64_t st = 99;
  const int n = (int)(3.0 * 8.0 * 4.0 * 4.0);
  for (int i = 0; i < n; i++) {
    const double x[3] = {8.0 * test_rng_uniform(&st), 2.0 + 4.0 * test_rng_uniform(&st),
                         4.0 * test_rng_uniform(&st)};
    double v[3];
    for (int d = 0; d < 3; d++) v[d] = sqrt(3.0) * (2.0 * test_rng_uniform(&st) - 1.0);
    if (sim_add_particle(sim, i, 0, x, v) < 0) return NULL;
  }
  if (sim_setup(sim)) return NULL;
  return sim;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  use_cuda = argc > 1 && !strcmp(argv[1], "cuda");
  if (use_cuda) test_cuda_require_gpu();
  const char *image = "bounce_back_slit.h5";
  int bad = rank == 0 ? make_image(image) : 0;
  MPI_Bcast(&bad, 1, MPI_INT, 0, MPI_COMM_WORLD);
  CHECK(!bad, "writing the slit image");

  for (int with = 1; with >= 0; with--) {
    scene_t s;
    scene_of(&s, image, with);
    char err[1024];
    penetration_map_t map;
    CHECK(penetration_map_create(&map, &s, err, sizeof err) == 0, "penetration map: %s", err);
    if (with && rank == 0) {
      char *buf = NULL;
      size_t len = 0;
      FILE *f = open_memstream(&buf, &len);
      sim_explain(&s, 1, f);
      fclose(f);
      CHECK(strstr(buf, "after_drift: position constraints: bounce_back"),
            "explain lacks the bounce_back phase:\n%s", buf);
      free(buf);
    }
    sim_t *sim = build(&s);
    CHECK(sim, "building the simulation (bounce_back %d)", with);
    long worst = 0, first_bad = -1;
    for (int step = 1; step <= 400; step++) {
      if (sim_step(sim)) {
        CHECK(!with, "step %d failed with bounce_back: %s", step, sim_last_error(sim));
        break;
      }
      penetration_t pen;
      penetration_count(&map, sim, &pen);
      if (pen.count > worst) worst = pen.count;
      if (pen.count && first_bad < 0) first_bad = step;
    }
    thermo_t th;
    sim_thermo(sim, &th);
    if (rank == 0)
      printf("%s, bounce_back %s: most particles inside the solid at once %ld (first at step %ld), "
             "T = %.3f, N = %ld\n",
             use_cuda ? "cuda" : "cpu", with ? "on " : "off", worst, first_bad, th.temperature,
             th.n_total);
    if (with) {
      CHECK(worst == 0, "%ld particles inside the solid with bounce_back (first at step %ld)",
            worst, first_bad);
      CHECK(th.n_total == (long)(3.0 * 8.0 * 4.0 * 4.0), "particle count changed");
    } else {
      CHECK(worst > 0, "without a boundary the penetration count stayed 0: the counter is blind");
    }
    sim_destroy(sim);
    penetration_map_free(&map);
  }
  if (rank == 0) remove(image);
  MPI_Finalize();
  return 0;
}
