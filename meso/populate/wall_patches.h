/* The database of pre-equilibrated wall patches (physics.md section 3; paper 2.3): cubes of a
 * frozen mDPD liquid at the wall density, one voxel edge wide, that the image wall builder copies
 * into the solid voxels near the pore space (a random patch in a random one of the 24 cube
 * orientations per voxel: no lattice, so no layering and no anisotropic slip). mdpore makes the
 * database itself (`mdpore build patches`): an mDPD run of a periodic box at the wall density,
 * equilibrated, then cut into cubes; stored as HDF5 and cached, deterministic for a seed
 * (docs/walls.md says how it is made). */
#ifndef MESO_BUILD_WALL_PATCHES_H
#define MESO_BUILD_WALL_PATCHES_H

#include <mpi.h>
#include <stddef.h>
#include <stdint.h>

typedef struct {
  double edge;    /* patch edge = voxel edge, in rc */
  double density; /* particles per rc^3 of the run the patches were cut from */
  uint64_t seed;  /* seed of that run */
  int count;      /* patches */
  long *start;    /* [count + 1]: patch p holds particles start[p] .. start[p + 1] - 1 */
  double *x;      /* [3 * start[count]]: positions in [0, edge)^3 relative to the patch's corner */
} wall_patches_t;

/* The database for (edge, density, seed): read from `path`, or, when path is "" or the file does
 * not exist, built (collective over comm; rank 0 writes it atomically to `path`, or to the cache
 * file wall_patches_cache_path names when path is "") and read back. A file whose edge, density
 * or seed differ from the request is refused with a message naming the file and both values.
 * 0, or -1 with the reason in err. */
int wall_patches_load_or_build(const char *path, double edge, double density, uint64_t seed,
                               MPI_Comm comm, wall_patches_t *out, char *err, size_t errlen);
void wall_patches_free(wall_patches_t *p);

/* How a database was made (attributes of its file, besides edge, density and seed). */
typedef struct {
  long steps;              /* equilibration steps of each run (dt = 0.01)                    */
  int runs;                /* independent runs (periodic boxes) the patches were cut from    */
  int cubes;               /* m: cubes per box edge, box side m * edge                      */
  double temperature;      /* kT at the last step of the last run                            */
  double temperature_mean; /* mean kT over the second half of every run's steps             */
} wall_patches_run_t;

/* Equilibration steps of a database run (wall_patches.c says how this number was chosen). */
#define WALL_PATCHES_STEPS 2000L
/* The file layout's version (attribute format_version). */
#define WALL_PATCHES_FORMAT 1
/* Accepted requests: edge in [WALL_PATCHES_EDGE_MIN, WALL_PATCHES_EDGE_MAX] rc, density in
 * (0, WALL_PATCHES_DENSITY_MAX] per rc^3. */
#define WALL_PATCHES_EDGE_MIN 0.05
#define WALL_PATCHES_EDGE_MAX 10.0
#define WALL_PATCHES_DENSITY_MAX 30.0

/* wall_patches_load_or_build with the number of equilibration steps of a build given (the public
 * one uses WALL_PATCHES_STEPS; the tests use fewer), and how the database was made in `run` (may
 * be NULL). A file that exists is read whatever its steps were. */
int wall_patches_load_or_build_steps(const char *path, double edge, double density, uint64_t seed,
                                     long steps, MPI_Comm comm, wall_patches_t *out,
                                     wall_patches_run_t *run, char *err, size_t errlen);

/* Build the database in memory on this process alone (MPI_COMM_SELF runs, CPU backend): the
 * equilibration runs and the cutting. Deterministic for (edge, density, seed, steps). 0, or -1 with
 * the reason in err. (wall_patches_run.c) */
int wall_patches_build(double edge, double density, uint64_t seed, long steps, wall_patches_t *out,
                       wall_patches_run_t *run, char *err, size_t errlen);

/* Write a database atomically (temporary file + rename); the same database gives the same bytes.
 * Read one back, checking every attribute and dataset, and that its edge, density and seed equal
 * the request (run may be NULL). 0, or -1 with the reason, naming the file and the key, in err. */
int wall_patches_write(const char *path, const wall_patches_t *p, const wall_patches_run_t *run,
                       char *err, size_t errlen);
int wall_patches_read(const char *path, double edge, double density, uint64_t seed,
                      wall_patches_t *out, wall_patches_run_t *run, char *err, size_t errlen);

/* The default cache file of a database: $MDPORE_CACHE_DIR, else $XDG_CACHE_HOME/mdpore, else
 * ~/.cache/mdpore, then "wall-patches-e<edge>-d<density>-s<seed>.h5". */
void wall_patches_cache_path(double edge, double density, uint64_t seed, char *out, size_t len);

/* Orientation o (0..23, the rotations of a cube) applied to a point of [0, edge)^3: the result is
 * in [0, edge)^3 again. o = 0 is the identity. */
void wall_patch_orient(int o, double edge, const double in[3], double out[3]);

#endif
