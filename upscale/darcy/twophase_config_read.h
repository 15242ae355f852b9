/* Reader of the `twophase:` block of a `mdpore darcy` config (twophase_config.h). */
#ifndef MDPORE_UPSCALE_TWOPHASE_CONFIG_READ_H
#define MDPORE_UPSCALE_TWOPHASE_CONFIG_READ_H

#include "common/yaml_tree.h"
#include "darcy_config.h"

/* Reads node n (key `twophase`) into c->twophase; call after the grid, boundary and laws are read.
 * Returns 0, or -1 after printing "FILE:LINE:COL: key 'twophase.x': expected ... (got ...)". */
int twophase_config_read(ytree_t *t, yaml_node_t *n, darcy_config *c);

#endif
