/* The `geometry:` block: image, label map, scale, axis map, flow axis, wall and fluid parameters,
 * species of each phase, patch database (scene_geometry.h). */
#include "scene/scene_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TRY(x)                                                                                     \
  do {                                                                                             \
    if ((x) != 0) return -1;                                                                       \
  } while (0)

static const char *const axis_words[] = {"x", "y", "z", NULL};

/* A positive number at key `key` of map n, into *out (left alone when absent). */
static int positive(ytree_t *t, yaml_node_t *n, const char *key, double *out, int allow_zero) {
  yaml_node_t *v = yt_get(t, n, key);
  if (!v) return 0;
  char path[96];
  snprintf(path, sizeof path, "geometry.%s", key);
  TRY(yt_double(t, v, path, out));
  if (!(*out > 0 || (allow_zero && *out == 0)))
    return yt_error(t, v, path, "expected a number %s 0 (got %g)", allow_zero ? ">=" : ">", *out);
  return 0;
}

static int species_of(ytree_t *t, yaml_node_t *m, const char *key, const scene_t *s, int *out) {
  yaml_node_t *v = yt_get(t, m, key);
  if (!v) return 0;
  char path[96], name[SCENE_NAME_LEN];
  snprintf(path, sizeof path, "geometry.species.%s", key);
  TRY(yt_string(t, v, path, name, sizeof name));
  if ((*out = scene_species_index(s, name)) < 0)
    return yt_error(t, v, path, "expected one of the species listed under 'species' (got '%s')",
                    name);
  return 0;
}

/* A region {lo: [x, y, z], hi: [x, y, z]} in rc, the box frame, at key `path` (map n): an
 * axis-aligned box inside the scene's box (parsed before `geometry`) with hi > lo on every axis. */
static int parse_region(ytree_t *t, yaml_node_t *n, const scene_t *s, const char *path,
                        const char *const *keys, double lo_out[3], double hi_out[3]) {
  char key_lo[96], key_hi[96];
  snprintf(key_lo, sizeof key_lo, "%s.lo", path);
  snprintf(key_hi, sizeof key_hi, "%s.hi", path);
  TRY(yt_expect_map(t, n, path));
  TRY(yt_check_keys(t, n, path, keys));
  yaml_node_t *lo = yt_get(t, n, "lo"), *hi = yt_get(t, n, "hi");
  if (!lo || !hi)
    return yt_error(t, n, lo ? key_hi : key_lo,
                    "expected both corners of the region, {lo: [x, y, z], hi: [x, y, z]} in rc "
                    "(got no '%s')",
                    lo ? "hi" : "lo");
  TRY(yt_vec3(t, lo, key_lo, lo_out));
  TRY(yt_vec3(t, hi, key_hi, hi_out));
  for (int d = 0; d < 3; d++) {
    const double tol = 1e-9 * (s->box_hi[d] - s->box_lo[d]);
    if (!(hi_out[d] > lo_out[d]))
      return yt_error(t, hi, key_hi,
                      "expected hi > lo on every axis (got hi %c = %g <= lo %c = %g)", "xyz"[d],
                      hi_out[d], "xyz"[d], lo_out[d]);
    const int below = !(lo_out[d] >= s->box_lo[d] - tol);
    if (below || !(hi_out[d] <= s->box_hi[d] + tol))
      return yt_error(t, below ? lo : hi, below ? key_lo : key_hi,
                      "expected a region inside the box, %g <= %c <= %g (got %s %c = %g)",
                      s->box_lo[d], "xyz"[d], s -> box_hi[d], below ? "lo" : "hi", "xyz"[d],
                      below ? lo_out[d] : hi_out[d]);
  }
  return 0;
}

/* geometry.fluid_region: {lo, hi}: fluid only inside this box. */
static int parse_fluid_region(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"lo", "hi", NULL};
  scene_geometry_t *g = &s->geometry;
  TRY(parse_region(t, n, s, "geometry.fluid_region", keys, g->fluid_lo, g->fluid_hi));
  g->fluid_region = 1;
  return 0;
}

/* geometry.fluid_species_regions: a list of {species, lo, hi, cylinder | sphere, outside}; the
 * builder's fluid particles inside a region (the first that holds one) take its species. Each
 * species is mobile and as heavy as geometry.species.fluid: the builder removes the centre-of-mass
 * velocity summed over the fluid's ids with one mass (populate/init_config.c). lo and hi default
 * to the box. */
static int parse_species_regions(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"species", "lo", "hi", "cylinder", "sphere", "outside", NULL};
  scene_geometry_t *g = &s->geometry;
  TRY(yt_expect_seq(t, n, "geometry.fluid_species_regions"));
  const int count = yt_seq_size(n);
  if (count < 1 || count > SCENE_MAX_FILLS)
    return yt_error(t, n, "geometry.fluid_species_regions",
                    "expected a list of 1 to %d regions (got %d)", SCENE_MAX_FILLS, count);
  for (int i = 0; i < count; i++) {
    char path[64], sub[96], name[SCENE_NAME_LEN];
    snprintf(path, sizeof path, "geometry.fluid_species_regions[%d]", i);
    yaml_node_t *item = yt_seq_item(t, n, i), *v;
    TRY(yt_expect_map(t, item, path));
    TRY(yt_check_keys(t, item, path, keys));
    scene_fill_t *f = &g->species_region[i];
    memset(f, 0, sizeof *f);
    memcpy(f->lo, s->box_lo, sizeof f->lo);
    memcpy(f->hi, s->box_hi, sizeof f->hi);
    snprintf(sub, sizeof sub, "%s.species", path);
    if (!(v = yt_get(t, item, "species")))
      return yt_error(t, item, sub, "expected a species name (got nothing)");
    TRY(yt_string(t, v, sub, name, sizeof name));
    if ((f->species = scene_species_index(s, name)) < 0)
      return yt_error(t, v, sub, "expected one of the species listed under 'species' (got '%s')",
                      name);
    const scene_species_t *sp = &s->species[f->species], *fl = &s->species[g->fluid_species];
    if (sp->frozen)
      return yt_error(t, v, sub, "expected a species that is not frozen (got '%s', frozen)", name);
    if (sp->mass != fl->mass)
      return yt_error(t, v, sub,
                      "expected a species as heavy as the fluid '%s' (mass %g) (got '%s', mass %g)",
                      fl->name, fl->mass, name, sp->mass);
    for (int c = 0; c < 2; c++) {
      const char *k = c ? "hi" : "lo";
      double *x = c ? f->hi : f->lo;
      if (!(v = yt_get(t, item, k))) continue;
      snprintf(sub, sizeof sub, "%s.%s", path, k);
      TRY(yt_vec3(t, v, sub, x));
    }
    for (int d = 0; d < 3; d++)
      if (!(f->hi[d] > f->lo[d])) {
        snprintf(sub, sizeof sub, "%s.hi", path);
        return yt_error(t, item, sub,
                        "expected hi > lo on every axis (got hi %c = %g <= lo %c = %g)", "xyz"[d],
                        f -> hi[d], "xyz"[d], f -> lo[d]);
      }
    TRY(scene_parse_fill_shape(t, item, path, s, f));
  }
  g->n_species_regions = count;
  return 0;
}

/* A species for fluid particles at key `path` (node v): listed, mobile and as heavy as
 * geometry.species.fluid (the builder removes the centre-of-mass velocity summed over the fluid's
 * ids with one mass, populate/init_config.c). */
static int fluid_like_species(ytree_t *t, yaml_node_t *v, const char *path, const scene_t *s,
                              int *out) {
  char name[SCENE_NAME_LEN];
  TRY(yt_string(t, v, path, name, sizeof name));
  if ((*out = scene_species_index(s, name)) < 0)
    return yt_error(t, v, path, "expected one of the species listed under 'species' (got '%s')",
                    name);
  const scene_species_t *sp = &s->species[*out], *fl = &s->species[s->geometry.fluid_species];
  if (sp->frozen)
    return yt_error(t, v, path, "expected a species that is not frozen (got '%s', frozen)", name);
  if (sp->mass != fl->mass)
    return yt_error(t, v, path,
                    "expected a species as heavy as the fluid '%s' (mass %g) (got '%s', mass %g)",
                    fl->name, fl->mass, name, sp->mass);
  return 0;
}

/* geometry.fluid_species_labels: {LABEL: species, ...}: the builder's fluid particles in pore
 * voxels of image label LABEL (0..255) take that species. Whether LABEL is pore in the image's
 * label map and present in the image is checked by the builder (populate/image_window.c), which
 * reads the image. */
static int parse_species_labels(ytree_t *t, yaml_node_t *n, scene_t *s) {
  scene_geometry_t *g = &s->geometry;
  TRY(yt_expect_map(t, n, "geometry.fluid_species_labels"));
  const int count = yt_map_size(n);
  if (count < 1 || count > SCENE_MAX_FILLS)
    return yt_error(t, n, "geometry.fluid_species_labels",
                    "expected a map of 1 to %d entries {LABEL: species} (got %d)", SCENE_MAX_FILLS,
                    count);
  for (int i = 0; i < count; i++) {
    yaml_node_t *key = NULL;
    const char *text = yt_map_key(t, n, i, &key);
    char path[96];
    snprintf(path, sizeof path, "geometry.fluid_species_labels.%s", text ? text : "?");
    char *end = NULL;
    const long label = text ? strtol(text, &end, 10) : -1;
    if (!text || end == text || *end || label < 0 || label > 255)
      return yt_error(t, key ? key : n, path,
                      "expected an image label, an integer 0..255 (got '%s')", text ? text : "");
    for (int k = 0; k < i; k++)
      if (g->species_label[k] == (int)label)
        return yt_error(t, key, path, "expected each label once (got %ld twice)", label);
    g->species_label[i] = (int)label;
    TRY(fluid_like_species(t, yt_map_value(t, n, i), path, s, &g->species_label_species[i]));
  }
  g->n_species_labels = count;
  return 0;
}

int scene_parse_geometry(ytree_t *t, yaml_node_t *n, scene_t *s) {
  static const char *const keys[] = {"image",
                                     "labels",
                                     "rc_per_voxel",
                                     "voxels_per_rc",
                                     "axis_map",
                                     "flow_axis",
                                     "wall_thickness",
                                     "wall_density",
                                     "fluid_density",
                                     "min_wall_distance",
                                     "isolated_pores",
                                     "species",
                                     "patches",
                                     "strict",
                                     "fluid_region",
                                     "fluid_species_regions",
                                     "fluid_species_labels",
                                     NULL};
  TRY(yt_check_keys(t, n, "geometry", keys));
  scene_geometry_t *g = &s->geometry;
  memset(g, 0, sizeof *g);
  g->on = 1;
  for (int d = 0; d < 3; d++) g->axis_map[d] = d;
  g->wall_density = 8.0;
  g->fluid_density = 6.2;
  /* 0.25 rc: about the closest approach of two particles in an mDPD liquid at these densities
   * (g(r) is near zero below it) and half the mean spacing of wall particles at density 8; fluid
   * started nearer a wall particle feels the largest forces of the first steps, and this keeps the
   * fill uniform (only a thin skin at the pore surface is redrawn; docs/walls.md). */
  g->min_wall_distance = 0.25;
  g->organic_species = g->inorganic_species = -1;
  g->fluid_species = -1;
  g->patch_seed = 1;
  yaml_node_t *v;
  char text[SCENE_PATH_LEN];
  if (!(v = yt_get(t, n, "image")))
    return yt_error(t, n, "geometry.image", "expected an image file (got nothing)");
  TRY(yt_string(t, v, "geometry.image", text, sizeof text));
  if (scene_relative_path(s->file, text, g->image, sizeof g->image))
    return yt_error(t, v, "geometry.image",
                    "expected a path that, joined to the scene's folder, is shorter than %d "
                    "characters",
                    SCENE_PATH_LEN);
  if ((v = yt_get(t, n, "labels")))
    TRY(yt_string(t, v, "geometry.labels", g->labels, sizeof g->labels));
  yaml_node_t *rpv = yt_get(t, n, "rc_per_voxel"), *vpr = yt_get(t, n, "voxels_per_rc");
  if (!!rpv + !!vpr != 1)
    return yt_error(t, n, "geometry.rc_per_voxel",
                    "expected exactly one of rc_per_voxel and voxels_per_rc (got %d)",
                    !!rpv + !!vpr);
  if (rpv) TRY(positive(t, n, "rc_per_voxel", &g->rc_per_voxel, 0));
  if (vpr) {
    double k = 0;
    TRY(positive(t, n, "voxels_per_rc", &k, 0));
    g->rc_per_voxel = 1.0 / k;
  }
  if ((v = yt_get(t, n, "axis_map"))) {
    TRY(yt_expect_seq(t, v, "geometry.axis_map"));
    if (yt_seq_size(v) != 3)
      return yt_error(
          t, v, "geometry.axis_map",
          "expected three image axes, one per box axis x, y, z, e.g. [x, y, z] (got %d)",
          yt_seq_size(v));
    int used[3] = {0, 0, 0};
    for (int d = 0; d < 3; d++) {
      const int a = yt_enum(t, yt_seq_item(t, v, d), "geometry.axis_map", axis_words);
      if (a < 0) return -1;
      if (used[a]++)
        return yt_error(t, v, "geometry.axis_map", "expected each image axis once (got '%s' twice)",
                        axis_words[a]);
      g->axis_map[d] = a;
    }
  }
  if (!(v = yt_get(t, n, "flow_axis")))
    return yt_error(t, n, "geometry.flow_axis",
                    "expected the box axis the flow goes along, x, y or z (got nothing)");
  if ((g->flow_axis = yt_enum(t, v, "geometry.flow_axis", axis_words)) < 0) return -1;
  TRY(positive(t, n, "wall_thickness", &g->wall_thickness, 0));
  TRY(positive(t, n, "wall_density", &g->wall_density, 0));
  TRY(positive(t, n, "fluid_density", &g->fluid_density, 0));
  TRY(positive(t, n, "min_wall_distance", &g->min_wall_distance, 1));
  if ((v = yt_get(t, n, "isolated_pores"))) {
    static const char *const modes[] = {"empty", "fill", NULL};
    if ((g->isolated_pores = yt_enum(t, v, "geometry.isolated_pores", modes)) < 0) return -1;
  }
  if (!(v = yt_get(t, n, "species")))
    return yt_error(t, n, "geometry.species",
                    "expected {fluid: NAME, inorganic: NAME, organic: NAME} (got nothing)");
  static const char *const sk[] = {"fluid", "organic", "inorganic", NULL};
  TRY(yt_check_keys(t, v, "geometry.species", sk));
  TRY(species_of(t, v, "fluid", s, &g->fluid_species));
  TRY(species_of(t, v, "organic", s, &g->organic_species));
  TRY(species_of(t, v, "inorganic", s, &g->inorganic_species));
  if (g->fluid_species < 0)
    return yt_error(t, v, "geometry.species.fluid", "expected the fluid's species (got nothing)");
  if (s->species[g->fluid_species].frozen)
    return yt_error(t, yt_get(t, v, "fluid"), "geometry.species.fluid",
                    "expected a species that is not frozen (got '%s', frozen)",
                    s->species[g->fluid_species].name);
  if (g->organic_species < 0 && g->inorganic_species < 0)
    return yt_error(t, v, "geometry.species",
                    "expected a wall species for 'organic' or 'inorganic' voxels (got neither)");
  const int walls[2] = {g->organic_species, g->inorganic_species};
  for (int k = 0; k < 2; k++) {
    if (walls[k] < 0) continue;
    if (walls[k] == g->fluid_species || !s->species[walls[k]].frozen)
      return yt_error(t, v, k ? "geometry.species.inorganic" : "geometry.species.organic",
                      "expected a frozen species other than the fluid's (got '%s')",
                      s->species[walls[k]].name);
  }
  if ((v = yt_get(t, n, "strict"))) TRY(yt_bool(t, v, "geometry.strict", &g->strict));
  if ((v = yt_get(t, n, "fluid_region"))) TRY(parse_fluid_region(t, v, s));
  if ((v = yt_get(t, n, "fluid_species_regions"))) TRY(parse_species_regions(t, v, s));
  if ((v = yt_get(t, n, "fluid_species_labels"))) TRY(parse_species_labels(t, v, s));
  if ((v = yt_get(t, n, "patches"))) {
    static const char *const pk[] = {"file", "seed", NULL};
    TRY(yt_check_keys(t, v, "geometry.patches", pk));
    yaml_node_t *w;
    if ((w = yt_get(t, v, "file"))) {
      TRY(yt_string(t, w, "geometry.patches.file", text, sizeof text));
      if (scene_relative_path(s->file, text, g->patches, sizeof g->patches))
        return yt_error(t, w, "geometry.patches.file",
                        "expected a path that, joined to the scene's folder, is shorter than %d "
                        "characters",
                        SCENE_PATH_LEN);
    }
    if ((w = yt_get(t, v, "seed"))) {
      long seed = 0;
      TRY(yt_long(t, w, "geometry.patches.seed", &seed));
      if (seed < 0)
        return yt_error(t, w, "geometry.patches.seed", "expected a seed >= 0 (got %ld)", seed);
      g->patch_seed = (uint64_t)seed;
    }
  }
  return 0;
}

int scene_geometry_read_image(const scene_t *s, mdp_image_t *img, char *err, size_t errlen) {
  const scene_geometry_t *g = &s->geometry;
  char e[MDP_IMAGE_ERR_LEN] = "";
  mdp_image_read_opts_t opts;
  mdp_image_read_opts_init(&opts);
  if (g->labels[0]) snprintf(opts.labels, sizeof opts.labels, "%s", g->labels);
  mdp_image_t raw;
  memset(&raw, 0, sizeof raw);
  memset(img, 0, sizeof *img);
  if (mdp_image_read(g->image, &opts, &raw, e)) {
    snprintf(err, errlen, "%s: key 'geometry.image': %s", s->file, e);
    return -1;
  }
  const int rc = mdp_image_permute_axes(&raw, g->axis_map, img, e);
  mdp_image_free(&raw);
  if (rc) {
    snprintf(err, errlen, "%s: key 'geometry.axis_map': %s", s->file, e);
    return -1;
  }
  const int n[3] = {img->nx, img->ny, img->nz};
  for (int d = 0; d < 3; d++) {
    const double want = n[d] * g->rc_per_voxel, got = s->box_hi[d] - s->box_lo[d];
    if (fabs(got - want) > 1e-9 * want) {
      snprintf(err, errlen,
               "%s: key 'box.hi': expected a box of %g x %g x %g rc (the image's %d x %d x %d "
               "voxels times rc_per_voxel %g, after axis_map) (got %g along %c)",
               s->file, n[0] * g->rc_per_voxel, n[1] * g->rc_per_voxel, n[2] * g->rc_per_voxel,
               n[0], n[1], n[2], g->rc_per_voxel, got, "xyz"[d]);
      mdp_image_free(img);
      return -1;
    }
  }
  return 0;
}

void scene_geometry_grid(const scene_t *s, const mdp_image_t *img, voxel_grid_t *grid) {
  grid->n[0] = img->nx;
  grid->n[1] = img->ny;
  grid->n[2] = img->nz;
  for (int d = 0; d < 3; d++) {
    grid->lo[d] = s->box_lo[d];
    grid->periodic[d] = s->periodic[d];
  }
  grid->inv_h = 1.0 / s->geometry.rc_per_voxel;
}
