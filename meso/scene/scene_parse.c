/* Scene file parser: YAML (libyaml) -> scene_t, with validation. The format is documented in
 * docs/scene-format.md. Every mistake stops with "FILE:LINE:COL: key 'a.b': expected ... (got
 * ...)". */
#include "common/same_file.h"
#include "common/size_check.h"
#include "common/yaml_tree.h"
#include "physics/density_kernels.h"
#include "scene/scene.h"
#include "scene/scene_catalog.h"
#include "scene/scene_geometry.h"
#include "scene/scene_balance.h"
#include "scene/scene_flood.h"
#include "scene/scene_guard.h"
#include "scene/scene_units.h"

#include <stdarg.h>

#include <ctype.h>
#include <libgen.h>
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TRY(x)                                                                                     \
  do {                                                                                             \
    if ((x) != 0) return -1;                                                                       \
  } while (0)

static const char *const axis_words[] = {"x", "y", "z", NULL};

/* Parameters given for one pair, with which ones were set (defaults and overrides are merged). */
enum { P_A, P_B, P_GAMMA, P_RC, P_RD, P_S, P_COUNT };
static const char *const pair_keys[] = {"A", "B", "gamma", "rc", "rd", "s", NULL};
typedef struct {
  double v[P_COUNT];
  int set[P_COUNT];
  yaml_node_t *where[P_COUNT];
} pair_in_t;

static void join(char *out, size_t len, const char *path, const char *key) {
  snprintf(out, len, "%s%s%s", path, *path ? "." : "", key);
}

static int parse_box(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"lo", "hi", "periodic", "procs", NULL};
  TRY(yt_check_keys(t, n, "box", keys));
  yaml_node_t *v;
  if ((v = yt_get(t, n, "lo"))) TRY(yt_vec3(t, v, "box.lo", s->box_lo));
  if (!(v = yt_get(t, n, "hi")))
    return yt_error(t, n, "box.hi", "expected the upper box corner [x, y, z] (got nothing)");
  TRY(yt_vec3(t, v, "box.hi", s->box_hi));
  for (int d = 0; d < 3; d++)
    if (!(s->box_hi[d] > s->box_lo[d]))
      return yt_error(t, v, "box.hi",
                      "expected hi > lo on every axis (got hi[%d] = %g <= lo[%d] = %g)", d,
                      s->box_hi[d], d, s->box_lo[d]);
  if ((v = yt_get(t, n, "periodic"))) {
    if (v->type == YAML_SCALAR_NODE) {
      int p;
      TRY(yt_bool(t, v, "box.periodic", &p));
      s->periodic[0] = s->periodic[1] = s->periodic[2] = p;
    } else {
      TRY(yt_bool3(t, v, "box.periodic", s->periodic));
    }
  }
  if ((v = yt_get(t, n, "procs"))) {
    TRY(yt_int3(t, v, "box.procs", s->procs));
    for (int d = 0; d < 3; d++)
      if (s->procs[d] < 0)
        return yt_error(t, v, "box.procs", "expected ranks per axis >= 0, 0 = automatic (got %d)",
                        s->procs[d]);
  }
  return 0;
}

/* species[i].velocity: a frozen species translating at a fixed velocity along one periodic box axis
 * (moving walls, plane Couette; docs/walls.md). The box is parsed before the species. */
static int parse_species_velocity(ytree_t *t, yaml_node_t *v, const char *path, const scene_t *s,
                                  scene_species_t *sp) {
  char sub[96];
  join(sub, sizeof sub, path, "velocity");
  double u[3];
  TRY(yt_vec3(t, v, sub, u));
  int n_axes = 0, axis = -1;
  for (int d = 0; d < 3; d++) {
    if (!isfinite(u[d])) return yt_error(t, v, sub, "expected finite numbers [ux, uy, uz]");
    if (u[d] != 0.0) n_axes++, axis = d;
  }
  if (n_axes == 0) return 0; /* at rest: a plain frozen species */
  if (!sp->frozen)
    return yt_error(t, v, sub,
                    "expected 'frozen: true' before a velocity: only a frozen species moves at a "
                    "fixed velocity (got a mobile species '%s')",
                    sp->name);
  if (n_axes > 1)
    return yt_error(t, v, sub,
                    "expected a velocity along one box axis, e.g. [0.5, 0, 0] (got [%g, %g, %g])",
                    u[0], u[1], u[2]);
  if (!s->periodic[axis])
    return yt_error(t, v, sub,
                    "expected a velocity along a periodic box axis (got one along %c, which is not "
                    "periodic: the particles would leave the box)",
                    "xyz"[axis]);
  for (int d = 0; d < 3; d++) sp->velocity[d] = u[d];
  sp->moving = 1;
  sp->move_axis = axis;
  return 0;
}

static int parse_species(ytree_t *t, yaml_node_t *n, scene_t *s) {
  TRY(yt_expect_seq(t, n, "species"));
  const int count = yt_seq_size(n);
  if (count < 1)
    return yt_error(t, n, "species", "expected at least one species (got an empty list)");
  if (count > SCENE_MAX_SPECIES)
    return yt_error(t, n, "species", "expected at most %d species (got %d)", SCENE_MAX_SPECIES,
                    count);
  static const char *const keys[] = {"name", "mass", "frozen", "velocity", NULL};
  for (int i = 0; i < count; i++) {
    char path[64], sub[96];
    snprintf(path, sizeof path, "species[%d]", i);
    yaml_node_t *item = yt_seq_item(t, n, i), *v;
    TRY(yt_check_keys(t, item, path, keys));
    scene_species_t *sp = &s->species[i];
    sp->mass = 1.0;
    join(sub, sizeof sub, path, "name");
    if (!(v = yt_get(t, item, "name")))
      return yt_error(t, item, sub, "expected a species name (got nothing)");
    TRY(yt_string(t, v, sub, sp->name, SCENE_NAME_LEN));
    for (const char *c = sp->name; *c; c++)
      if (!isalnum((unsigned char)*c) && *c != '_')
        return yt_error(t, v, sub, "expected letters, digits and '_' only (got '%s')", sp->name);
    for (int j = 0; j < i; j++)
      if (!strcmp(s->species[j].name, sp->name))
        return yt_error(t, v, sub, "expected a unique species name (got '%s' twice)", sp->name);
    if ((v = yt_get(t, item, "mass"))) {
      join(sub, sizeof sub, path, "mass");
      TRY(yt_double(t, v, sub, &sp->mass));
      if (!(sp->mass > 0)) return yt_error(t, v, sub, "expected a mass > 0 (got %g)", sp->mass);
    }
    if ((v = yt_get(t, item, "frozen"))) {
      join(sub, sizeof sub, path, "frozen");
      TRY(yt_bool(t, v, sub, &sp->frozen));
    }
    if ((v = yt_get(t, item, "velocity"))) TRY(parse_species_velocity(t, v, path, s, sp));
  }
  s->n_species = count;
  return 0;
}

static int parse_pair_params(ytree_t *t, yaml_node_t *n, const char *path, pair_in_t *p) {
  TRY(yt_check_keys(t, n, path, pair_keys));
  for (int k = 0; k < P_COUNT; k++) {
    yaml_node_t *v = yt_get(t, n, pair_keys[k]);
    if (!v) continue;
    char sub[128];
    join(sub, sizeof sub, path, pair_keys[k]);
    TRY(yt_double(t, v, sub, &p->v[k]));
    p->set[k] = 1;
    p->where[k] = v;
  }
  return 0;
}

/* pairs: {default: {...}, a-b: {...}} -> merged per-pair parameters. */
static int parse_pairs(ytree_t *t, yaml_node_t *n, const scene_t *s,
                       pair_in_t pin[SCENE_MAX_SPECIES][SCENE_MAX_SPECIES]) {
  TRY(yt_expect_map(t, n, "pairs"));
  static const char *const named[] = {"default", NULL}; /* + speciesA-speciesB */
  yt_record_keys("pairs", named, 1);
  const int np = yt_map_size(n);
  yaml_node_t *def = yt_get(t, n, "default");
  pair_in_t d;
  memset(&d, 0, sizeof d);
  if (def) TRY(parse_pair_params(t, def, "pairs.default", &d));
  for (int a = 0; a < s->n_species; a++)
    for (int b = 0; b < s->n_species; b++) pin[a][b] = d;
  for (int i = 0; i < np; i++) {
    yaml_node_t *kn;
    const char *key = yt_map_key(t, n, i, &kn);
    if (!key) return yt_error(t, kn, "pairs", "expected 'default' or 'speciesA-speciesB' keys");
    if (!strcmp(key, "default")) continue;
    char path[160], a_name[SCENE_NAME_LEN] = "", b_name[SCENE_NAME_LEN] = "";
    snprintf(path, sizeof path, "pairs.%s", key);
    const char *dash = strchr(key, '-');
    if (dash && dash - key < SCENE_NAME_LEN && strlen(dash + 1) < SCENE_NAME_LEN) {
      memcpy(a_name, key, (size_t)(dash - key));
      a_name[dash - key] = 0;
      strcpy(b_name, dash + 1);
    }
    const int a = scene_species_index(s, a_name), b = scene_species_index(s, b_name);
    if (!dash || a < 0 || b < 0) {
      char list[512] = "";
      for (int k = 0; k < s->n_species; k++) {
        strncat(list, k ? ", " : "", sizeof list - strlen(list) - 1);
        strncat(list, s->species[k].name, sizeof list - strlen(list) - 1);
      }
      return yt_error(t, kn, path,
                      "expected 'default' or 'A-B' with A and B among the species (%s) (got '%s')",
                      list, key);
    }
    for (int j = 0; j < i; j++) {
      const char *other = yt_map_key(t, n, j, NULL);
      char rev[2 * SCENE_NAME_LEN + 2];
      snprintf(rev, sizeof rev, "%s-%s", b_name, a_name);
      if (other && (!strcmp(other, key) || !strcmp(other, rev)))
        return yt_error(t, kn, path, "expected each species pair once (got it again as '%s')", key);
    }
    pair_in_t over;
    memset(&over, 0, sizeof over);
    TRY(parse_pair_params(t, yt_map_value(t, n, i), path, &over));
    for (int k = 0; k < P_COUNT; k++)
      if (over.set[k]) {
        pin[a][b].v[k] = pin[b][a].v[k] = over.v[k];
        pin[a][b].set[k] = pin[b][a].set[k] = 1;
        pin[a][b].where[k] = pin[b][a].where[k] = over.where[k];
      }
  }
  return 0;
}

/* effects: {name: options, ...}: each name looked up in the catalog, its options parsed by the
 * effect itself (scene_effect_entry_t.parse). */
static int parse_effects(ytree_t *t, yaml_node_t *n, const scene_catalog_t *cat, scene_t *s) {
  TRY(yt_expect_map(t, n, "effects"));
  { /* the catalog of effect names, and of the effects that take no options (yt_record_keys) */
    const char *names[64];
    int k = 0;
    for (; k < cat->count && k < 63; k++) names[k] = cat->entries[k]->name;
    names[k] = NULL;
    yt_record_keys("effects", names, 0);
    static const char *const none[] = {NULL};
    for (k = 0; k < cat->count; k++)
      if (!cat->entries[k]->parse) {
        char path[160];
        snprintf(path, sizeof path, "effects.%s", cat->entries[k]->name);
        yt_record_keys(path, none, 0);
      }
  }
  const int count = yt_map_size(n);
  for (int i = 0; i < count; i++) {
    yaml_node_t *kn;
    const char *key = yt_map_key(t, n, i, &kn);
    int e = -1;
    for (int k = 0; key && k < cat->count; k++)
      if (!strcmp(key, cat->entries[k]->name)) e = k;
    char path[160];
    snprintf(path, sizeof path, "effects.%s", key ? key : "?");
    if (e < 0) {
      char list[512] = "";
      for (int k = 0; k < cat->count; k++) {
        strncat(list, k ? ", " : "", sizeof list - strlen(list) - 1);
        strncat(list, cat->entries[k]->name, sizeof list - strlen(list) - 1);
      }
      return yt_error(t, kn, path, "unknown effect (expected one of: %s)", list);
    }
    if (s->effect[e]) return yt_error(t, kn, path, "expected each effect once (got a duplicate)");
    s->effect[e] = 1;
    if (cat->entries[e]->defaults) cat->entries[e]->defaults(s);
    yaml_node_t *opt = yt_map_value(t, n, i);
    if (yt_is_null(opt)) continue;
    if (cat->entries[e]->parse) {
      TRY(cat->entries[e]->parse(t, opt, path, s));
    } else {
      static const char *const none[] = {NULL};
      if (opt->type == YAML_MAPPING_NODE && yt_map_size(opt) == 0) continue;
      TRY(yt_check_keys(t, opt, path, none));
    }
  }
  return 0;
}

/* Check the merged pair parameters against the named effects and copy them into the scene. */
static int finish_pairs(ytree_t *t, yaml_node_t *pairs_node, const scene_catalog_t *cat, scene_t *s,
                        pair_in_t pin[SCENE_MAX_SPECIES][SCENE_MAX_SPECIES]) {
  /* The parameters the named effects need, and which effects need each (for the message). */
  static const unsigned param_bit[P_COUNT] = {
      SCENE_PAIR_A, SCENE_PAIR_B, SCENE_PAIR_GAMMA, 0, SCENE_PAIR_RD, 0};
  int need[P_COUNT] = {0};
  char why[P_COUNT][256] = {{0}};
  for (int e = 0; e < cat->count; e++)
    for (int k = 0; k < P_COUNT; k++)
      if (s->effect[e] && (cat->entries[e]->pair_params & param_bit[k])) {
        need[k] = 1;
        const size_t used = strlen(why[k]);
        snprintf(why[k] + used, sizeof why[k] - used, "%s%s", used ? "/" : "",
                 cat->entries[e]->name);
      }
  for (int a = 0; a < s->n_species; a++)
    for (int b = a; b < s->n_species; b++) {
      pair_in_t *p = &pin[a][b];
      char path[160];
      snprintf(path, sizeof path, "pairs.%s-%s", s->species[a].name, s->species[b].name);
      for (int k = 0; k < P_COUNT; k++) {
        char sub[192];
        join(sub, sizeof sub, path, pair_keys[k]);
        if (need[k] && !p->set[k])
          return yt_error(t, pairs_node, sub,
                          "expected a value: %s is named (got nothing; set it under "
                          "pairs.default or this pair)",
                          why[k]);
      }
      if (!p->set[P_RC]) p->v[P_RC] = 1.0;
      if (!p->set[P_RD]) p->v[P_RD] = p->v[P_RC];
      if (!(p->v[P_RC] > 0)) {
        char sub[192];
        join(sub, sizeof sub, path, "rc");
        return yt_error(t, p->where[P_RC], sub, "expected rc > 0 (got %g)", p->v[P_RC]);
      }
      /* s: the thermostat weight's exponent; 0 (not set) = the thermostat's own exponent */
      if (p->set[P_S] && !(p->v[P_S] > 0 && p->v[P_S] <= SCENE_PAIR_S_MAX)) {
        char sub[192];
        join(sub, sizeof sub, path, "s");
        return yt_error(t, p->where[P_S], sub,
                        "expected an exponent 0 < s <= %g of the thermostat weight w_R = (1 - "
                        "r/rc)^s (got %g)",
                        SCENE_PAIR_S_MAX, p->v[P_S]);
      }
      scene_pair_t q = {p->v[P_A],  p->v[P_B],  p->v[P_GAMMA],
                        p->v[P_RC], p->v[P_RD], p->set[P_S] ? p->v[P_S] : 0.0};
      s->pair[a][b] = s->pair[b][a] = q;
    }
  return 0;
}

/* The node at a dotted key path ("pairs.liquid-wall.rd"), or its deepest existing parent: where a
 * check's message points. */
static yaml_node_t *node_at(ytree_t *t, const char *key) {
  yaml_node_t *n = yt_root(t);
  char buf[256];
  snprintf(buf, sizeof buf, "%s", key);
  const char *parent = "";
  for (char *part = strtok(buf, "."); part && n && n->type == YAML_MAPPING_NODE;
       part = strtok(NULL, ".")) {
    yaml_node_t *next = yt_get(t, n, part);
    /* a pair "a-b" may be given only under pairs.default */
    if (!next && !strcmp(parent, "pairs")) next = yt_get(t, n, "default");
    if (!next) break;
    n = next;
    parent = part;
  }
  return n;
}

static int report_error(scene_report_t *r, const char *key, const char *fmt, ...) {
  ytree_t *t = r->ctx;
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  return yt_error(t, node_at(t, key), key, "%s", msg);
}

static void report_warn(scene_report_t *r, const char *key, const char *fmt, ...) {
  ytree_t *t = r->ctx;
  char msg[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(msg, sizeof msg, fmt, ap);
  va_end(ap);
  yt_warn(t, node_at(t, key), key, "%s", msg);
}

/* Scene-wide rules that involve effects, then each named effect's own check. */
static int check_effects(ytree_t *t, const scene_catalog_t *cat, scene_t *s) {
  int walls_needed = 0, confined = 0;
  char confining[256] = "";
  for (int d = 0; d < 3; d++) walls_needed |= !s->periodic[d];
  for (int e = 0; e < cat->count; e++)
    if (cat->entries[e]->confines) {
      confined |= s->effect[e];
      const size_t used = strlen(confining);
      snprintf(confining + used, sizeof confining - used, "%s%s", used ? " or " : "",
               cat->entries[e]->name);
    }
  if (walls_needed && !confined)
    return yt_error(t, node_at(t, "box.periodic"), "box.periodic",
                    "expected every axis periodic, or the %s effect for the non-periodic ones (got "
                    "a non-periodic axis without it)",
                    confining);
  scene_report_t r = {.error = report_error, .warn = report_warn, .ctx = t};
  for (int e = 0; e < cat->count; e++)
    if (s->effect[e] && cat->entries[e]->check) TRY(cat->entries[e]->check(s, &r));
  return 0;
}

/* initial.fill[i].cylinder / .sphere / .outside: the shape cut out of a fill region (also read
 * for geometry.fluid_species_regions[i], scene_geometry.h). */
int scene_parse_fill_shape(ytree_t *t, yaml_node_t *item, const char *path, const scene_t *s,
                           scene_fill_t *f) {
  static const char *const axis_words[] = {"x", "y", "z", NULL};
  yaml_node_t *cyl = yt_get(t, item, "cylinder"), *sph = yt_get(t, item, "sphere"), *v, *w;
  char sub[128], key[160];
  if (cyl && sph) {
    join(sub, sizeof sub, path, "sphere");
    return yt_error(t, sph, sub, "expected one shape per region: cylinder or sphere (got both)");
  }
  if ((v = yt_get(t, item, "outside"))) {
    join(sub, sizeof sub, path, "outside");
    TRY(yt_bool(t, v, sub, &f->outside));
    if (!cyl && !sph)
      return yt_error(t, v, sub, "expected a cylinder or a sphere in the same region (got none)");
  }
  if (!cyl && !sph) return 0;
  f->shape = cyl ? FILL_SHAPE_CYLINDER : FILL_SHAPE_SPHERE;
  join(sub, sizeof sub, path, cyl ? "cylinder" : "sphere");
  yaml_node_t *sh = cyl ? cyl : sph;
  static const char *const ck[] = {"axis", "centre", "radius", NULL};
  static const char *const sk[] = {"centre", "radius", NULL};
  TRY(yt_expect_map(t, sh, sub));
  TRY(yt_check_keys(t, sh, sub, cyl ? ck : sk));
  if (cyl) {
    join(key, sizeof key, sub, "axis");
    if (!(w = yt_get(t, sh, "axis")))
      return yt_error(t, sh, key, "expected x, y or z (got nothing)");
    if ((f->shape_axis = yt_enum(t, w, key, axis_words)) < 0) return -1;
  }
  join(key, sizeof key, sub, "centre");
  if (!(w = yt_get(t, sh, "centre")))
    return yt_error(t, sh, key, "expected a point [x, y, z] (got nothing)");
  TRY(yt_vec3(t, w, key, f->centre));
  for (int d = 0; d < 3; d++)
    if ((!cyl || d != f->shape_axis) &&
        (f->centre[d] < s->box_lo[d] || f->centre[d] > s->box_hi[d]))
      return yt_error(t, w, key, "expected a point inside the box [%g, %g] on axis %c (got %g)",
                      s->box_lo[d], s->box_hi[d], "xyz"[d], f -> centre[d]);
  join(key, sizeof key, sub, "radius");
  if (!(w = yt_get(t, sh, "radius")))
    return yt_error(t, sh, key, "expected a radius > 0 (got nothing)");
  TRY(yt_double(t, w, key, &f->radius));
  if (!(f->radius > 0)) return yt_error(t, w, key, "expected a radius > 0 (got %g)", f->radius);
  return 0;
}

static int parse_fill(ytree_t *t, yaml_node_t *n, scene_t *s) {
  TRY(yt_expect_seq(t, n, "initial.fill"));
  const int count = yt_seq_size(n);
  if (count < 1)
    return yt_error(t, n, "initial.fill", "expected at least one region (got an empty list)");
  if (count > SCENE_MAX_FILLS)
    return yt_error(t, n, "initial.fill", "expected at most %d regions (got %d)", SCENE_MAX_FILLS,
                    count);
  static const char *const keys[] = {"species",  "lo",     "hi",      "density", "mode",
                                     "cylinder", "sphere", "outside", NULL};
  static const char *const modes[] = {"lattice", "random", NULL};
  for (int i = 0; i < count; i++) {
    char path[64], sub[96], name[SCENE_NAME_LEN];
    snprintf(path, sizeof path, "initial.fill[%d]", i);
    yaml_node_t *item = yt_seq_item(t, n, i), *v;
    TRY(yt_check_keys(t, item, path, keys));
    scene_fill_t *f = &s->init.fill[i];
    f->mode = FILL_RANDOM;
    memcpy(f->lo, s->box_lo, sizeof f->lo);
    memcpy(f->hi, s->box_hi, sizeof f->hi);
    join(sub, sizeof sub, path, "species");
    if (!(v = yt_get(t, item, "species")))
      return yt_error(t, item, sub, "expected a species name (got nothing)");
    TRY(yt_string(t, v, sub, name, sizeof name));
    if ((f->species = scene_species_index(s, name)) < 0)
      return yt_error(t, v, sub, "expected one of the species listed under 'species' (got '%s')",
                      name);
    join(sub, sizeof sub, path, "density");
    if (!(v = yt_get(t, item, "density")))
      return yt_error(t, item, sub, "expected a number density (got nothing)");
    TRY(yt_double(t, v, sub, &f->density));
    if (!(f->density > 0))
      return yt_error(t, v, sub, "expected a number density > 0 (got %g)", f->density);
    if ((v = yt_get(t, item, "mode"))) {
      join(sub, sizeof sub, path, "mode");
      if ((f->mode = yt_enum(t, v, sub, modes)) < 0) return -1;
    }
    for (int c = 0; c < 2; c++) {
      const char *k = c ? "hi" : "lo";
      double *x = c ? f->hi : f->lo;
      if (!(v = yt_get(t, item, k))) continue;
      join(sub, sizeof sub, path, k);
      TRY(yt_vec3(t, v, sub, x));
      for (int d = 0; d < 3; d++)
        if (x[d] < s->box_lo[d] || x[d] > s->box_hi[d])
          return yt_error(t, v, sub,
                          "expected a corner inside the box [%g, %g] on axis %c (got %g)",
                          s->box_lo[d], s->box_hi[d], "xyz"[d], x[d]);
    }
    for (int d = 0; d < 3; d++)
      if (!(f->hi[d] > f->lo[d])) {
        join(sub, sizeof sub, path, "hi");
        return yt_error(t, item, sub,
                        "expected hi > lo on every axis (got hi[%d] = %g <= lo[%d] = %g)", d,
                        f->hi[d], d, f->lo[d]);
      }
    TRY(scene_parse_fill_shape(t, item, path, s, f));
  }
  s->init.n_fill = count;
  return 0;
}

static int parse_initial(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"fill", "lammps_data", "snapshot", "temperature", NULL};
  TRY(yt_check_keys(t, n, "initial", keys));
  yaml_node_t *fill = yt_get(t, n, "fill"), *data = yt_get(t, n, "lammps_data"),
              *snap = yt_get(t, n, "snapshot");
  if (s->geometry.on && !!fill + !!data + !!snap > 0)
    return yt_error(t, n, "initial",
                    "expected only 'temperature' here: the particles come from 'geometry' (got "
                    "fill, lammps_data or snapshot as well)");
  if (s->geometry.on) {
    s->init.kind = INIT_GEOMETRY;
  } else if (!!fill + !!data + !!snap != 1)
    return yt_error(t, n, "initial", "expected exactly one of fill, lammps_data, snapshot (got %d)",
                    !!fill + !!data + !!snap);
  char p[SCENE_PATH_LEN];
  if (s->geometry.on) {
    /* nothing more: the geometry builder makes the particles */
  } else if (fill) {
    s->init.kind = INIT_FILL;
    TRY(parse_fill(t, fill, s));
  } else if (data) {
    s->init.kind = INIT_LAMMPS_DATA;
    TRY(yt_string(t, data, "initial.lammps_data", p, sizeof p));
    if (scene_relative_path(s->file, p, s->init.path, sizeof s->init.path))
      return yt_error(t, data, "initial.lammps_data",
                      "expected a path that, joined to the scene's folder, is shorter than %d "
                      "characters",
                      SCENE_PATH_LEN);
  } else {
    s->init.kind = INIT_SNAPSHOT;
    TRY(yt_string(t, snap, "initial.snapshot", p, sizeof p));
    if (scene_relative_path(s->file, p, s->init.path, sizeof s->init.path))
      return yt_error(t, snap, "initial.snapshot",
                      "expected a path that, joined to the scene's folder, is shorter than %d "
                      "characters",
                      SCENE_PATH_LEN);
  }
  yaml_node_t *v = yt_get(t, n, "temperature");
  if (v) {
    TRY(yt_double(t, v, "initial.temperature", &s->init.temperature));
    if (s->init.temperature < 0)
      return yt_error(t, v, "initial.temperature", "expected a temperature >= 0 (got %g)",
                      s->init.temperature);
  }
  return 0;
}

static int parse_run(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"dt", "steps", "seed", "vv_lambda", "target_error", NULL};
  TRY(yt_check_keys(t, n, "run", keys));
  yaml_node_t *v;
  if (!(v = yt_get(t, n, "dt")))
    return yt_error(t, n, "run.dt", "expected a time step > 0 (got nothing)");
  TRY(yt_double(t, v, "run.dt", &s->dt));
  if (!(s->dt > 0)) return yt_error(t, v, "run.dt", "expected a time step > 0 (got %g)", s->dt);
  if (!(v = yt_get(t, n, "steps")))
    return yt_error(t, n, "run.steps", "expected a number of steps (got nothing)");
  TRY(yt_long(t, v, "run.steps", &s->steps));
  if (s->steps < 0) return yt_error(t, v, "run.steps", "expected steps >= 0 (got %ld)", s->steps);
  if ((v = yt_get(t, n, "seed"))) {
    long seed;
    TRY(yt_long(t, v, "run.seed", &seed));
    if (seed < 0) return yt_error(t, v, "run.seed", "expected a seed >= 0 (got %ld)", seed);
    s->seed = (uint64_t)seed;
  }
  if ((v = yt_get(t, n, "vv_lambda"))) {
    TRY(yt_double(t, v, "run.vv_lambda", &s->vv_lambda));
    if (s->vv_lambda < 0 || s->vv_lambda > 1)
      return yt_error(t, v, "run.vv_lambda", "expected 0 <= lambda <= 1 (got %g)", s->vv_lambda);
  }
  if ((v = yt_get(t, n, "target_error"))) {
    TRY(yt_double(t, v, "run.target_error", &s->target_error));
    if (!(s->target_error > 0 && s->target_error < 1))
      return yt_error(t, v, "run.target_error",
                      "expected a relative error of q with 0 < E < 1, e.g. 0.02 (got %g)",
                      s->target_error);
  }
  return 0;
}

/* A periodic output {every, file}. */
static int parse_periodic(ytree_t *t, yaml_node_t *n, const char *path, scene_output_t *o,
                          const char *const *exts) {
  static const char *const keys[] = {"every", "file", NULL};
  TRY(yt_check_keys(t, n, path, keys));
  char sub[96];
  yaml_node_t *v;
  join(sub, sizeof sub, path, "every");
  if (!(v = yt_get(t, n, "every")))
    return yt_error(t, n, sub, "expected an interval in steps (got nothing)");
  TRY(yt_long(t, v, sub, &o->every));
  if (o->every < 1)
    return yt_error(t, v, sub, "expected an interval >= 1 step (got %ld)", o->every);
  join(sub, sizeof sub, path, "file");
  if (!(v = yt_get(t, n, "file"))) return yt_error(t, n, sub, "expected a file name (got nothing)");
  TRY(yt_string(t, v, sub, o->path, SCENE_PATH_LEN));
  if (exts) {
    const size_t L = strlen(o->path);
    int ok = 0;
    for (int i = 0; exts[i]; i++) {
      const size_t e = strlen(exts[i]);
      ok |= L > e && !strcmp(o->path + L - e, exts[i]);
    }
    if (!ok)
      return yt_error(t, v, sub, "expected a file name ending in %s%s%s (got '%s')", exts[0],
                      exts[1] ? " or " : "", exts[1] ? exts[1] : "", o->path);
  }
  return 0;
}

/* output.flux.phases: species whose own superficial velocity gets a column (docs/scene-format.md);
 * each one counted by the flux (so the phases' q add up to a part of q) and listed once. */
static int parse_flux_phases(ytree_t *t, yaml_node_t *v, scene_t *s) {
  scene_flux_t *f = &s->flux;
  TRY(yt_expect_seq(t, v, "output.flux.phases"));
  if (yt_seq_size(v) < 1)
    return yt_error(t, v, "output.flux.phases",
                    "expected a list of counted species names, e.g. [water, oil] (got an empty "
                    "list)");
  for (int i = 0; i < yt_seq_size(v); i++) {
    char sub[64], name[SCENE_NAME_LEN];
    snprintf(sub, sizeof sub, "output.flux.phases[%d]", i);
    yaml_node_t *item = yt_seq_item(t, v, i);
    TRY(yt_string(t, item, sub, name, sizeof name));
    const int sp = scene_species_index(s, name);
    if (sp < 0)
      return yt_error(t, item, sub, "expected one of the species listed under 'species' (got '%s')",
                      name);
    if (!(f->species_mask >> sp & 1u))
      return yt_error(t, item, sub,
                      "expected a species the flux counts (mobile, and in output.flux.species when "
                      "that is given) (got '%s')",
                      name);
    for (int k = 0; k < f->n_phases; k++)
      if (f->phase_species[k] == sp)
        return yt_error(t, item, sub, "expected each species once (got '%s' twice)", name);
    f->phase_species[f->n_phases++] = sp;
  }
  return 0;
}

/* output.flux: {axis, every, file, species, density, bulk_modulus, phases} (docs/scene-format.md).
 * Checks what the scene alone can tell: the counted species are mobile, and a fluid density is
 * known (from the fill, from geometry.fluid_density, or given). */
static int parse_flux(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"axis",    "every",        "file",   "species",
                                     "density", "bulk_modulus", "phases", NULL};
  static const char *const ext[] = {".csv", ".h5", NULL};
  scene_flux_t *f = &s->flux;
  TRY(yt_check_keys(t, n, "output.flux", keys));
  yaml_node_t *v;
  if ((v = yt_get(t, n, "axis"))) {
    if ((f->axis = yt_enum(t, v, "output.flux.axis", axis_words)) < 0) return -1;
  } else if (s->geometry.on) {
    f->axis = s->geometry.flow_axis;
  } else {
    return yt_error(t, n, "output.flux.axis", "expected x, y or z: the flow axis (got nothing)");
  }
  /* every and file: the same rules as the other periodic outputs */
  if (!(v = yt_get(t, n, "every")))
    return yt_error(t, n, "output.flux.every", "expected an interval in steps (got nothing)");
  TRY(yt_long(t, v, "output.flux.every", &f->every));
  if (f->every < 1)
    return yt_error(t, v, "output.flux.every", "expected an interval >= 1 step (got %ld)",
                    f->every);
  if (!(v = yt_get(t, n, "file")))
    return yt_error(t, n, "output.flux.file", "expected a file name (got nothing)");
  TRY(yt_string(t, v, "output.flux.file", f->path, SCENE_PATH_LEN));
  const size_t L = strlen(f->path);
  int ok = 0;
  for (int i = 0; ext[i]; i++)
    ok |= L > strlen(ext[i]) && !strcmp(f->path + L - strlen(ext[i]), ext[i]);
  if (!ok)
    return yt_error(t, v, "output.flux.file",
                    "expected a file name ending in .csv or .h5 (got '%s')", f->path);
  if ((v = yt_get(t, n, "species"))) {
    TRY(yt_expect_seq(t, v, "output.flux.species"));
    if (yt_seq_size(v) < 1)
      return yt_error(t, v, "output.flux.species",
                      "expected a list of mobile species names (got an empty list)");
    for (int i = 0; i < yt_seq_size(v); i++) {
      char sub[64], name[SCENE_NAME_LEN];
      snprintf(sub, sizeof sub, "output.flux.species[%d]", i);
      yaml_node_t *item = yt_seq_item(t, v, i);
      TRY(yt_string(t, item, sub, name, sizeof name));
      const int sp = scene_species_index(s, name);
      if (sp < 0)
        return yt_error(t, item, sub,
                        "expected one of the species listed under 'species' (got '%s')", name);
      if (s->species[sp].frozen)
        return yt_error(t, item, sub, "expected a mobile species (got '%s', which is frozen)",
                        name);
      f->species_mask |= 1u << sp;
    }
  } else {
    for (int sp = 0; sp < s->n_species; sp++)
      if (!s->species[sp].frozen) f->species_mask |= 1u << sp;
    if (!f->species_mask)
      return yt_error(t, n, "output.flux",
                      "expected a scene with a mobile species to count (got only frozen ones)");
  }
  if ((v = yt_get(t, n, "phases"))) TRY(parse_flux_phases(t, v, s));
  if ((v = yt_get(t, n, "bulk_modulus"))) {
    TRY(yt_double(t, v, "output.flux.bulk_modulus", &f->bulk_modulus));
    if (!(f->bulk_modulus > 0) || !isfinite(f->bulk_modulus))
      return yt_error(t, v, "output.flux.bulk_modulus",
                      "expected the liquid's bulk modulus K = n dp/dn > 0 in kT / rc^3 (about 310 "
                      "for the standard mDPD water at n = 6.2) (got %g)",
                      f->bulk_modulus);
  }
  if ((v = yt_get(t, n, "density"))) {
    TRY(yt_double(t, v, "output.flux.density", &f->density));
    if (!(f->density > 0))
      return yt_error(t, v, "output.flux.density", "expected a number density > 0 (got %g)",
                      f->density);
  } else if (s->init.kind == INIT_FILL && s->init.n_fill > 0) {
    for (int sp = 0; sp < s->n_species; sp++) {
      if (!(f->species_mask >> sp & 1u)) continue;
      int filled = 0;
      for (int k = 0; k < s->init.n_fill; k++) filled |= s->init.fill[k].species == sp;
      if (!filled)
        return yt_error(t, n, "output.flux.density",
                        "expected the fluid number density: species '%s' is counted but no "
                        "initial.fill region holds it (got nothing)",
                        s->species[sp].name);
    }
  } else if (!s->geometry.on) {
    return yt_error(t, n, "output.flux.density",
                    "expected the fluid number density n of the flux (the initial configuration, "
                    "a LAMMPS data file, snapshot or checkpoint, does not give one) (got nothing)");
  }
  return 0;
}

/* output.profile.radial: {shape: cylinder|sphere, centre, rmax, centre_species}. */
static int parse_profile_radial(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"shape", "centre", "rmax", "centre_species", NULL};
  static const char *const shapes[] = {"cylinder", "sphere", NULL};
  const char *path = "output.profile.radial";
  scene_profile_t *p = &s->profile;
  yaml_node_t *w;
  TRY(yt_expect_map(t, n, path));
  TRY(yt_check_keys(t, n, path, keys));
  if (!(w = yt_get(t, n, "shape")))
    return yt_error(t, n, "output.profile.radial.shape",
                    "expected cylinder or sphere (got nothing)");
  if ((p->radial = 1 + yt_enum(t, w, "output.profile.radial.shape", shapes)) < 1) return -1;
  if (!(w = yt_get(t, n, "centre")))
    return yt_error(t, n, "output.profile.radial.centre",
                    "expected a point [x, y, z] (got nothing)");
  TRY(yt_vec3(t, w, "output.profile.radial.centre", p->centre));
  double half = INFINITY;
  for (int d = 0; d < 3; d++) {
    if (p->radial == 1 && d == p->axis) continue;
    const double l = 0.5 * (s->box_hi[d] - s->box_lo[d]);
    if (l < half) half = l;
  }
  if (!(w = yt_get(t, n, "rmax")))
    return yt_error(t, n, "output.profile.radial.rmax", "expected a radius > 0 (got nothing)");
  TRY(yt_double(t, w, "output.profile.radial.rmax", &p->rmax));
  if (!(p->rmax > 0) || p->rmax > half)
    return yt_error(t, w, "output.profile.radial.rmax",
                    "expected 0 < rmax <= %g (half the smallest box edge across the %s; got %g)",
                    half, p->radial == 1 ? "axis" : "box", p->rmax);
  p->centre_species = -1;
  if ((w = yt_get(t, n, "centre_species"))) {
    char name[SCENE_NAME_LEN];
    TRY(yt_string(t, w, "output.profile.radial.centre_species", name, sizeof name));
    p->centre_species = scene_species_index(s, name);
    if (p->centre_species < 0 || s->species[p->centre_species].frozen)
      return yt_error(t, w, "output.profile.radial.centre_species",
                      "expected a mobile species listed under 'species' (got '%s')", name);
  }
  return 0;
}

static int parse_output(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"thermo",  "profile",  "snapshot", "dump", "checkpoint",
                                     "summary", "progress", "flux",     NULL};
  TRY(yt_check_keys(t, n, "output", keys));
  static const char *const thermo_ext[] = {".csv", ".h5", NULL}, *const h5[] = {".h5", NULL};
  yaml_node_t *v;
  if ((v = yt_get(t, n, "thermo")))
    TRY(parse_periodic(t, v, "output.thermo", &s->thermo, thermo_ext));
  if ((v = yt_get(t, n, "snapshot")))
    TRY(parse_periodic(t, v, "output.snapshot", &s->snapshot, NULL));
  if ((v = yt_get(t, n, "dump"))) TRY(parse_periodic(t, v, "output.dump", &s->dump, NULL));
  if ((v = yt_get(t, n, "checkpoint")))
    TRY(parse_periodic(t, v, "output.checkpoint", &s->checkpoint, h5));
  if ((v = yt_get(t, n, "summary")))
    TRY(yt_string(t, v, "output.summary", s->summary_path, SCENE_PATH_LEN));
  if ((v = yt_get(t, n, "progress"))) TRY(yt_bool(t, v, "output.progress", &s->progress));
  if ((v = yt_get(t, n, "profile"))) {
    static const char *const pk[] = {"axis", "bins", "every", "start", "file", "radial", NULL};
    scene_profile_t *p = &s->profile;
    TRY(yt_check_keys(t, v, "output.profile", pk));
    yaml_node_t *w;
    if (!(w = yt_get(t, v, "axis")))
      return yt_error(t, v, "output.profile.axis", "expected x, y or z (got nothing)");
    if ((p->axis = yt_enum(t, w, "output.profile.axis", axis_words)) < 0) return -1;
    long bins = 0;
    if (!(w = yt_get(t, v, "bins")))
      return yt_error(t, v, "output.profile.bins", "expected a number of bins (got nothing)");
    TRY(yt_long(t, w, "output.profile.bins", &bins));
    if (bins < 1 || bins > 100000)
      return yt_error(t, w, "output.profile.bins", "expected 1 to 100000 bins (got %ld)", bins);
    p->nbins = (int)bins;
    p->every = 10;
    if ((w = yt_get(t, v, "every"))) {
      TRY(yt_long(t, w, "output.profile.every", &p->every));
      if (p->every < 1)
        return yt_error(t, w, "output.profile.every", "expected an interval >= 1 (got %ld)",
                        p->every);
    }
    if ((w = yt_get(t, v, "start"))) {
      TRY(yt_long(t, w, "output.profile.start", &p->start));
      if (p->start < 0)
        return yt_error(t, w, "output.profile.start", "expected a step >= 0 (got %ld)", p->start);
    }
    if (!(w = yt_get(t, v, "file")))
      return yt_error(t, v, "output.profile.file", "expected a file name (got nothing)");
    TRY(yt_string(t, w, "output.profile.file", p->path, SCENE_PATH_LEN));
    if ((w = yt_get(t, v, "radial"))) TRY(parse_profile_radial(t, w, s));
  }
  if ((v = yt_get(t, n, "flux"))) TRY(parse_flux(t, v, s));
  return 0;
}

static void set_defaults(scene_t *s) {
  s->kT = 1.0;
  s->vv_lambda = 0.5;
  s->density_kernel = MESO_KERNEL_WARREN;
  s->periodic[0] = s->periodic[1] = s->periodic[2] = 1;
  s->seed = 12345;
  s->progress = 1;
  s->neighbour_skin = -1.0; /* the backend's default (mdpore run --skin) */
  s->init.temperature = -1; /* -> kT after parsing */
  strcpy(s->summary_path, "summary.json");
  scene_guard_defaults(s);
  scene_balance_defaults(s);
}

static int parse_document(ytree_t *t, const scene_catalog_t *cat, scene_t *s) {
  yaml_node_t *root = yt_root(t), *v;
  static const char *const keys[] = {"name",   "box",     "species",  "pairs",   "density_kernel",
                                     "kT",     "effects", "geometry", "initial", "run",
                                     "output", "restart", "guard",    "balance", "units",
                                     "flood",  NULL};
  TRY(yt_check_keys(t, root, "", keys));
  if ((v = yt_get(t, root, "name")))
    TRY(yt_string(t, v, "name", s->name, SCENE_NAME_LEN));
  else {
    char tmp[SCENE_PATH_LEN];
    snprintf(tmp, sizeof tmp, "%s", s->file);
    snprintf(s->name, sizeof s->name, "%s", basename(tmp));
    char *dot = strrchr(s->name, '.');
    if (dot) *dot = 0;
  }
  if (!(v = yt_get(t, root, "box")))
    return yt_error(t, root, "box", "expected a box {lo, hi, periodic} (got nothing)");
  TRY(parse_box(t, v, s));
  if (!(v = yt_get(t, root, "species")))
    return yt_error(t, root, "species",
                    "expected a list of species {name, mass, frozen} (got nothing)");
  TRY(parse_species(t, v, s));
  if ((v = yt_get(t, root, "density_kernel"))) {
    static const char *const kernels[] = {"warren", "lucy", NULL};
    if ((s->density_kernel = yt_enum(t, v, "density_kernel", kernels)) < 0) return -1;
    s->density_kernel = s->density_kernel == 1 ? MESO_KERNEL_LUCY : MESO_KERNEL_WARREN;
  }
  if ((v = yt_get(t, root, "kT"))) {
    TRY(yt_double(t, v, "kT", &s->kT));
    if (!(s->kT > 0)) return yt_error(t, v, "kT", "expected kT > 0 (got %g)", s->kT);
  }
  if (!(v = yt_get(t, root, "effects")))
    return yt_error(t, root, "effects", "expected a mapping of effect names (got nothing)");
  TRY(parse_effects(t, v, cat, s));

  pair_in_t pin[SCENE_MAX_SPECIES][SCENE_MAX_SPECIES];
  memset(pin, 0, sizeof pin);
  yaml_node_t *pairs = yt_get(t, root, "pairs");
  if (pairs) TRY(parse_pairs(t, pairs, s, pin));
  TRY(finish_pairs(t, pairs ? pairs : root, cat, s, pin));

  if ((v = yt_get(t, root, "run")))
    TRY(parse_run(t, v, s));
  else
    return yt_error(t, root, "run", "expected run settings {dt, steps, seed} (got nothing)");

  if ((v = yt_get(t, root, "restart"))) {
    char p[SCENE_PATH_LEN];
    TRY(yt_string(t, v, "restart", p, sizeof p));
    if (scene_relative_path(s->file, p, s->restart_from, sizeof s->restart_from))
      return yt_error(t, v, "restart",
                      "expected a path that, joined to the scene's folder, is shorter than %d "
                      "characters",
                      SCENE_PATH_LEN);
  }
  if ((v = yt_get(t, root, "geometry"))) TRY(scene_parse_geometry(t, v, s));
  if ((v = yt_get(t, root, "initial")))
    TRY(parse_initial(t, v, s));
  else if (s->geometry.on)
    s->init.kind = INIT_GEOMETRY;
  else if (!s->restart_from[0])
    return yt_error(t, root, "initial",
                    "expected an initial configuration (fill, lammps_data or snapshot), a "
                    "'geometry' image or a 'restart' checkpoint (got none of them)");
  if (s->init.temperature < 0) s->init.temperature = s->kT;

  if ((v = yt_get(t, root, "output"))) TRY(parse_output(t, v, s));
  if ((v = yt_get(t, root, "guard"))) TRY(scene_parse_guard(t, v, s));
  if ((v = yt_get(t, root, "flood"))) {
    TRY(yt_expect_map(t, v, "flood"));
    TRY(scene_parse_flood(t, v, s));
  }
  if ((v = yt_get(t, root, "balance"))) TRY(scene_parse_balance(t, v, s));
  if ((v = yt_get(t, root, "units"))) TRY(scene_parse_units(t, v, s));
  if (s->target_error > 0 && s->flux.every == 0)
    return yt_error(t, node_at(t, "run.target_error"), "run.target_error",
                    "expected output.flux as well: the target is the relative error of the flux q "
                    "(got no output.flux)");
  return check_effects(t, cat, s);
}

/* Bytes per cell of a cell list (bin start and count) and per particle (state, forces, ghosts and
 * neighbour bins): the estimates the scene's sizes are checked with before anything is built. */
#define SCENE_BYTES_PER_CELL 8.0
#define SCENE_BYTES_PER_PARTICLE 256.0

/* The cell grid at the largest pair cutoff and the fill's particle count, checked before the run
 * allocates them (docs/scene-format.md, "Sizes"). */
static int check_sizes(ytree_t *t, const scene_t *s) {
  double rcut = 0.0;
  for (int a = 0; a < s->n_species; a++)
    for (int b = 0; b < s->n_species; b++) {
      if (s->pair[a][b].rc > rcut) rcut = s->pair[a][b].rc;
      if (s->pair[a][b].rd > rcut) rcut = s->pair[a][b].rd;
    }
  if (!(rcut > 0)) rcut = 1.0;
  char why[320];
  const double cells = mdp_cell_count(s->box_lo, s->box_hi, rcut);
  if (mdp_size_check(cells, 2147483646.0, SCENE_BYTES_PER_CELL, "cells of the cell grid", why,
                     sizeof why))
    return yt_error(t, node_at(t, "box.hi"), "box.hi",
                    "expected a box the cell grid of cutoff %g fits on one rank (%s)", rcut, why);
  double particles = 0.0;
  for (int i = 0; i < s->init.n_fill; i++) {
    const scene_fill_t *f = &s->init.fill[i];
    particles += f->density * (f->hi[0] - f->lo[0]) * (f->hi[1] - f->lo[1]) * (f->hi[2] - f->lo[2]);
  }
  if (mdp_size_check(particles, 2147483646.0, SCENE_BYTES_PER_PARTICLE, "particles of the fill",
                     why, sizeof why))
    return yt_error(t, node_at(t, "initial.fill"), "initial.fill",
                    "expected a fill that fits in memory (density x region volume; %s)", why);
  return 0;
}

/* No output names an input (the scene, its image, patch database or initial configuration) or
 * another output. Resuming from the scene's own checkpoint is allowed. */
static int check_output_paths(ytree_t *t, const scene_t *s) {
  enum { NOUT = 9 };
  const char *outs[NOUT] = {s->thermo.every ? s->thermo.path : NULL,
                            s->profile.every ? s->profile.path : NULL,
                            s->snapshot.every ? s->snapshot.path : NULL,
                            s->dump.every ? s->dump.path : NULL,
                            s->checkpoint.every ? s->checkpoint.path : NULL,
                            s->flux.every ? s->flux.path : NULL,
                            s->summary_path,
                            s->flood.on ? s->flood.path : NULL,
                            s->flood.on && s->flood.profile_path[0] ? s->flood.profile_path : NULL};
  static const char *const out_keys[NOUT] = {
      "output.thermo", "output.profile", "output.snapshot", "output.dump",  "output.checkpoint",
      "output.flux",   "output.summary", "flood.file",      "flood.profile"};
  const int has_init = s->init.kind == INIT_LAMMPS_DATA || s->init.kind == INIT_SNAPSHOT;
  const char *ins[4] = {s->file, has_init ? s->init.path : "",
                        s->geometry.on ? s->geometry.image : "",
                        s->geometry.on ? s->geometry.patches : ""};
  static const char *const in_keys[4] = {"the scene file", "initial", "geometry.image",
                                         "geometry.patches.file"};
  char why[2600];
  for (int i = 0; i < NOUT; i++) {
    const char *one[1] = {outs[i]}, *one_key[1] = {out_keys[i]};
    if (mdp_check_outputs(one, one_key, 1, ins, in_keys, 4, why, sizeof why) ||
        mdp_check_outputs(outs, out_keys, i + 1, NULL, NULL, 0, why, sizeof why))
      return yt_error(t, node_at(t, out_keys[i]), out_keys[i], "%s", why);
  }
  return 0;
}

int scene_parse_file(const char *path, const scene_catalog_t *catalog, scene_t *scene) {
  int rank = 0, inited = 0;
  MPI_Initialized(&inited);
  if (inited) MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  memset(scene, 0, sizeof *scene);
  if (strlen(path) >= SCENE_PATH_LEN) {
    if (rank == 0) fprintf(stderr, "%s: scene path too long\n", path);
    return -1;
  }
  strcpy(scene->file, path);
  set_defaults(scene);
  ytree_t t;
  if (yt_load(&t, path, rank != 0)) return -1;
  int rc = parse_document(&t, catalog, scene);
  if (rc == 0) rc = check_sizes(&t, scene);
  if (rc == 0) rc = check_output_paths(&t, scene);
  yt_free(&t);
  return rc;
}
