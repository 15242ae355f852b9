/* The `geometry:` block of a scene (docs/scene-format.md): a segmented image and how it becomes
 * walls and fluid. Parsed here; built by meso/populate/image_walls.c. */
#ifndef MESO_SCENE_SCENE_GEOMETRY_H
#define MESO_SCENE_SCENE_GEOMETRY_H

#include "common/yaml_tree.h"
#include "mdpore_image.h"
#include "physics/voxel_grid.h"
#include "scene/scene.h"

#include <stddef.h>

/* Parse `geometry:` into scene->geometry (species must be parsed first). 0, or -1 after
 * "FILE:LINE:COL: key 'geometry.K': expected ...". */
int scene_parse_geometry(ytree_t *t, yaml_node_t *n, scene_t *s);

/* The cylinder / sphere / outside keys of a region item at `path` (initial.fill[i] or
 * geometry.fluid_species_regions[i]) into f; defined in scene_parse.c. 0, or -1 after an error
 * naming the key. */
int scene_parse_fill_shape(ytree_t *t, yaml_node_t *item, const char *path, const scene_t *s,
                           scene_fill_t *f);

/* The geometry's image as the box sees it: read with the scene's label map, axes permuted by
 * geometry.axis_map, and checked against the box (box length = voxels x rc_per_voxel on every
 * axis). 0, or -1 with a message naming the scene file, the key and what was expected in err. */
int scene_geometry_read_image(const scene_t *s, mdp_image_t *img, char *err, size_t errlen);

/* The voxel grid of such an image over the box (physics/voxel_grid.h). */
void scene_geometry_grid(const scene_t *s, const mdp_image_t *img, voxel_grid_t *grid);

#endif
