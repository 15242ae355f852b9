/* The `flood:` block of a scene (docs/twophase.md "Flooding"; scene.h scene_flood_t): one liquid
 * displacing another from a sample along a periodic axis (run/run_flood.c runs it). */
#ifndef MESO_SCENE_SCENE_FLOOD_H
#define MESO_SCENE_SCENE_FLOOD_H

#include "common/yaml_tree.h"
#include "scene/scene.h"

/* Parse `flood:` into scene->flood (box and species already parsed). 0, or -1 after
 * "FILE:LINE:COL: key 'flood.K': expected ...". */
int scene_parse_flood(ytree_t *t, yaml_node_t *n, scene_t *s);

#endif
