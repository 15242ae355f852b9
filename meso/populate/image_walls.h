/* Particles from a scene's `geometry:` image (init kind INIT_GEOMETRY; docs/walls.md): frozen wall
 * particles in the solid voxels within the wall thickness of the pore space, copied from the patch
 * database (wall_patches.h) with a patch and one of 24 orientations per voxel, and fluid particles
 * in the pore voxels of the clusters that carry flow along geometry.flow_axis.
 *
 * Everything is a pure function of the image, the scene and its seeds. The global list is walls
 * first in voxel order, then fluid in voxel order, ids 1, 2, ... Each rank builds only its part of
 * it (image_walls_build_local): it reads the voxels that overlap its subdomain, one more each side,
 * plus a halo of ceil(min_wall_distance / voxel) + ceil(thickness / voxel) voxels (image_window.c;
 * partial reads of the file), classifies them, and generates the particles of the voxels that
 * overlap its subdomain (and the one more each side), with the ids the whole list
 * would give them (image_ids.c: per-line particle counts summed over the ranks). What needs the
 * whole image is reduced without any rank holding it: phase and particle counts by MPI_Allreduce,
 * the pore clusters by labelling each rank's voxels and merging the labels that meet across rank
 * faces and periodic faces on rank 0 (image_clusters_mpi.c), the voxels that take one extra fluid
 * particle by a distributed selection of the smallest Philox keys (image_fluid.c). So the
 * configuration does not depend on the number of ranks and is bitwise that of the whole-list build
 * this replaced (test build_image_walls_ranks_np4: 1, 2, 3 and 4 ranks). image_walls_build keeps
 * the whole image and list on every rank (tests, scene checks).
 *
 * Limits: the halo is read by every rank that needs it (a rank reads its share plus thickness /
 * voxel + 3 or so voxels on each side of each cut); the id offsets use a table of 16 bytes per
 * image line (x row) and x segment of the decomposition on every rank; the centre-of-mass velocity
 * that is removed is summed over all fluid ids on every rank (O(fluid) time, no memory); bounce_back
 * and the penetration count still hold the whole solid map on every rank (1 byte per voxel). */
#ifndef MESO_BUILD_IMAGE_WALLS_H
#define MESO_BUILD_IMAGE_WALLS_H

#include "populate/wall_patches.h"
#include "scene/scene.h"

#include <mpi.h>
#include <stdint.h>
#include <stdio.h>

/* What a voxel becomes (image_walls_t.cls; IMAGE_VOXEL_EXTRA is or-ed onto fluid voxels that take
 * one particle more than the floor of the mean, see image_fluid.c). */
enum image_voxel_class {
  IMAGE_VOXEL_DEEP = 0,      /* solid deeper than the wall thickness: no particles          */
  IMAGE_VOXEL_ORGANIC = 1,   /* wall voxel of organic solid: geometry.organic_species       */
  IMAGE_VOXEL_INORGANIC = 2, /* wall voxel of inorganic solid: geometry.inorganic_species   */
  IMAGE_VOXEL_FLUID = 3,     /* pore voxel that gets fluid                                  */
  IMAGE_VOXEL_EMPTY = 4,     /* pore voxel left empty (isolated_pores: empty)               */
  IMAGE_VOXEL_CLASS = 0x7f,  /* mask of the class                                           */
  IMAGE_VOXEL_EXTRA = 0x80
};

/* Tries per fluid particle: a uniform position in a pore voxel is refused only where it lies within
 * min_wall_distance of a wall particle, a thin skin at the pore surface (test_image_walls prints
 * the share of positions redrawn), so 100 tries fail only for a voxel almost wholly inside it. */
#define IMAGE_FLUID_TRIES 100

/* Counts for the report (image_walls_report) and the tests. */
typedef struct {
  long long voxels, pore, organic, inorganic; /* image voxels per phase                  */
  long long wall_voxels[2], deep_voxels[2];   /* [0] organic, [1] inorganic solid        */
  int clusters;                               /* 6-connected pore clusters of the image  */
  int spanning;                               /* clusters touching both flow-axis faces  */
  int joined;             /* others joined to a spanning one through a periodic face   */
  int isolated, dead_end; /* the rest: touching no face / some face                    */
  long long spanning_voxels, joined_voxels, isolated_voxels, dead_end_voxels;
  long long fluid_voxels; /* pore voxels that get fluid                                */
  long wall_particles[2]; /* [0] organic, [1] inorganic                                */
  long fluid_target;      /* round(fluid_density x fluid_voxels x voxel volume)        */
  long fluid_dropped;     /* particles that found no place min_wall_distance from walls */
  long fluid_redrawn;     /* positions drawn again (too near a wall particle)           */
  long fluid_particles;   /* fluid_target - fluid_dropped                              */
  /* the filled pore volume (rc^3): with geometry.fluid_region, its part inside the region; the
   * region's filled pore voxels wholly outside it (left empty) and partly inside it */
  double fluid_volume;
  long long region_outside, region_partial;
} image_walls_counts_t;

typedef struct image_walls_cache image_walls_cache_t;

typedef struct {
  const scene_t *scene;
  int n[3];            /* voxels along the box axes (after geometry.axis_map)             */
  double h;            /* voxel edge (rc) = patch edge                                    */
  double lo[3];        /* box corner = corner of voxel (0, 0, 0)                          */
  int periodic[3];     /* the box's                                                       */
  double thickness;    /* wall thickness used (rc)                                        */
  double min_distance; /* geometry.min_wall_distance (rc)                                 */
  int fluid_base;      /* floor of the mean number of fluid particles per voxel           */
  /* The rank's voxels, per box axis a range start + [0, len) (taken modulo n along a periodic
   * axis; len <= n): own = the voxels whose centre lies in the subdomain (the ranks' own ranges
   * partition the image), gen = the voxels that overlap the subdomain, one more on each side (their
   * particles are offered), win = gen plus the halo (what was read). */
  int own_lo[3], own_n[3], gen_lo[3], gen_n[3], win_lo[3], win_n[3];
  int whole;     /* every rank built the whole image (image_walls_build)            */
  MPI_Comm work; /* the communicator of the reductions (MPI_COMM_SELF when whole)   */
  uint8_t *cls;  /* per window voxel (x fastest): enum image_voxel_class            */
  /* per window voxel: 0, or k + 1 when its image label is geometry.fluid_species_labels entry k
   * (NULL without that key); label_voxels[k]: the image's voxels of that label, label_particles[k]
   * the fluid particles built in them (before fluid_species_regions) */
  uint8_t *label_sp;
  long long label_voxels[SCENE_MAX_FILLS], label_particles[SCENE_MAX_FILLS];
  wall_patches_t db; /* the patch database                                              */
  /* the local list: the gen voxels with particles, walls then fluid, each in voxel order: global
   * voxel index, first particle in the local list ([n + 1]) and its global id */
  long n_wall_vox;
  int64_t *wall_vox, *wall_id;
  long *wall_start;
  long n_fluid_vox;
  int64_t *fluid_vox, *fluid_id;
  long *fluid_start;
  long n_wall, n_fluid; /* particles of the whole list                                     */
  image_walls_counts_t count;
  image_walls_cache_t *cache; /* the last fluid voxel generated (sequential access)       */
  /* memory: voxels this rank read, bytes of the build's arrays now and at their peak; rank 0
   * holds every rank's pair for the report ([ranks], NULL elsewhere) */
  long long voxels_read, mem_now, mem_peak;
  int ranks;
  long long *rank_read, *rank_peak;
} image_walls_t;

/* Read and check the scene's image, classify its voxels, load or build the patch database, count
 * the particles. image_walls_build: every rank builds the whole image and the whole list (tests,
 * scene checks). image_walls_build_local: the rank's part for the subdomain [sub_lo, sub_hi)
 * (sim_subdomain). Collective over comm. 0, or -1 after a message on stderr (by the lowest failing
 * rank) naming the scene file, the key and what was expected. */
int image_walls_build(const scene_t *scene, MPI_Comm comm, image_walls_t *g);
int image_walls_build_local(const scene_t *scene, MPI_Comm comm, const double sub_lo[3],
                            const double sub_hi[3], image_walls_t *g);
void image_walls_free(image_walls_t *g);

/* What image_walls_build_local will hold at its peak on this rank, before it allocates anything:
 * the image's size (its header), the rank's window and gen voxels, and the build's bytes
 * (engine/memory_plan.h: memory_geometry_build_bytes). Collective over comm (the x segments of the
 * decomposition). 0, or -1 when the image or the scene's sizes are refused (*bytes = 0; the build
 * then says why). */
typedef struct {
  int n[3];              /* the image's voxels along the box axes (after axis_map)          */
  long long window, gen; /* this rank's window and gen voxels                                */
  double bytes;          /* the build's peak                                                  */
} image_walls_plan_t;
int image_walls_plan(const scene_t *scene, MPI_Comm comm, const double sub_lo[3],
                     const double sub_hi[3], image_walls_plan_t *p);

/* Total particles of the whole list; particles of the local list (the whole list after
 * image_walls_build); particle i (0 <= i < local) of the local list: its id, species, position.
 * Fastest when called with i increasing (fluid voxels are generated one at a time). */
long image_walls_total(const image_walls_t *g);
long image_walls_local(const image_walls_t *g);
void image_walls_particle(const image_walls_t *g, long i, int64_t *id, int *species, double x[3]);

/* The report block (image, phases, walls kept and dropped, particles per species, pore clusters and
 * what was done with them, fluid dropped by the minimum distance, realised densities). */
void image_walls_report(const image_walls_t *g, FILE *out);

/* The patch and orientation (0..23) of voxel `voxel` (linear index in box axes, x fastest): a
 * Philox hash of (patch_seed, voxel), independent of the decomposition. */
void image_walls_patch_of(uint64_t patch_seed, int64_t voxel, int patches, int *patch, int *orient);

/* Between image_walls.c, image_window.c, image_clusters_mpi.c, image_fluid.c and image_ids.c. */
/* Window index of voxel q (box axes; any integer along a periodic axis), -1 when outside the image
 * or the window. */
long long image_walls_win(const image_walls_t *g, const int q[3]);
/* Global voxel coordinates of local coordinates c of a range [start, start + len) (wrapped). */
static inline void image_walls_global(const image_walls_t *g, const int start[3], const int c[3],
                                      int q[3]) {
  for (int d = 0; d < 3; d++) q[d] = (start[d] + c[d]) % g->n[d];
}
static inline int64_t image_walls_voxel(const image_walls_t *g, const int q[3]) {
  return (int64_t)q[0] + (int64_t)g->n[0] * ((int64_t)q[1] + (int64_t)g->n[1] * q[2]);
}
/* 1 when global coordinates q lie in the range [start, start + len) (wrapped) of every axis. */
int image_walls_in_range(const image_walls_t *g, const int start[3], const int len[3],
                         const int q[3]);
/* Memory bookkeeping of the build's arrays (signed bytes). */
void image_walls_mem(image_walls_t *g, long long bytes);

/* The window's ranges alone (image_window.c): the image's size (its header) and the rank's ranges
 * as image_window_read sets them, nothing allocated. 0 or -1 + err. */
int image_window_ranges(const scene_t *s, image_walls_t *g, const double sub_lo[3],
                        const double sub_hi[3], int halo, char *err, size_t errlen);
/* The window (image_window.c): the image's size, the rank's ranges for the subdomain (whole: the
 * whole image) with `halo` voxels around gen, and the phases (mdp_phase_t) of the window voxels,
 * read with partial reads and geometry.axis_map. Local (no communication). 0 or -1 + err. */
int image_window_read(const scene_t *s, image_walls_t *g, const double sub_lo[3],
                      const double sub_hi[3], int halo, uint8_t **phase, char *err, size_t errlen);

/* The pore clusters (image_clusters_mpi.c): labels the rank's gen voxels, merges across ranks on
 * rank 0, sets FLUID / EMPTY on the pore voxels of gen and fills the cluster counts (identical on
 * every rank). Collective over g->work. 0, or -1 with the same message on every rank (the flow axis
 * does not percolate, or memory). */
int image_clusters_classify(const scene_t *s, image_walls_t *g, const uint8_t *phase, char *err,
                            size_t errlen);

/* Fluid counts per voxel of gen (base + the IMAGE_VOXEL_EXTRA bit, total = round(density x
 * volume)): *kept = the kept particles of every gen voxel (allocated here, gen order, x fastest)
 * and the global fluid counts. Collective over
 * g->work. 0 or -1 + message naming the scene file (same on every rank). */
int image_fluid_count(image_walls_t *g, uint16_t **kept, char *err, size_t errlen);
/* The kept fluid particles of voxel v (positions into x[3 * k], at most fluid_base + 1): returns
 * how many; *dropped receives those that found no place, *redrawn (may be NULL) the positions
 * drawn again because they were too near a wall particle. */
int image_fluid_voxel(const image_walls_t *g, int64_t v, double *x, long *dropped, long *redrawn);
/* Fluid particle i of the local fluid list (0 <= i < fluid_start[n_fluid_vox]; cached per voxel). */
void image_fluid_particle(const image_walls_t *g, long i, double x[3]);
/* The last k < n with start[k] <= i (start non-decreasing, start[0] = 0 <= i < start[n]). */
long image_walls_find(const long *start, long n, long i);
/* Number of wall particles of voxel v (0 unless a wall voxel of the window), and its particle j. */
long image_walls_voxel_count(const image_walls_t *g, int64_t v);
void image_walls_voxel_particle(const image_walls_t *g, int64_t v, long j, double x[3]);

/* The local list and its ids (image_ids.c): the wall and fluid particle counts of every gen voxel,
 * summed per image line and rank segment over the ranks, give every gen voxel its first id.
 * Collective over g->work. 0 or -1 + message (same on every rank). */
int image_ids_assign(image_walls_t *g, const uint16_t *kept, char *err, size_t errlen);

#endif
