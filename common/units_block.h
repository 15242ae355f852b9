/* A `units:` block (docs/scene-format.md, "units"): the physical meaning of the reduced units of a
 * scene, read and checked here so that `mdpore run` (meso/scene/scene_units.c) and `mdpore
 * permeability` (campaign/campaign_template.c) read it the same way. The factors come from
 * common/units.h. Forms:
 *   {mapping: water, coarse_graining: N_m, temperature: T}   the mDPD water mapping: N_m water
 *        molecules per particle at the fluid density n: rc^3 = N_m n m_water / rho_water,
 *        m = N_m m_water (physics.md section 4: N_m = 3, n = 6.2 -> rc = 0.82 nm)
 *   {rc: M, tau: S | mass: KG, energy: J | temperature: T}   a user's own units
 *   {voxel_size: M, ...}   rc = voxel_size / geometry.rc_per_voxel (a scene with an image)
 * Energy unit e = kB T / kT (the scene's kT), or `energy`. Without tau or mass a particle carries
 * the water of its volume, m = rho_water / n. */
#ifndef MDPORE_COMMON_UNITS_BLOCK_H
#define MDPORE_COMMON_UNITS_BLOCK_H

#include "common/units.h"
#include "common/yaml_tree.h"

/* What the document around the block says (NAN: not known). */
typedef struct {
  double kT;                /* the scene's reduced kT (1 when absent) */
  double density;           /* fluid particles per rc^3, for the water mapping and m = rho_w / n */
  char density_source[128]; /* the key it came from, e.g. "geometry.fluid_density" */
  double rc_per_voxel;      /* voxel edge in rc (NAN: no geometry; voxel_size is then refused) */
} units_context_t;

void units_context_init(units_context_t *c);
/* Read the block at n (`path` is its key, e.g. "units"): every value finite and > 0, words known,
 * forms not mixed. 0, or -1 after "FILE:LINE:COL: key 'units.K': expected ...". */
int units_block_read(ytree_t *t, yaml_node_t *n, const char *path, const units_context_t *ctx,
                     units_mapping_t *m);
#endif
