/* Typed, position-aware reading of a YAML (or JSON) document over libyaml's document API, shared by
 * the scene parser (meso/io), the `mdpore darcy` config and fit-JSON readers (upscale/darcy).
 * Every getter takes the dotted key path of the node it reads and, on a mistake, prints
 *   FILE:LINE:COL: key 'path.to.key': expected WHAT (got WHAT)
 * to stderr and returns -1, so callers can stop at the first error. */
#ifndef MDPORE_COMMON_YAML_TREE_H
#define MDPORE_COMMON_YAML_TREE_H

#include <yaml.h>

typedef struct {
  const char *file;
  yaml_document_t doc;
  int quiet; /* 1: no messages (other ranks than 0) */
} ytree_t;

/* Load the first document of a file. Returns 0, or -1 with a message (syntax errors name line:col).
 */
int yt_load(ytree_t *t, const char *path, int quiet);
void yt_free(ytree_t *t);
yaml_node_t *yt_root(ytree_t *t);

/* Print "FILE:LINE:COL: key 'PATH': MESSAGE" (printf-style message) and return -1. */
int yt_error(const ytree_t *t, const yaml_node_t *at, const char *path, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* Same as a warning ("warning: ..."); returns 0. */
int yt_warn(const ytree_t *t, const yaml_node_t *at, const char *path, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* A short description of what a node holds, for "(got ...)": "'abc'", "a mapping", "a list". */
const char *yt_describe(const yaml_node_t *n, char *buf, int len);

int yt_is_null(const yaml_node_t *n); /* empty scalar or ~ / null */
int yt_expect_map(const ytree_t *t, yaml_node_t *n, const char *path);
int yt_expect_seq(const ytree_t *t, yaml_node_t *n, const char *path);

/* Check that every key of a mapping is plain text, in `allowed` (NULL-terminated) and appears once.
 * `allowed` NULL: any key (mappings whose keys the caller reads itself, such as species names). */
int yt_check_keys(const ytree_t *t, yaml_node_t *map, const char *path, const char *const *allowed);
/* The catalog of accepted keys, for the test that compares it with the docs (tests/docs,
 * check_keys_docs.py): with MDPORE_KEY_LOG=FILE set, every key list a reader checks is appended
 * to FILE as "PATH<TAB>KEY KEY ...", plus "*" when other keys (species names) are accepted too.
 * yt_check_keys records its list; a reader that checks its keys itself records them here. */
void yt_record_keys(const char *path, const char *const *allowed, int any_other);
/* Value node of a key in a mapping, or NULL when absent. */
yaml_node_t *yt_get(ytree_t *t, yaml_node_t *map, const char *key);
/* Value node of a key that must be present; NULL after "key 'PATH': expected WHAT (the key is
 * missing)" at the mapping's position. `path` is the key's full path, `what` e.g. "a number". */
yaml_node_t *yt_need(ytree_t *t, yaml_node_t *map, const char *key, const char *path,
                     const char *what);
/* Mapping iteration: number of pairs, i-th key string (scalar keys only) and value node. */
int yt_map_size(const yaml_node_t *map);
const char *yt_map_key(ytree_t *t, yaml_node_t *map, int i, yaml_node_t **key_node);
yaml_node_t *yt_map_value(ytree_t *t, yaml_node_t *map, int i);
int yt_seq_size(const yaml_node_t *seq);
yaml_node_t *yt_seq_item(ytree_t *t, yaml_node_t *seq, int i);

/* Scalars. `what` in messages is generated from the type ("a number", "an integer", ...). */
int yt_double(const ytree_t *t, yaml_node_t *n, const char *path, double *out);
int yt_long(const ytree_t *t, yaml_node_t *n, const char *path, long *out);
int yt_bool(const ytree_t *t, yaml_node_t *n, const char *path, int *out);
int yt_string(const ytree_t *t, yaml_node_t *n, const char *path, char *out, int len);
/* A list of exactly three numbers / booleans / integers. */
int yt_vec3(ytree_t *t, yaml_node_t *n, const char *path, double out[3]);
int yt_bool3(ytree_t *t, yaml_node_t *n, const char *path, int out[3]);
int yt_int3(ytree_t *t, yaml_node_t *n, const char *path, int out[3]);
/* One of a fixed set of words; returns its index in `words` (NULL-terminated) or -1 after a
 * message. */
int yt_enum(const ytree_t *t, yaml_node_t *n, const char *path, const char *const *words);

#endif
