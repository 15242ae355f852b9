/* geometry.fluid_species_labels (docs/scene-format.md): a slit (6 pore layers between 3-voxel
 * walls, 20 x 12 x 6 voxels, rc_per_voxel 1: 6.2 particles per voxel) whose pore voxels carry
 * label 0 or, in a pattern of slabs and single voxels, label 3 (both pore), loaded through two
 * scenes: one with fluid_species_labels {3: oil}, one without (one liquid). Asserts:
 *  - the same particles (ids, positions, bitwise) in both builds: only species differ;
 *  - every fluid particle in a label-3 voxel is oil, every other one water;
 *  - the oil count within the fill's rounding of the label-3 voxels: each fluid voxel takes the
 *    floor of the mean or one more, less the particles dropped near walls;
 *  - the same species per id on 1 rank and on all ranks (the rank-local build).
 * Run on 2 ranks. */
#include "common/mpi_singleton.h"
#include "effects/scene_load.h"
#include "engine/sim.h"
#include "io/gather.h"
#include "mdpore_image.h"
#include "populate/image_walls.h"
#include "populate/init_config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_io_check.h"

#define IMG "species_labels_slit.h5"
#define SCENE_TWO "species_labels_two.yaml"
#define SCENE_ONE "species_labels_one.yaml"
#define PATCHES "species_labels_patches.h5"

enum { NX = 20, NY = 12, NZ = 6, WALL = 3, PORE = 6 };

static const char *scene_head =
    "box: {lo: [0, 0, 0], hi: [20, 12, 6]}\n"
    "species:\n"
    "  - {name: water}\n"
    "  - {name: oil}\n"
    "  - {name: quartz, frozen: true}\n"
    "pairs:\n"
    "  default: {A: -40, B: 25, gamma: 4.5, rc: 1, rd: 0.75}\n"
    "  water-oil: {A: -20}\n"
    "effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}}\n"
    "geometry:\n"
    "  image: " IMG "\n"
    "  rc_per_voxel: 1\n"
    "  flow_axis: x\n"
    "  species: {fluid: water, inorganic: quartz}\n"
    "  patches: {file: " PATCHES ", seed: 7}\n";
static const char *scene_tail = "initial: {temperature: 1.0}\n"
                                "run: {dt: 0.01, steps: 10, seed: 11}\n";

/* label 3: the slab 5 <= x < 12, and every 7th other pore voxel */
static int oil_voxel(int i, int j, int k) {
  return (i >= 5 && i < 12) || (i + NX * (j + NY * k)) % 7 == 0;
}

static int make_image(long *n3) {
  mdp_image_t img;
  char err[MDP_IMAGE_ERR_LEN];
  if (mdp_make_slit(&img, PORE, WALL, NX, NZ, err) ||
      mdp_image_parse_labels("pore=0,3;inorganic=1", img.phase_of, err)) {
    fprintf(stderr, "%s\n", err);
    return -1;
  }
  *n3 = 0;
  for (int k = 0; k < NZ; k++)
    for (int j = WALL; j < WALL + PORE; j++)
      for (int i = 0; i < NX; i++)
        if (oil_voxel(i, j, k)) img.label[mdp_image_index(&img, i, j, k)] = 3, (*n3)++;
  int rc = mdp_image_write_hdf5(&img, IMG, err);
  if (rc) fprintf(stderr, "%s\n", err);
  mdp_image_free(&img);
  return rc ? -1 : 0;
}

static int write_scene(const char *path, const char *extra) {
  FILE *f = fopen(path, "w");
  int ok = f && fputs(scene_head, f) >= 0 && fputs(extra, f) >= 0 && fputs(scene_tail, f) >= 0;
  if (f) ok = fclose(f) == 0 && ok;
  return ok ? 0 : -1;
}

static int build(const scene_t *s, MPI_Comm comm, particle_set_t *out) {
  sim_t *sim = sim_create(s, comm);
  if (!sim || init_configuration(sim, s)) return -1;
  int rc = gather_particles(sim, 0, 0, out, NULL);
  sim_destroy(sim);
  return rc;
}

static const particle_set_t *sort_set;
static int by_id(const void *a, const void *b) {
  const int64_t x = sort_set->id[*(const long *)a], y = sort_set->id[*(const long *)b];
  return (x > y) - (x < y);
}
/* Indices of the set in id order. */
static long *id_order(const particle_set_t *p) {
  long *o = malloc((size_t)(p->n ? p->n : 1) * sizeof *o);
  for (long i = 0; i < p->n; i++) o[i] = i;
  sort_set = p;
  qsort(o, (size_t)p->n, sizeof *o, by_id);
  return o;
}

int main(int argc, char **argv) {
  mpi_singleton_prepare();
  MPI_Init(&argc, &argv);
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const double t0 = MPI_Wtime();
  int ok = 1;
  long n3 = 0;
  if (rank == 0) remove(PATCHES); /* built afresh (rank 0 writes it) */
  if (rank == 0)
    ok = make_image(&n3) == 0 &&
         write_scene(SCENE_TWO, "  fluid_species_labels: {3: oil}\n") == 0 &&
         write_scene(SCENE_ONE, "") == 0;
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!ok) return 1;
  scene_t two, one;
  if (scene_load(SCENE_TWO, &two) || scene_load(SCENE_ONE, &one)) return 1;
  image_walls_t g;
  CHECK(image_walls_build(&two, MPI_COMM_WORLD, &g) == 0);
  particle_set_t p2, p1, p2self;
  CHECK(build(&two, MPI_COMM_WORLD, &p2) == 0);
  CHECK(build(&one, MPI_COMM_WORLD, &p1) == 0);
  CHECK(build(&two, MPI_COMM_SELF, &p2self) == 0);
  if (rank == 0) {
    const int water = 0, oil = 1, quartz = 2;
    CHECK(p2.n == p1.n && p2.n == p2self.n && p2.n > 0);
    long *o2 = id_order(&p2), *o1 = id_order(&p1), *os = id_order(&p2self);
    long n_oil = 0, n_water = 0, wrong = 0, moved = 0, differ = 0;
    const double h = 1;
    for (long r = 0; r < p2.n && p2.n == p1.n && p2.n == p2self.n; r++) {
      const long a = o2[r], b = o1[r], c = os[r];
      moved += p2.id[a] != p1.id[b] || memcmp(p2.x + 3 * a, p1.x + 3 * b, 3 * sizeof(double));
      differ += p2.species[a] != p2self.species[c] || p2.id[a] != p2self.id[c];
      if (p2.species[a] == quartz) {
        wrong += p1.species[b] != quartz;
        continue;
      }
      wrong += p1.species[b] != water; /* the one-liquid build: all water */
      int q[3];
      for (int d = 0; d < 3; d++) q[d] = (int)floor(p2.x[3 * a + d] / h);
      const int expect = oil_voxel(q[0], q[1], q[2]) ? oil : water;
      wrong += p2.species[a] != expect;
      n_oil += p2.species[a] == oil, n_water += p2.species[a] == water;
    }
    const image_walls_counts_t *ct = &g.count;
    const long base = g.fluid_base;
    printf(
        "species labels: %ld particles, fluid %ld: oil %ld water %ld; label-3 voxels %ld of %lld "
        "fluid voxels (%.4f), oil share %.4f; floor of the mean %ld per voxel, %ld dropped\n",
        p2.n, n_oil + n_water, n_oil, n_water, n3, ct->fluid_voxels,
        (double)n3 / (double)ct->fluid_voxels, (double)n_oil / (double)(n_oil + n_water), base,
        ct->fluid_dropped);
    CHECK(moved == 0);
    CHECK(differ == 0);
    CHECK(wrong == 0);
    CHECK(n_oil + n_water == ct->fluid_particles);
    CHECK(g.label_voxels[0] == n3);
    CHECK(g.label_particles[0] == n_oil); /* the report's count */
    /* each voxel holds base or base + 1 particles before the drops */
    CHECK(n_oil >= base * n3 - ct->fluid_dropped && n_oil <= (base + 1) * n3);
    CHECK(n_water >= base * (ct->fluid_voxels - n3) - ct->fluid_dropped &&
          n_water <= (base + 1) * (ct->fluid_voxels - n3));
    free(o2), free(o1), free(os);
    particle_set_free(&p2), particle_set_free(&p1), particle_set_free(&p2self);
    remove(IMG), remove(SCENE_TWO), remove(SCENE_ONE), remove(PATCHES);
  }
  image_walls_free(&g);
  MPI_Allreduce(MPI_IN_PLACE, &failures, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (rank == 0) printf("%s (%.2f s)\n", failures ? "FAILED" : "ok", MPI_Wtime() - t0);
  MPI_Finalize();
  return failures ? 1 : 0;
}
