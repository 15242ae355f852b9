/* The `balance:` block of a scene (docs/scene-format.md, "`balance`"): where the cuts between
 * the ranks' subdomains go (meso/domain/balance.c) and when they move again during a run
 * (meso/engine/sim_balance.c). */
#ifndef MESO_SCENE_SCENE_BALANCE_H
#define MESO_SCENE_SCENE_BALANCE_H

#include "common/yaml_tree.h"
#include "scene/scene.h"

/* The defaults (set before parsing): uniform cuts, as without the block. */
void scene_balance_defaults(scene_t *s);
/* Parse `balance:` into scene->balance. 0, or -1 after "FILE:LINE:COL: key 'balance.K': ...". */
int scene_parse_balance(ytree_t *t, yaml_node_t *n, scene_t *s);

#endif
