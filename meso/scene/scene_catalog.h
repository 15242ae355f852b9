/* What the scene parser needs to know of the effects, handed to it by the registry
 * (meso/effects/effect_registry.c) so that the scene layer stays below the effects: each effect's
 * name, the pair parameters it needs, and its own option parser and consistency check. The parser
 * itself (scene_parse.c) is only the generic YAML walk. */
#ifndef MESO_SCENE_SCENE_CATALOG_H
#define MESO_SCENE_SCENE_CATALOG_H

#include "common/yaml_tree.h"
#include "scene/scene.h"

#include <stddef.h>
#include <stdio.h>

/* Pair parameters an effect needs (every species pair must then have a value). */
enum scene_pair_param {
  SCENE_PAIR_A = 1 << 0,
  SCENE_PAIR_B = 1 << 1,
  SCENE_PAIR_GAMMA = 1 << 2,
  SCENE_PAIR_RD = 1 << 3
};

/* Where an effect's check reports: error() and warn() name the key ("pairs.liquid-wall.rd") and
 * what was expected. When the scene comes from a file they print "FILE:LINE:COL: key 'K': ..."
 * at that key's line; for a scene built in code (plan_build) error() fills a message buffer and
 * warnings are dropped. */
typedef struct scene_report {
  int (*error)(struct scene_report *r, const char *key, const char *fmt, ...)
      __attribute__((format(printf, 3, 4))); /* returns -1 */
  void (*warn)(struct scene_report *r, const char *key, const char *fmt, ...)
      __attribute__((format(printf, 3, 4)));
  void *ctx;
} scene_report_t;

typedef struct scene_effect_entry {
  const char *name;     /* the key under 'effects:' */
  unsigned pair_params; /* OR of enum scene_pair_param */
  int confines;         /* 1: keeps particles inside the non-periodic faces of the box */
  /* Set the effect's option defaults when it is named (before parse). NULL: all zero. */
  void (*defaults)(scene_t *s);
  /* Parse the options node (a mapping, or null/empty when none were given) into the scene (through
   * SCENE_EFFECT_OPTIONS). path = "effects.NAME" for messages (yt_error). NULL: takes no options. */
  int (*parse)(ytree_t *t, yaml_node_t *options, const char *path, scene_t *s);
  /* Check the whole scene for this effect once everything is parsed: 0, or r->error(...) (-1).
   * NULL: nothing to check. */
  int (*check)(const scene_t *s, scene_report_t *r);
} scene_effect_entry_t;

typedef struct scene_catalog {
  int count;                                  /* entries, indexed by effect id */
  const scene_effect_entry_t *const *entries; /* [count] */
} scene_catalog_t;

#endif
