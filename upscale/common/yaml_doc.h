/* Thin helpers over libyaml's document API that produce "FILE:LINE: key 'k': expected ..., got ..."
 * messages (the config and fit-JSON readers use them). */
#ifndef MDPORE_UPSCALE_YAML_DOC_H
#define MDPORE_UPSCALE_YAML_DOC_H

#include <yaml.h>

typedef struct {
  yaml_document_t doc;
  const char *path;
  char *err;
  int errlen;
  int failed;
} ydoc;

/* Loads a file (YAML or JSON). Returns the root node or NULL with the error set. */
yaml_node_t *ydoc_load(ydoc *y, const char *path, char *err, int errlen);
void ydoc_free(ydoc *y);
int ydoc_fail(ydoc *y, const yaml_node_t *at, const char *fmt, ...);
int ydoc_line(const yaml_node_t *n);

/* Value of key in a mapping node (NULL if absent or map is not a mapping). */
yaml_node_t *ydoc_get(ydoc *y, const yaml_node_t *map, const char *key);
/* Fails (naming the key) if the mapping has a key not in the NULL-terminated list. */
int ydoc_only_keys(ydoc *y, const yaml_node_t *map, const char *what, const char *const *keys);
/* Scalars: number (finite), integer, string. Return 0 or -1 with the error set. */
int ydoc_number(ydoc *y, const yaml_node_t *map, const char *key, double *v);
int ydoc_int(ydoc *y, const yaml_node_t *map, const char *key, long *v);
const char *ydoc_string(ydoc *y, const yaml_node_t *map, const char *key);
int ydoc_is_map(const yaml_node_t *n);
int ydoc_is_seq(const yaml_node_t *n);
int ydoc_seq_len(const yaml_node_t *n);
yaml_node_t *ydoc_seq_item(ydoc *y, const yaml_node_t *seq, int i);
/* Number/int from a scalar node (for sequence items). */
int ydoc_node_number(ydoc *y, const yaml_node_t *n, const char *what, double *v);

#endif
