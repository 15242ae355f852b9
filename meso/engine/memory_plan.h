/* The memory plan of a run (docs/scene-format.md "Sizes"): the bytes one rank's particle arrays,
 * cell and neighbour lists, ghost buffers, image-derived fields, geometry build, initial
 * configuration and output buffers take, computed in double from the particle counts and the real
 * sizes of the engine's structures before any of them is allocated. sim_memory_check (sim.h)
 * compares it with the memory available (common/memory_limit.h) and refuses a run that cannot fit;
 * mdpore run --explain prints it. */
#ifndef MESO_ENGINE_MEMORY_PLAN_H
#define MESO_ENGINE_MEMORY_PLAN_H

#include "effects/plan.h"
#include "scene/scene.h"

#include <stddef.h>
#include <stdio.h>

#define MEMORY_PLAN_ITEMS 16

/* What the plan is built from. */
typedef struct {
  double owned;       /* particles owned by the rank (the largest rank's)                     */
  double total;       /* particles of the whole run                                           */
  double density;     /* the largest number density of the particles (rc^-3): list lengths    */
  double extent[3];   /* the rank's subdomain (rc)                                            */
  double voxels;      /* geometry: voxels of the image (0: none)                              */
  double input_set;   /* particles of an initial configuration every rank holds while they are
                         added (LAMMPS data, snapshot; 0: none)                                */
  double build_bytes; /* geometry: what the image build holds while its particles are added  */
  const char *stage;  /* what is checked: NULL for the run's particles, else what is about to
                         be built (the refusal names it; static or caller-owned text)          */
  int backend;        /* enum scene_backend                                                   */
  double device_bytes_per_particle; /* CUDA path: device bytes per particle slot (0: CPU)    */
} memory_inputs_t;

typedef struct {
  const char *name; /* static text */
  double bytes;
} memory_item_t;

typedef struct {
  memory_item_t item[MEMORY_PLAN_ITEMS];
  int n;
  double owned, ghosts; /* particles on the rank: owned, and ghost copies                    */
  double stride;        /* neighbour-list entries per owned particle (CPU path)              */
  double total;         /* host bytes of one rank                                             */
  double device;        /* CUDA path: device bytes of one rank (one GPU); 0 on the CPU path   */
} memory_plan_t;

/* The plan of one rank (host items; the device total apart). */
void memory_plan_build(const scene_t *s, const plan_t *plan, const memory_inputs_t *in,
                       memory_plan_t *mp);
/* One line per item, then the total (and the device's, on the CUDA path). */
void memory_plan_print(const memory_plan_t *mp, FILE *out);
/* The three largest items, "particle arrays 1.2 GB, neighbour lists 800 MB, ...". */
void memory_plan_largest(const memory_plan_t *mp, char *out, size_t len);
/* Bytes in words: "812 kB", "35.2 MB", "1.21 GB". */
const char *memory_bytes_text(double bytes, char *buf, size_t len);

/* What the geometry build (populate/image_walls.c) holds at its peak on one rank, in bytes: an upper
 * bound from the voxels of its window (what it reads: the voxels near its subdomain and a halo),
 * of gen (those it makes particles for), the image's x lines (ny nz), the x segments of the
 * decomposition and whether geometry.fluid_species_labels is set; the largest of its stages (the
 * image read, the pore clusters, the distance transform, the fluid counts, the id table and the
 * local list), each the sum of the arrays it holds. */
double memory_geometry_build_bytes(double window, double gen, double lines, double segments,
                                   int labels);

/* The largest number density of the scene's particles: its fills, or the geometry's wall and fluid
 * densities; 0 when the scene does not say (an initial configuration from a file). */
double memory_scene_density(const scene_t *s);
/* The inputs from the scene alone (mdpore run --explain; rank subdomains of equal size `dims`):
 * fills as density x region volume, a geometry at its largest density over the whole box (an upper
 * bound: the image is not read), a file's particles as 0 (counted when it is read). */
void memory_inputs_from_scene(const scene_t *s, const int dims[3], memory_inputs_t *in);

#endif
