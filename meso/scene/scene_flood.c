/* The `flood:` block (scene_flood.h). */
#include "scene/scene_flood.h"
#include "common/size_check.h"

#include <math.h>
#include <string.h>

#define TRY(x)                                                                                     \
  do {                                                                                             \
    if ((x) != 0) return -1;                                                                       \
  } while (0)

/* the maps' arrays per cell while a frame is built: two counts and the saturation */
#define FLOOD_MAP_BYTES_PER_CELL 16.0
/* the profile's arrays per bin: two counts on every rank */
#define FLOOD_BYTES_PER_BIN 16.0

/* [lo, hi] inside the box along `axis`, lo < hi. */
static int slab(ytree_t *t, yaml_node_t *v, const char *path, const scene_t *s, int axis,
                double *lo, double *hi) {
  if (yt_expect_seq(t, v, path)) return -1;
  if (yt_seq_size(v) != 2)
    return yt_error(t, v, path, "expected a list of two numbers [lo, hi] (got %d items)",
                    yt_seq_size(v));
  TRY(yt_double(t, yt_seq_item(t, v, 0), path, lo));
  TRY(yt_double(t, yt_seq_item(t, v, 1), path, hi));
  if (!(*hi > *lo && *lo >= s->box_lo[axis] && *hi <= s->box_hi[axis]))
    return yt_error(t, v, path, "expected lo < hi inside the box along %c, [%g, %g] (got [%g, %g])",
                    'x' + axis, s->box_lo[axis], s->box_hi[axis], *lo, *hi);
  return 0;
}

/* A mobile species by name. */
static int liquid(ytree_t *t, yaml_node_t *v, const char *path, const scene_t *s, int *out) {
  char name[SCENE_NAME_LEN];
  TRY(yt_string(t, v, path, name, sizeof name));
  *out = scene_species_index(s, name);
  if (*out < 0) return yt_error(t, v, path, "expected the name of a species (got '%s')", name);
  if (s->species[*out].frozen)
    return yt_error(t, v, path, "expected a mobile (liquid) species (got the frozen '%s')", name);
  return 0;
}

static int positive(ytree_t *t, yaml_node_t *n, const char *key, const char *path, double *out) {
  yaml_node_t *v = yt_get(t, n, key);
  if (!v) return 0;
  TRY(yt_double(t, v, path, out));
  if (!(*out > 0 && isfinite(*out)))
    return yt_error(t, v, path, "expected a finite value > 0 (got %g)", *out);
  return 0;
}

static int steps_at_least(ytree_t *t, yaml_node_t *n, const char *key, const char *path, long min,
                          long *out) {
  yaml_node_t *v = yt_get(t, n, key);
  if (!v) return 0;
  TRY(yt_long(t, v, path, out));
  if (*out < min) return yt_error(t, v, path, "expected steps >= %ld (got %ld)", min, *out);
  return 0;
}

static int parse_maps(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"every", "cell", "file", NULL};
  scene_flood_t *f = &s->flood;
  TRY(yt_check_keys(t, n, "flood.maps", keys));
  f->map_every = 1;
  f->map_cell = 1.0;
  strcpy(f->map_path, "flood_maps");
  TRY(steps_at_least(t, n, "every", "flood.maps.every", 1, &f->map_every));
  TRY(positive(t, n, "cell", "flood.maps.cell", &f->map_cell));
  yaml_node_t *v;
  if ((v = yt_get(t, n, "file"))) TRY(yt_string(t, v, "flood.maps.file", f->map_path, 200));
  double cells = 1.0;
  for (int d = 0; d < 3; d++) cells *= ceil((s->box_hi[d] - s->box_lo[d]) / f->map_cell);
  char why[256];
  if (mdp_size_check(cells, 2147483646.0, FLOOD_MAP_BYTES_PER_CELL, "cells of the saturation maps",
                     why, sizeof why))
    return yt_error(t, yt_get(t, n, "cell") ? yt_get(t, n, "cell") : n, "flood.maps.cell",
                    "expected a cell edge whose cells over the box fit (%s) (got %g rc)", why,
                    f->map_cell);
  return 0;
}

int scene_parse_flood(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {
      "along", "sample",  "sink", "invading", "defending", "start",   "every",        "bins",
      "file",  "profile", "maps", "density",  "viscosity", "tension", "breakthrough", NULL};
  static const char *const axis_words[] = {"x", "y", "z", NULL};
  TRY(yt_check_keys(t, n, "flood", keys));
  if (s->restart_from[0])
    return yt_error(t, n, "flood",
                    "expected a run from its first step: a flood is not resumed from a checkpoint "
                    "(its recovery and injected volume count from its start; got 'restart')");
  scene_flood_t *f = &s->flood;
  memset(f, 0, sizeof *f);
  f->every = 100;
  f->nbins = 20;
  f->breakthrough = 0.1;
  strcpy(f->path, "flood.csv");
  yaml_node_t *v;
  if (!(v = yt_need(t, n, "along", "flood.along", "x|y|z: the flow axis"))) return -1;
  if ((f->axis = yt_enum(t, v, "flood.along", axis_words)) < 0) return -1;
  const int a = f->axis;
  if (!s->periodic[a])
    return yt_error(t, v, "flood.along",
                    "expected a periodic axis (the injection side wraps round to the sample's "
                    "inlet; got the non-periodic %c)",
                    'x' + a);
  if (!(v = yt_need(t, n, "sample", "flood.sample", "[lo, hi]: the sample's faces"))) return -1;
  TRY(slab(t, v, "flood.sample", s, a, &f->sample_lo, &f->sample_hi));
  if (!(v = yt_need(t, n, "sink", "flood.sink", "[lo, hi]: the sink slab"))) return -1;
  TRY(slab(t, v, "flood.sink", s, a, &f->sink_lo, &f->sink_hi));
  const double L = s->box_hi[a] - s->box_lo[a];
  if (scene_circle_overlap(f->sink_lo, f->sink_hi, f->sample_lo, f->sample_hi, L) > 0 ||
      f->sample_hi - f->sample_lo + f->sink_hi - f->sink_lo >= L)
    return yt_error(t, v, "flood.sink",
                    "expected a slab outside the sample [%g, %g] with room on both sides (got "
                    "[%g, %g])",
                    f->sample_lo, f->sample_hi, f->sink_lo, f->sink_hi);
  if (!(v = yt_need(t, n, "invading", "flood.invading", "the injected liquid's species")))
    return -1;
  TRY(liquid(t, v, "flood.invading", s, &f->invading));
  if (!(v = yt_need(t, n, "defending", "flood.defending", "the displaced liquid's species")))
    return -1;
  TRY(liquid(t, v, "flood.defending", s, &f->defending));
  if (f->invading == f->defending)
    return yt_error(t, v, "flood.defending",
                    "expected a species other than the invading one (got '%s' for both)",
                    s->species[f->invading].name);
  if (s->species[f->invading].mass != s->species[f->defending].mass)
    return yt_error(t, v, "flood.defending",
                    "expected the mass of the invading liquid (%g): a particle changes species at "
                    "the sink, keeping its velocity (got %g)",
                    s->species[f->invading].mass, s->species[f->defending].mass);
  TRY(steps_at_least(t, n, "start", "flood.start", 0, &f->start));
  TRY(steps_at_least(t, n, "every", "flood.every", 1, &f->every));
  if ((v = yt_get(t, n, "bins"))) {
    long bins;
    TRY(yt_long(t, v, "flood.bins", &bins));
    char why[256];
    if (bins < 1 || mdp_size_check((double)bins, 1e7, FLOOD_BYTES_PER_BIN, "bins", why, sizeof why))
      return yt_error(t, v, "flood.bins", "expected 1 to 10^7 bins across the sample (got %ld)",
                      bins);
    f->nbins = (int)bins;
  }
  if ((v = yt_get(t, n, "breakthrough"))) {
    TRY(yt_double(t, v, "flood.breakthrough", &f->breakthrough));
    if (!(f->breakthrough > 0 && f->breakthrough < 1))
      return yt_error(t, v, "flood.breakthrough",
                      "expected the invading saturation of the sample's last bin that marks "
                      "breakthrough, 0 < S < 1 (got %g)",
                      f->breakthrough);
  }
  TRY(positive(t, n, "density", "flood.density", &f->density));
  TRY(positive(t, n, "viscosity", "flood.viscosity", &f->viscosity));
  TRY(positive(t, n, "tension", "flood.tension", &f->tension));
  if ((v = yt_get(t, n, "file"))) TRY(yt_string(t, v, "flood.file", f->path, SCENE_PATH_LEN));
  if ((v = yt_get(t, n, "profile")))
    TRY(yt_string(t, v, "flood.profile", f->profile_path, SCENE_PATH_LEN));
  if ((v = yt_get(t, n, "maps"))) {
    if (yt_expect_map(t, v, "flood.maps")) return -1;
    TRY(parse_maps(t, v, s));
  }
  f->on = 1;
  return 0;
}
