/* The `geometry:` block of a scene (docs/scene-format.md): a segmented image and how it becomes
 * walls and fluid. Parsed here; built by meso/build/image_walls.c. */
#ifndef MESO_SCENE_SCENE_GEOMETRY_H
#define MESO_SCENE_SCENE_GEOMETRY_H

#include "common/yaml_tree.h"
#include "scene/scene.h"

/* Parse `geometry:` into scene->geometry (species must be parsed first). 0, or -1 after
 * "FILE:LINE:COL: key 'geometry.K': expected ...". */
int scene_parse_geometry(ytree_t *t, yaml_node_t *n, scene_t *s);

#endif
