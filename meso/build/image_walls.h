/* Particles from a scene's `geometry:` image (init kind INIT_GEOMETRY; docs/walls.md): frozen wall
 * particles in the solid voxels within the wall thickness of the pore space, copied from the patch
 * database (wall_patches.h) with a patch and one of 24 orientations per voxel, and fluid particles
 * in the pore voxels of the clusters that carry flow along geometry.flow_axis.
 *
 * Everything is a pure function of the image, the scene and its seeds: every rank builds the same
 * global list (walls first in voxel order, then fluid in voxel order; ids 1, 2, ...) and offers it
 * to the engine, which keeps the particles of its subdomain. So the configuration does not depend on
 * the number of ranks.
 *
 * Limit: every rank reads the whole image and holds it (about 10 bytes per voxel while building,
 * then 1 byte per voxel plus 16 per wall or fluid voxel), and generates the whole global list
 * (three times: the fluid count, then offer_source's two passes) although it keeps only its own
 * subdomain's particles. Measured (one core): a 256^3 image at rc_per_voxel 0.5, 15.6 M particles:
 * 7.2 s to build, 3.1 s per pass over the list, 361 MB. Reading only a rank's part of the image
 * (plus the wall thickness) is a later step. */
#ifndef MESO_BUILD_IMAGE_WALLS_H
#define MESO_BUILD_IMAGE_WALLS_H

#include "build/wall_patches.h"
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
  uint8_t *cls;        /* per voxel (x fastest): enum image_voxel_class                   */
  wall_patches_t db;   /* the patch database                                              */
  long n_wall_vox;     /* wall voxels, in voxel order: index and first particle           */
  int64_t *wall_vox;
  long *wall_start; /* [n_wall_vox + 1] */
  long n_fluid_vox; /* fluid voxels, in voxel order: index and first particle          */
  int64_t *fluid_vox;
  long *fluid_start;    /* [n_fluid_vox + 1], global index minus the wall particles        */
  long n_wall, n_fluid; /* particles                                                       */
  image_walls_counts_t count;
  image_walls_cache_t *cache; /* the last fluid voxel generated (sequential access)       */
} image_walls_t;

/* Read and check the scene's image, classify its voxels, load or build the patch database, count
 * the particles of every voxel. Collective over comm (the patch database may be built); every rank
 * gets the same result. 0, or -1 after a message on stderr (rank 0) naming the scene file, the key
 * and what was expected. */
int image_walls_build(const scene_t *scene, MPI_Comm comm, image_walls_t *g);
void image_walls_free(image_walls_t *g);

/* Total particles, and particle i (0 <= i < total) of the global list: id i + 1, its species and
 * position. Fastest when called with i increasing (fluid voxels are generated one at a time). */
long image_walls_total(const image_walls_t *g);
void image_walls_particle(const image_walls_t *g, long i, int64_t *id, int *species, double x[3]);

/* The report block (image, phases, walls kept and dropped, particles per species, pore clusters and
 * what was done with them, fluid dropped by the minimum distance, realised densities). */
void image_walls_report(const image_walls_t *g, FILE *out);

/* The patch and orientation (0..23) of voxel `voxel` (linear index in box axes, x fastest): a
 * Philox hash of (patch_seed, voxel), independent of the decomposition. */
void image_walls_patch_of(uint64_t patch_seed, int64_t voxel, int patches, int *patch, int *orient);

/* Between image_walls.c and image_fluid.c. */
/* Fluid counts per voxel (base + the IMAGE_VOXEL_EXTRA bit, total = round(density x volume)),
 * then every fluid voxel's particles generated once to know how many keep min_wall_distance from
 * the walls: fills fluid_vox, fluid_start, n_fluid, the fluid counts and the cache. 0 or -1 +
 * message naming the scene file. */
int image_fluid_count(image_walls_t *g, char *err, size_t errlen);
/* Fluid particle i (0 <= i < n_fluid) of the global fluid list (cached per voxel). */
void image_fluid_particle(const image_walls_t *g, long i, double x[3]);
/* The last k < n with start[k] <= i (start non-decreasing, start[0] = 0 <= i < start[n]). */
long image_walls_find(const long *start, long n, long i);
/* The kept fluid particles of voxel v (positions into x[3 * k], at most fluid_base + 1): returns
 * how many; *dropped receives those that found no place, *redrawn (may be NULL) the positions
 * drawn again because they were too near a wall particle. */
int image_fluid_voxel(const image_walls_t *g, int64_t v, double *x, long *dropped, long *redrawn);
/* Number of wall particles of voxel v (0 unless a wall voxel), and its particle j. */
long image_walls_voxel_count(const image_walls_t *g, int64_t v);
void image_walls_voxel_particle(const image_walls_t *g, int64_t v, long j, double x[3]);

#endif
