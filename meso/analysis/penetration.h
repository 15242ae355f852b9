/* Penetration count: mobile particles inside the solid voxels of the scene's
 * geometry image, and how deep. Whatever boundary a scene uses, this number must stay 0; the run
 * loop puts it in the thermo log and the summary, and with geometry.strict stops the run naming the
 * particle, the voxel and the step. The same pass counts the mobile particles of the pore core (pore
 * voxels at least core_rc from the solid): the density the pore fluid has away from the walls,
 * whose viscosity a permeability campaign uses (docs/permeability.md). */
#ifndef MESO_ANALYSIS_PENETRATION_H
#define MESO_ANALYSIS_PENETRATION_H

#include "engine/sim.h"
#include "physics/voxel_grid.h"

#include <stddef.h>
#include <stdint.h>

typedef struct {
  int on;
  voxel_grid_t grid; /* the image's voxels over the box */
  int n[3];
  double h;       /* voxel edge (rc) */
  float *depth;   /* [n0 n1 n2]: for a solid voxel, the distance (rc) from its centre to the nearest
                    pore voxel's centre (26-connected layers x h, > 0); for a pore voxel, minus the
                    distance to the nearest solid voxel's centre (<= 0; -FLT_MAX with no solid) */
  double core_rc; /* pore core: pore voxels with depth <= -core_rc (MESO_PORE_CORE_RC) */
  long core_voxels; /* their number (0: the pores have no core) */
  const scene_t *scene;
} penetration_map_t;

typedef struct {
  long count;       /* mobile particles in solid voxels (all ranks) */
  double max_depth; /* depth of the deepest voxel holding one (rc) */
  int64_t id;       /* the deepest one (-1 when none) */
  double x[3];
  int voxel[3];
  long core_count; /* mobile particles in pore-core voxels (all ranks) */
} penetration_t;

/* The pore core's inner edge: 1.5 rc from the solid, past the layered fluid next to a wall (the
 * contact layer is 8% denser than the core at wall density 4, docs/permeability.md). */
#define MESO_PORE_CORE_RC 1.5
/* The run loop's census of a geometry scene (penetrations, the pore core's density): at thermo rows
 * and every this many steps. On the GPU each copies the particles to the host (~25 ms at 10M
 * particles over PCIe, so ~0.5% of the step time at this interval). */
#define MESO_GEOMETRY_SAMPLE_EVERY 500

/* The map of the scene's geometry image (off when the scene has none). 0, or -1 with the reason. */
int penetration_map_create(penetration_map_t *m, const scene_t *scene, char *err, size_t errlen);
void penetration_map_free(penetration_map_t *m);

/* Count over the particles of sim (collective; identical result on every rank). */
void penetration_count(const penetration_map_t *m, sim_t *sim, penetration_t *out);

#endif
