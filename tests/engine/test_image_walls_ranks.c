/* The rank-local geometry build (meso/populate/image_walls.h, docs/walls.md section 6) on 1, 2, 3 and
 * 4 ranks (sub-communicators of a 4-rank run): the same particles, bitwise (ids, species,
 * positions, velocities), the same counts (clusters and their categories, walls, fluid), and each
 * rank reading only its share plus the halo. The image (48 x 15 x 8 voxels, rc_per_voxel 0.5,
 * periodic box) is a slit along x with pores that cross the ranks' cuts:
 *  - a tube along x at (y 1, z 5) from the x = 0 face to x = 29, joined to the slit only through
 *    the periodic x face (its partner at x = 47 is connected to the slit): "joined", crossing cuts;
 *  - an isolated pore along x (x 20..27, y 12, z 4) across the x cut of 2 ranks;
 *  - a dead-end sheet at y = 14 (x 10..37, z 6), facing solid across the periodic y face;
 *  - a dead-end pocket across the periodic y face (y 0 and y 14, x 4..5, z 2..3: two clusters).
 * The voxel counts are asserted against the image by brute force (the same numbers on 1 rank).
 * Run on 4 ranks. */
#include "common/mpi_singleton.h"
#include "populate/image_walls.h"
#include "populate/init_config.h"
#include "effects/scene_load.h"
#include "engine/sim.h"
#include "io/gather.h"
#include "mdpore_image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_io_check.h"

#define IMG "image_walls_ranks.h5"
#define SCENE "image_walls_ranks.yaml"
#define PATCHES "image_walls_ranks_patches.h5"

enum { NX = 48, NY = 15, NZ = 8 };

static const char *scene_text =
    "box: {lo: [0, 0, 0], hi: [24, 7.5, 4]}\n"
    "species:\n"
    "  - {name: liquid}\n"
    "  - {name: quartz, frozen: true}\n"
    "  - {name: kerogen, frozen: true}\n"
    "pairs:\n"
    "  default: {A: -40, B: 25, gamma: 4.5, rc: 1, rd: 0.75}\n"
    "effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}}\n"
    "geometry:\n"
    "  image: " IMG "\n"
    "  labels: pore=0,inorganic=1,organic=2\n"
    "  rc_per_voxel: 0.5\n"
    "  flow_axis: x\n"
    "  species: {fluid: liquid, inorganic: quartz, organic: kerogen}\n"
    "  patches: {file: " PATCHES ", seed: 3}\n"
    "initial: {temperature: 1.0}\n"
    "run: {dt: 0.01, steps: 10, seed: 5}\n";

static void set(mdp_image_t *img, int i, int j, int k, int label) {
  img->label[mdp_image_index(img, i, j, k)] = (uint8_t)label;
}

static int make_image(void) {
  mdp_image_t img;
  char err[MDP_IMAGE_ERR_LEN];
  if (mdp_image_alloc(&img, NX, NY, NZ, err) ||
      mdp_image_parse_labels("pore=0,inorganic=1,organic=2", img.phase_of, err)) {
    fprintf(stderr, "%s\n", err);
    return -1;
  }
  for (int k = 0; k < NZ; k++)
    for (int j = 0; j < NY; j++)
      for (int i = 0; i < NX; i++) set(&img, i, j, k, j < 4 ? 1 : j < 10 ? 0 : 2);
  for (int i = 0; i < 30; i++) set(&img, i, 1, 5, 0);       /* joined tube */
  for (int j = 1; j < 4; j++) set(&img, NX - 1, j, 5, 0);   /* its partner, open to the slit */
  for (int i = 20; i < 28; i++) set(&img, i, 12, 4, 0);     /* isolated */
  for (int i = 10; i < 38; i++) set(&img, i, NY - 1, 6, 0); /* dead-end sheet */
  for (int k = 2; k < 4; k++)
    for (int i = 4; i < 6; i++) set(&img, i, 0, k, 0), set(&img, i, NY - 1, k, 0); /* pocket */
  int rc = mdp_image_write_hdf5(&img, IMG, err);
  if (rc) fprintf(stderr, "%s\n", err);
  mdp_image_free(&img);
  return rc ? -1 : 0;
}

/* FNV-1a over bytes */
static uint64_t fnv(uint64_t h, const void *p, size_t n) {
  const unsigned char *b = p;
  for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * 1099511628211ull;
  return h;
}

typedef struct {
  long n;
  uint64_t hash;
  image_walls_counts_t count;
  long long read_max, own_bound_ok;
} result_t;

/* Build on comm: the particles (gathered, sorted, hashed) and the builder's counts; every rank's
 * voxels read against its share plus the halo. */
/* Rank 0: the results on 1..4 ranks agree; the image's counts by brute force (var 0). */
static void check_results(const result_t *res, int size, int var, const char *what) {
  const image_walls_counts_t *c = &res[1].count;
  /* the image by brute force: the pore voxels of each kind */
  const long long tube = 30, partner = 3, iso = 8, sheet = 28, pocket = 8;
  const long long slit = (long long)NX * 6 * NZ;
  CHECK(c->pore == slit + tube + partner + iso + sheet + pocket);
  CHECK(c->clusters == 6 && c->spanning == 1 && c->joined == 1 && c->isolated == 1 &&
        c->dead_end == 3);
  CHECK(c->spanning_voxels == slit + partner && c->joined_voxels == tube &&
        c->isolated_voxels == iso && c->dead_end_voxels == sheet + pocket);
  if (var == 0) CHECK(c->fluid_voxels == slit + partner + tube);
  if (var == 1) CHECK(c->fluid_voxels == c->pore && c->fluid_dropped > 0);
  if (var == 2) CHECK(c->region_partial > 0 && c->region_outside > 0);
  for (int np = 1; np <= size && np <= 4; np++) {
    const result_t *r = &res[np];
    printf("image walls ranks: %s: %d rank%s: %ld particles, hash %016llx, clusters %d (spanning "
           "%d, joined %d, isolated %d, dead-end %d), fluid %ld (%ld dropped), walls %ld; voxels "
           "read at most %lld of %d (within share + halo: %s)\n",
           what, np, np > 1 ? "s" : "", r->n, (unsigned long long)r->hash, r->count.clusters,
           r->count.spanning, r->count.joined, r->count.isolated, r->count.dead_end,
           r->count.fluid_particles, r->count.fluid_dropped,
           r->count.wall_particles[0] + r->count.wall_particles[1], r->read_max, NX * NY * NZ,
           r->own_bound_ok ? "yes" : "no");
    CHECK(r->n == res[1].n && r->n > 0 && r->hash == res[1].hash);
    CHECK(r->count.clusters == c->clusters && r->count.spanning == c->spanning &&
          r->count.joined == c->joined && r->count.isolated == c->isolated &&
          r->count.dead_end == c->dead_end && r->count.joined_voxels == c->joined_voxels &&
          r->count.dead_end_voxels == c->dead_end_voxels &&
          r->count.fluid_voxels == c->fluid_voxels &&
          r->count.fluid_particles == c->fluid_particles &&
          r->count.fluid_target == c->fluid_target && r->count.fluid_dropped == c->fluid_dropped &&
          r->count.fluid_redrawn == c->fluid_redrawn &&
          r->count.region_partial == c->region_partial &&
          r->count.wall_voxels[0] == c->wall_voxels[0] &&
          r->count.wall_voxels[1] == c->wall_voxels[1] &&
          r->count.wall_particles[0] == c->wall_particles[0] &&
          r->count.wall_particles[1] == c->wall_particles[1]);
    CHECK(r->own_bound_ok);
    if (np > 1) CHECK(r->read_max < (long long)NX * NY * NZ);
  }
}

static int run(const scene_t *s, MPI_Comm comm, result_t *out) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  memset(out, 0, sizeof *out);
  sim_t *sim = sim_create(s, comm);
  if (!sim || init_configuration(sim, s)) return -1;
  double lo[3], hi[3];
  sim_subdomain(sim, lo, hi);
  image_walls_t g;
  if (image_walls_build_local(s, comm, lo, hi, &g)) return -1;
  /* the window: own voxels, 2 more each side (gen), the halo: the min_wall_distance scan and the
   * wall thickness 1.75 rc, in voxels of 0.5 rc */
  const int halo = (int)ceil(s->geometry.min_wall_distance / 0.5) + (int)ceil(1.75 / 0.5);
  long long bound = 1;
  for (int d = 0; d < 3; d++) {
    const int n[3] = {NX, NY, NZ}, w = g.own_n[d] + 2 * (2 + halo);
    bound *= w < n[d] ? w : n[d];
  }
  long long ok = g.voxels_read <= bound, rmax = g.voxels_read;
  MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_LONG_LONG, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, &rmax, 1, MPI_LONG_LONG, MPI_MAX, comm);
  out->own_bound_ok = ok, out->read_max = rmax;
  out->count = g.count;
  image_walls_free(&g);
  particle_set_t ps;
  int rc = gather_particles(sim, 0, 0, &ps, NULL);
  sim_destroy(sim);
  if (rc) return -1;
  if (rank == 0) {
    particle_set_sort_by_id(&ps);
    uint64_t h = 1469598103934665603ull;
    for (long i = 0; i < ps.n; i++) {
      h = fnv(h, &ps.id[i], sizeof ps.id[i]);
      h = fnv(h, &ps.species[i], sizeof ps.species[i]);
      h = fnv(h, ps.x + 3 * i, 3 * sizeof(double));
      h = fnv(h, ps.v + 3 * i, 3 * sizeof(double));
    }
    out->n = ps.n, out->hash = h;
  }
  particle_set_free(&ps);
  return 0;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  int rank, size;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int ok = 1;
  if (rank == 0) {
    remove(PATCHES);
    FILE *f = fopen(SCENE, "w");
    ok = f && fputs(scene_text, f) >= 0;
    if (f) fclose(f);
    ok = ok && make_image() == 0;
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!ok) return 1;
  scene_t s;
  if (scene_load(SCENE, &s)) return 1;
  /* the scene, then isolated_pores: fill with a min_wall_distance over a voxel (a wider halo,
   * particles dropped), then a fluid_region across the ranks' cuts (partial voxels) */
  const char *variant[3] = {"scene", "isolated_pores fill, min_wall_distance 0.6",
                            "fluid_region [3.3, 2.1, 0.7]..[17.7, 4.9, 3.3]"};
  for (int var = 0; var < 3; var++) {
    scene_t sv = s;
    if (var == 1) sv.geometry.isolated_pores = ISOLATED_FILL, sv.geometry.min_wall_distance = 0.6;
    if (var == 2) {
      const double lo[3] = {3.3, 2.1, 0.7}, hi[3] = {17.7, 4.9, 3.3};
      sv.geometry.fluid_region = 1;
      memcpy(sv.geometry.fluid_lo, lo, sizeof lo), memcpy(sv.geometry.fluid_hi, hi, sizeof hi);
    }
    result_t res[5];
    for (int np = 1; np <= size && np <= 4; np++) {
      MPI_Comm comm;
      MPI_Comm_split(MPI_COMM_WORLD, rank < np ? 0 : MPI_UNDEFINED, rank, &comm);
      if (comm != MPI_COMM_NULL) {
        if (rank == 0) printf("--- %s: %d rank%s\n", variant[var], np, np > 1 ? "s" : "");
        CHECK(run(&sv, comm, &res[np]) == 0);
        MPI_Comm_free(&comm);
      }
      MPI_Barrier(MPI_COMM_WORLD);
    }
    if (rank == 0) check_results(res, size, var, variant[var]);
  }
  MPI_Bcast(&failures, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Finalize();
  return failures ? 1 : 0;
}
