/* The `units:` block of a scene (docs/scene-format.md, "units"): what the reduced units are in SI,
 * so that the outputs give q in m/s and G in Pa/m next to the reduced numbers. Read by
 * common/units_block.h (shared with mdpore permeability); here the scene supplies its kT, its fluid
 * density and its geometry's rc_per_voxel. Outputs only: not part of the physics hash. */
#ifndef MESO_SCENE_SCENE_UNITS_H
#define MESO_SCENE_SCENE_UNITS_H

#include "common/yaml_tree.h"
#include "common/units_block.h"
#include "scene/scene.h"

/* Parse `units:` into scene->units (after the rest of the scene: it reads kT, geometry, the fills
 * and output.flux.density). 0, or -1 after "FILE:LINE:COL: key 'units.K': expected ...". */
int scene_parse_units(ytree_t *t, yaml_node_t *n, scene_t *s);

#endif
