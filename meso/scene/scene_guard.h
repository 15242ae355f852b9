/* The `guard:` block of a scene (docs/scene-format.md, "Guardrails"): the settings of the run's
 * health checks that are not on every step (meso/analysis/temperature_guard.c, density_guard.c). */
#ifndef MESO_SCENE_SCENE_GUARD_H
#define MESO_SCENE_SCENE_GUARD_H

#include "common/yaml_tree.h"
#include "scene/scene.h"

/* The defaults (set before parsing). */
void scene_guard_defaults(scene_t *s);
/* Parse `guard:` into scene->guard. 0, or -1 after "FILE:LINE:COL: key 'guard.K': expected ...". */
int scene_parse_guard(ytree_t *t, yaml_node_t *n, scene_t *s);

#endif
