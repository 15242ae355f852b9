/* Key readers shared by the parts of the `mdpore darcy` config reader (darcy_config.c,
 * twophase_config_read.c). Each prints "FILE:LINE:COL: key 'a.b': expected ... (got ...)" and
 * returns -1 on a bad value. */
#ifndef MDPORE_UPSCALE_DARCY_CONFIG_KEYS_H
#define MDPORE_UPSCALE_DARCY_CONFIG_KEYS_H

#include <stddef.h>

#include "common/yaml_tree.h"
#include "darcy_units.h"

/* A number with an optional unit at node n (key path `path`) into the unit system's base unit. */
int darcy_key_quantity(ytree_t *t, yaml_node_t *n, const char *path, darcy_quantity q, int si,
                       double *v);
/* A file name at node n, relative to the config file's folder unless absolute. */
int darcy_key_file_name(ytree_t *t, yaml_node_t *n, const char *path, char *out, size_t len);

#endif
