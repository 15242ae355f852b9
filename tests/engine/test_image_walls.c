/* The image wall builder (meso/populate/image_walls.h, docs/walls.md) on a slit made with
 * mdp_make_slit (6 pore layers between 4-voxel walls, 16 x 14 x 8 voxels, rc_per_voxel 0.5, the
 * upper wall organic, the lower inorganic) with three extra pores cut into the walls: a dead-end
 * pocket across the periodic y face, an isolated voxel, and a voxel open to the x = 0 face that
 * joins the slit only through the periodic x face. Written to HDF5 and loaded through a scene file
 * as a user would. Asserts, against the image and brute force:
 *  - the wall particles are the kept wall voxels' patches (sum of the chosen patches' sizes), no
 *    particle in a solid voxel deeper than the thickness (rc + rd = 1.75 rc = 3.5 voxels);
 *  - the clusters: 1 spanning x, 1 joined through the periodic face, 1 isolated, 2 dead-end;
 *  - fluid only in the voxels of the spanning and joined clusters (none in solid or in the left-empty
 *    pores), round(6.2 x their volume) minus the reported drops, none closer than
 *    min_wall_distance to a wall particle; with isolated_pores: fill the other pores get fluid too;
 *  - frozen walls at rest, ids 1..N unique, the same particles (ids, positions, velocities, bitwise)
 *    built on 1 rank and on all ranks;
 *  - 300 steps (mdpd_attraction, mdpd_repulsion, dpd_thermostat; walls frozen) without an engine
 *    error.
 * Run on 2 ranks. With one argument SCENE.yaml it only builds that scene's geometry and exits 1
 * when that fails (the checker of tests/engine/bad_scenes/geometry). */
#include "common/mpi_singleton.h"
#include "populate/image_walls.h"
#include "populate/init_config.h"
#include "analysis/penetration.h"
#include "effects/scene_load.h"
#include "engine/sim.h"
#include "io/gather.h"
#include "mdpore_image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_io_check.h"

#define IMG "image_walls_slit.h5"
#define SCENE "image_walls_slit.yaml"
#define PATCHES "image_walls_patches.h5"

static const char *scene_text =
    "box: {lo: [0, 0, 0], hi: [8, 7, 4]}\n"
    "species:\n"
    "  - {name: liquid}\n"
    "  - {name: quartz, frozen: true}\n"
    "  - {name: kerogen, frozen: true}\n"
    "pairs:\n"
    "  default: {A: -40, B: 25, gamma: 4.5, rc: 1, rd: 0.75}\n"
    "  liquid-quartz: {A: -30}\n"
    "  liquid-kerogen: {A: -20}\n"
    "effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}, bounce_back: {},\n"
    "          wall_boundary: {}}\n"
    "geometry:\n"
    "  image: " IMG "\n"
    "  labels: pore=0,inorganic=1,organic=2\n"
    "  rc_per_voxel: 0.5\n"
    "  flow_axis: x\n"
    "  species: {fluid: liquid, inorganic: quartz, organic: kerogen}\n"
    "  patches: {file: " PATCHES ", seed: 7}\n"
    "initial: {temperature: 1.0}\n"
    "run: {dt: 0.01, steps: 300, seed: 11}\n";

enum { NX = 16, NY = 14, NZ = 8, WALL = 4, PORE = 6 };

static int make_image(void) {
  mdp_image_t img;
  char err[MDP_IMAGE_ERR_LEN];
  if (mdp_make_slit(&img, PORE, WALL, NX, NZ, err) ||
      mdp_image_parse_labels("pore=0,inorganic=1,organic=2", img.phase_of, err)) {
    fprintf(stderr, "%s\n", err);
    return -1;
  }
  for (int k = 0; k < NZ; k++)
    for (int j = WALL + PORE; j < NY; j++)
      for (int i = 0; i < NX; i++) img.label[mdp_image_index(&img, i, j, k)] = 2; /* organic */
  /* dead-end pocket: y = 0 and y = 13 (joined to each other across the periodic y face only) */
  for (int k = 2; k < 4; k++)
    for (int i = 4; i < 6; i++) {
      img.label[mdp_image_index(&img, i, 0, k)] = 0;
      img.label[mdp_image_index(&img, i, NY - 1, k)] = 0;
    }
  img.label[mdp_image_index(&img, 10, 12, 4)] = 0; /* isolated */
  /* (15, 2..3, 0) belongs to the slit; (0, 2, 0) joins it through the periodic x face */
  img.label[mdp_image_index(&img, 15, 3, 0)] = 0;
  img.label[mdp_image_index(&img, 15, 2, 0)] = 0;
  img.label[mdp_image_index(&img, 0, 2, 0)] = 0;
  int rc = mdp_image_write_hdf5(&img, IMG, err);
  if (rc) fprintf(stderr, "%s\n", err);
  mdp_image_free(&img);
  return rc ? -1 : 0;
}

static int build(const scene_t *s, MPI_Comm comm, particle_set_t *out) {
  sim_t *sim = sim_create(s, comm);
  if (!sim || init_configuration(sim, s)) return -1;
  int rc = gather_particles(sim, 0, 0, out, NULL);
  sim_destroy(sim);
  return rc;
}

static double pdist2(const double *a, const double *b, const double L[3]) {
  double r2 = 0;
  for (int d = 0; d < 3; d++) {
    double x = a[d] - b[d];
    x -= L[d] * nearbyint(x / L[d]);
    r2 += x * x;
  }
  return r2;
}

static int check_scene(const char *path) {
  scene_t s;
  if (scene_load(path, &s)) return 1;
  image_walls_t g;
  if (image_walls_build(&s, MPI_COMM_WORLD, &g)) return 1;
  image_walls_free(&g);
  return 0;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  if (argc == 2) {
    const int rc = check_scene(argv[1]);
    MPI_Finalize();
    return rc;
  }
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const double t0 = MPI_Wtime();
  int ok = 1;
  if (rank == 0) {
    remove(PATCHES); /* built afresh (rank 0 writes it) */
    FILE *f = fopen(SCENE, "w");
    ok = f && fputs(scene_text, f) >= 0;
    if (f) fclose(f);
    ok = ok && make_image() == 0;
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!ok) return 1;
  scene_t s;
  if (scene_load(SCENE, &s)) return 1;
  image_walls_t g;
  CHECK(image_walls_build(&s, MPI_COMM_WORLD, &g) == 0);
  const double t_model = MPI_Wtime();
  particle_set_t all, one;
  CHECK(build(&s, MPI_COMM_WORLD, &all) == 0);
  CHECK(build(&s, MPI_COMM_SELF, &one) == 0);
  const double t_built = MPI_Wtime();
  if (rank == 0) {
    const image_walls_counts_t *c = &g.count;
    mdp_image_t img;
    char err[MDP_IMAGE_ERR_LEN];
    mdp_image_read_opts_t o;
    mdp_image_read_opts_init(&o);
    CHECK(mdp_image_read(IMG, &o, &img, err) == 0);
    wall_patches_t db;
    char perr[1024];
    CHECK(wall_patches_load_or_build(PATCHES, 0.5, 8, 7, MPI_COMM_SELF, &db, perr, sizeof perr) ==
          0);
    const double h = 0.5, L[3] = {NX * h, NY * h, NZ * h}, T = 1.75 / h; /* thickness, voxels */
    const long nvox = NX * NY * NZ;
    /* brute force: solid voxels within T of a pore voxel centre (periodic) */
    char *kept = calloc(nvox, 1);
    long kept_n = 0, deep_n = 0, expect_wall = 0;
    for (long v = 0; v < nvox; v++) {
      if (mdp_image_is_pore(&img, v)) continue;
      const double a[3] = {v % NX, v / NX % NY, v / (NX * NY)};
      double best = 1e30;
      for (long u = 0; u < nvox; u++) {
        if (!mdp_image_is_pore(&img, u)) continue;
        const double b[3] = {u % NX, u / NX % NY, u / (NX * NY)};
        const double Lv[3] = {NX, NY, NZ}, r2 = pdist2(a, b, Lv);
        if (r2 < best) best = r2;
      }
      if (best <= T * T) {
        kept[v] = 1, kept_n++;
        int p, or ;
        image_walls_patch_of(7, v, db.count, &p, & or);
        expect_wall += db.start[p + 1] - db.start[p];
      } else {
        deep_n++;
      }
    }
    /* the fluid voxels: the slit, (15, 2..3, 0) and the joined (0, 2, 0) */
    char *fluid_vox = calloc(nvox, 1);
    long nfv = 0;
    for (long v = 0; v < nvox; v++) {
      const int i = v % NX, j = v / NX % NY, k = v / (NX * NY);
      fluid_vox[v] = (j >= WALL && j < WALL + PORE) || (k == 0 && i == 15 && (j == 2 || j == 3)) ||
                     (k == 0 && i == 0 && j == 2);
      nfv += fluid_vox[v];
    }
    printf("image walls: %ld wall voxels kept (%ld deep), %d patches, %ld wall particles "
           "expected\n",
           kept_n, deep_n, db.count, expect_wall);
    CHECK(c->wall_voxels[0] + c->wall_voxels[1] == kept_n);
    CHECK(c->deep_voxels[0] + c->deep_voxels[1] == deep_n && deep_n > 0);
    CHECK(c->clusters == 5 && c->spanning == 1 && c->joined == 1 && c->isolated == 1 &&
          c->dead_end == 2);
    CHECK(c->spanning_voxels == NX * PORE * NZ + 2 && c->joined_voxels == 1 &&
          c->isolated_voxels == 1 && c->dead_end_voxels == 8);
    CHECK(c->fluid_voxels == nfv);
    const long target = lround(6.2 * nfv * h * h * h);
    CHECK(c->fluid_target == target);
    CHECK(c->fluid_particles == target - c->fluid_dropped);
    /* the particles */
    particle_set_sort_by_id(&all);
    particle_set_sort_by_id(&one);
    long nw = 0, nf = 0, bad_id = 0, in_solid = 0, wall_deep = 0, wall_moving = 0, wrong_sp = 0;
    for (long i = 0; i < all.n; i++) {
      bad_id += all.id[i] != i + 1;
      const double *x = all.x + 3 * i;
      int q[3];
      const int n3[3] = {NX, NY, NZ};
      for (int d = 0; d < 3; d++) q[d] = (((int)floor(x[d] / h)) % n3[d] + n3[d]) % n3[d];
      const long v = q[0] + NX * (q[1] + (long)NY * q[2]);
      const int sp = all.species[i];
      if (sp == 0) {
        nf++;
        in_solid += !fluid_vox[v];
      } else {
        nw++;
        wall_deep += !kept[v];
        wall_moving += all.v[3 * i] != 0 || all.v[3 * i + 1] != 0 || all.v[3 * i + 2] != 0;
        wrong_sp += sp != (mdp_image_phase(&img, v) == MDP_PHASE_ORGANIC ? 2 : 1);
      }
    }
    /* the smallest fluid-wall distance (periodic), brute force */
    double dmin2 = 1e30;
    for (long i = 0; i < all.n; i++) {
      if (all.species[i] != 0) continue;
      for (long j = 0; j < all.n; j++) {
        if (all.species[j] == 0) continue;
        const double r2 = pdist2(all.x + 3 * i, all.x + 3 * j, L);
        if (r2 < dmin2) dmin2 = r2;
      }
    }
    printf(
        "image walls: %ld particles: %ld wall (expected %ld), %ld fluid (target %ld, %ld "
        "dropped, %ld positions redrawn); nearest fluid-wall pair %.4f rc (min_wall_distance %g)\n",
        all.n, nw, expect_wall, nf, target, c->fluid_dropped, c->fluid_redrawn, sqrt(dmin2),
        s.geometry.min_wall_distance);
    CHECK(nw == expect_wall && nw == c->wall_particles[0] + c->wall_particles[1]);
    CHECK(nf == target - c->fluid_dropped);
    CHECK(bad_id == 0 && in_solid == 0 && wall_deep == 0 && wall_moving == 0 && wrong_sp == 0);
    CHECK(sqrt(dmin2) >= s.geometry.min_wall_distance * (1 - 1e-12));
    int identical = one.n == all.n;
    for (long i = 0; identical && i < all.n; i++)
      identical = all.id[i] == one.id[i] && all.species[i] == one.species[i] &&
                  !memcmp(all.x + 3 * i, one.x + 3 * i, 3 * sizeof(double)) &&
                  !memcmp(all.v + 3 * i, one.v + 3 * i, 3 * sizeof(double));
    CHECK(identical);
    free(kept), free(fluid_vox);
    wall_patches_free(&db);
    mdp_image_free(&img);
  }
  particle_set_free(&all);
  particle_set_free(&one);
  /* isolated_pores: fill: the isolated voxel and the dead-end pocket get fluid as well */
  {
    scene_t s2 = s;
    s2.geometry.isolated_pores = ISOLATED_FILL;
    image_walls_t g2;
    CHECK(image_walls_build(&s2, MPI_COMM_WORLD, &g2) == 0);
    CHECK(g2.count.fluid_voxels == g.count.fluid_voxels + 9);
    CHECK(g2.count.fluid_target == lround(6.2 * g2.count.fluid_voxels * 0.125));
    image_walls_free(&g2);
    /* a minimum distance larger than a voxel (two voxels scanned), read from the list directly */
    s2 = s;
    s2.geometry.min_wall_distance = 0.6;
    CHECK(image_walls_build(&s2, MPI_COMM_WORLD, &g2) == 0);
    const long n = image_walls_total(&g2);
    double *x = malloc(3 * (size_t)n * sizeof *x);
    int *sp = malloc((size_t)n * sizeof *sp);
    const double L[3] = {8, 7, 4};
    double dmin2 = 1e30;
    long nf = 0;
    for (long i = 0; i < n; i++) {
      int64_t id;
      image_walls_particle(&g2, i, &id, sp + i, x + 3 * i);
      nf += sp[i] == 0;
    }
    for (long i = 0; i < n; i++)
      for (long j = 0; j < n && sp[i] == 0; j++)
        if (sp[j] != 0 && pdist2(x + 3 * i, x + 3 * j, L) < dmin2)
          dmin2 = pdist2(x + 3 * i, x + 3 * j, L);
    if (rank == 0)
      printf("image walls: min_wall_distance 0.6: %ld fluid (target %ld, %ld dropped, %ld "
             "redrawn), nearest fluid-wall pair %.4f rc\n",
             nf, g2.count.fluid_target, g2.count.fluid_dropped, g2.count.fluid_redrawn,
             sqrt(dmin2));
    CHECK(nf == g2.count.fluid_target - g2.count.fluid_dropped && g2.count.fluid_dropped > 0);
    CHECK(sqrt(dmin2) >= 0.6 * (1 - 1e-12));
    free(x), free(sp);
    image_walls_free(&g2);
  }
  const long n_total = image_walls_total(&g);
  image_walls_free(&g);
  /* a short run with bounce_back and wall_boundary: no engine error, and no fluid particle inside a
   * solid voxel after any step */
  sim_t *sim = sim_create(&s, MPI_COMM_WORLD);
  CHECK(sim && init_configuration(sim, &s) == 0 && sim_setup(sim) == 0);
  penetration_map_t pmap;
  char perr[1024];
  CHECK(penetration_map_create(&pmap, &s, perr, sizeof perr) == 0 && pmap.on);
  int step_rc = 0;
  long worst = 0;
  for (long k = 0; k < s.steps && !step_rc; k++) {
    step_rc = sim_step(sim);
    penetration_t pen;
    penetration_count(&pmap, sim, &pen);
    if (pen.count > worst) worst = pen.count;
  }
  penetration_map_free(&pmap);
  CHECK(step_rc == 0);
  CHECK(worst == 0);
  thermo_t th;
  sim_thermo(sim, &th);
  CHECK(th.step == s.steps && th.n_total == n_total);
  if (rank == 0)
    printf("image walls: %ld steps (bounce_back + wall_boundary): penetrations at most %ld; T = "
           "%.3f, N = %ld, "
           "p = %.3f; model %.2f s, builds %.2f s, "
           "run %.2f s\n",
           th.step, worst, th.temperature, th.n_total,
           (th.pressure[0] + th.pressure[1] + th.pressure[2]) / 3, t_model - t0, t_built - t_model,
           MPI_Wtime() - t_built);
  sim_destroy(sim);
  MPI_Bcast(&failures, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Finalize();
  return failures ? 1 : 0;
}
