/* The scene of one run: the template with the flow axis, the body force, the flux output and the
 * run's budget and target set, paths made absolute, emitted as YAML text (libyaml's emitter).
 *   effects.body_force   {FLUID: [g along the axis]} (FLUID: geometry.species.fluid, or every
 *                        species that is not frozen), replacing any body force of the template
 *   geometry.flow_axis   the axis (scenes with geometry)
 *   output.flux          axis, file flux.csv, every (kept when the template sets it)
 *   output.summary       summary.json; output.progress false
 *   run.target_error     --target-error; run.steps --max-steps (when given); run.dt --dt (when
 *                        given, or from --accuracy); run.seed base + a hash
 *                        of g (independent noise per gradient)
 *                        --target-error-k: no run.target_error, run.steps --round-steps and
 *                        output.checkpoint at the end of the run (campaign_rounds.c continues it)
 *   geometry.image, geometry.patches.file, initial.lammps_data, initial.snapshot: absolute.
 * --drive pressure: box and image grow by the reservoir, effects.inlet_force replaces body_force
 * (pressure_drive below); the same rewrite for an IMAGE's template and a SCENE with a geometry
 * image (campaign_template.c pads either image). --boundary mirror / --sides mirror: the box doubles
 * along the mirrored dimensions and the geometry reads the mirrored image (mirror_geometry). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

#include "campaign.h"
#include "common/yaml_tree.h"

typedef yaml_document_t doc_t;

static int node_id(doc_t *d, yaml_node_t *n) {
  return n ? (int)(n - d->nodes.start) + 1 : 0;
}

static int scalar(doc_t *d, const char *text) {
  return yaml_document_add_scalar(d, NULL, (yaml_char_t *)text, -1, YAML_ANY_SCALAR_STYLE);
}

static int number(doc_t *d, double v) {
  char b[64];
  snprintf(b, sizeof b, "%.15g", v);
  return scalar(d, b);
}

/* Value node id of `key` in mapping `map_id` (0 when absent). */
static int get(doc_t *d, int map_id, const char *key) {
  yaml_node_t *m = yaml_document_get_node(d, map_id);
  if (!m || m->type != YAML_MAPPING_NODE) return 0;
  for (yaml_node_pair_t *p = m->data.mapping.pairs.start; p < m->data.mapping.pairs.top; p++) {
    yaml_node_t *k = yaml_document_get_node(d, p->key);
    if (k && k->type == YAML_SCALAR_NODE && !strcmp((char *)k->data.scalar.value, key))
      return p->value;
  }
  return 0;
}

/* Sets `key` of mapping `map_id` to node `value` (replacing or appending). */
static int set(doc_t *d, int map_id, const char *key, int value) {
  yaml_node_t *m = yaml_document_get_node(d, map_id);
  for (yaml_node_pair_t *p = m->data.mapping.pairs.start; p < m->data.mapping.pairs.top; p++) {
    yaml_node_t *k = yaml_document_get_node(d, p->key);
    if (k && k->type == YAML_SCALAR_NODE && !strcmp((char *)k->data.scalar.value, key)) {
      p->value = value;
      return 0;
    }
  }
  int k = scalar(d, key);
  return yaml_document_append_mapping_pair(d, map_id, k, value) ? 0 : -1;
}

/* The mapping under `key`, made when absent. */
static int child_map(doc_t *d, int map_id, const char *key) {
  int c = get(d, map_id, key);
  yaml_node_t *n = yaml_document_get_node(d, c);
  if (n && n->type == YAML_MAPPING_NODE) return c;
  c = yaml_document_add_mapping(d, NULL, YAML_BLOCK_MAPPING_STYLE);
  set(d, map_id, key, c);
  return c;
}

static const char *text_of(doc_t *d, int id) {
  yaml_node_t *n = yaml_document_get_node(d, id);
  return n && n->type == YAML_SCALAR_NODE ? (const char *)n->data.scalar.value : NULL;
}

/* A relative path value made absolute against the template's folder. */
static void absolutize(doc_t *d, int map_id, const char *key, const char *dir) {
  const char *v = text_of(d, get(d, map_id, key));
  if (!v || v[0] == '/' || !v[0]) return;
  char path[2 * CAMP_PATH];
  snprintf(path, sizeof path, "%s/%s", dir, v);
  set(d, map_id, key, scalar(d, path));
}

/* Appends the emitter's output to a growing buffer. */
typedef struct {
  char *s;
  size_t n, cap;
} sbuf;

static int write_handler(void *data, unsigned char *buffer, size_t size) {
  sbuf *b = data;
  if (b->n + size + 1 > b->cap) {
    size_t cap = 2 * (b->n + size + 1);
    char *s = realloc(b->s, cap);
    if (!s) return 0;
    b->s = s;
    b->cap = cap;
  }
  memcpy(b->s + b->n, buffer, size);
  b->n += size;
  b->s[b->n] = 0;
  return 1;
}

/* Removes `key` from mapping `map_id` (no-op when absent). */
static void unset(doc_t *d, int map_id, const char *key) {
  yaml_node_t *m = yaml_document_get_node(d, map_id);
  if (!m || m->type != YAML_MAPPING_NODE) return;
  for (yaml_node_pair_t *p = m->data.mapping.pairs.start; p < m->data.mapping.pairs.top; p++) {
    yaml_node_t *k = yaml_document_get_node(d, p->key);
    if (k && k->type == YAML_SCALAR_NODE && !strcmp((char *)k->data.scalar.value, key)) {
      memmove(p, p + 1, (size_t)(m->data.mapping.pairs.top - p - 1) * sizeof *p);
      m->data.mapping.pairs.top--;
      return;
    }
  }
}

static int pair_of_numbers(doc_t *d, double a, double b) {
  int seq = yaml_document_add_sequence(d, NULL, YAML_FLOW_SEQUENCE_STYLE);
  yaml_document_append_sequence_item(d, seq, number(d, a));
  yaml_document_append_sequence_item(d, seq, number(d, b));
  return seq;
}

/* The mirror treatments (campaign_boundary.c): the box doubles along every mirrored dimension
 * (the flow axis for --boundary mirror, the lateral axes for --sides mirror) and the geometry reads
 * the mirrored image, already in the box frame. A wall patch file or a fluid region belongs to the
 * unmirrored box and is refused. */
static int mirror_geometry(doc_t *d, int root, const camp_opts *o, int axis,
                           const char *template_path) {
  int any = 0;
  for (int k = 0; k < 3; k++) any |= camp_mirrored_along(o, axis, k);
  if (!any) return 0;
  int geo = get(d, root, "geometry"), box = get(d, root, "box");
  const char *refused = !geo                          ? "geometry.image"
                        : get(d, geo, "patches")      ? "geometry.patches"
                        : get(d, geo, "fluid_region") ? "geometry.fluid_region"
                                                      : NULL;
  if (refused) {
    fprintf(stderr,
            "mdpore permeability: %s: key '%s': the mirror treatment (--boundary mirror or "
            "--sides mirror) mirrors the geometry's image and needs %s; give --boundary "
            "periodic|reservoir and --sides periodic for this scene\n",
            template_path, refused,
            !geo ? "one" : "neither a patch file nor a fluid region of the unmirrored box");
    return -1;
  }
  yaml_node_t *lo_n = yaml_document_get_node(d, get(d, box, "lo"));
  yaml_node_t *hi_n = yaml_document_get_node(d, get(d, box, "hi"));
  if (!lo_n || !hi_n || lo_n->type != YAML_SEQUENCE_NODE || hi_n->type != YAML_SEQUENCE_NODE ||
      hi_n->data.sequence.items.top - hi_n->data.sequence.items.start != 3 ||
      lo_n->data.sequence.items.top - lo_n->data.sequence.items.start != 3) {
    fprintf(stderr, "mdpore permeability: %s: key 'box': expected lo and hi lists of 3 numbers\n",
            template_path);
    return -1;
  }
  int hi_new = yaml_document_add_sequence(d, NULL, YAML_FLOW_SEQUENCE_STYLE);
  for (int k = 0; k < 3; k++) {
    const double lo = atof(text_of(d, lo_n->data.sequence.items.start[k]));
    const double hi = atof(text_of(d, hi_n->data.sequence.items.start[k]));
    yaml_document_append_sequence_item(
        d, hi_new, number(d, camp_mirrored_along(o, axis, k) ? lo + 2 * (hi - lo) : hi));
  }
  set(d, box, "hi", hi_new);
  if (o->boundary_of_axis[axis] != CAMP_BOUNDARY_RESERVOIR) { /* the reservoir sets its own */
    char image[CAMP_PATH];
    camp_mirror_image_path(o, axis, image, sizeof image);
    set(d, geo, "image", scalar(d, image));
    unset(d, geo, "axis_map"); /* the mirrored image was written in the box frame */
  }
  return 0;
}

/* Pressure drive (docs/permeability.md): the box grows by the reservoir along the axis, the
 * geometry reads the padded image, the body force goes and inlet_force acts in the middle of the
 * reservoir, between probe slabs next to the sample faces:
 *   sample [lo, lo + Ls), reservoir [lo + Ls, lo + Ls + R), slab [lo + Ls + gap + w, lo + Ls + R -
 *   gap - w), force per particle f = g Ls / L_slab. */
static int pressure_drive(doc_t *d, int root, int effects, const camp_opts *o, int axis, double g,
                          const char (*fluid)[256], int nf, const char *template_path) {
  int box = get(d, root, "box");
  yaml_node_t *lo_n = yaml_document_get_node(d, get(d, box, "lo"));
  yaml_node_t *hi_n = yaml_document_get_node(d, get(d, box, "hi"));
  if (!lo_n || !hi_n || lo_n->type != YAML_SEQUENCE_NODE || hi_n->type != YAML_SEQUENCE_NODE ||
      hi_n->data.sequence.items.top - hi_n->data.sequence.items.start != 3) {
    fprintf(stderr, "mdpore permeability: %s: key 'box': expected lo and hi lists of 3 numbers\n",
            template_path);
    return -1;
  }
  double lo[3], hi[3];
  for (int k = 0; k < 3; k++) {
    lo[k] = atof(text_of(d, lo_n->data.sequence.items.start[k]));
    hi[k] = atof(text_of(d, hi_n->data.sequence.items.start[k]));
  }
  const double ls = hi[axis] - lo[axis], r = camp_reservoir_voxels(o) * o->rc_per_voxel;
  const double gw = CAMP_PROBE_GAP + CAMP_PROBE_WIDTH;
  const double slab_lo = lo[axis] + ls + gw, slab_hi = lo[axis] + ls + r - gw;
  if (!(slab_hi - slab_lo >= 0.5)) {
    fprintf(stderr,
            "mdpore permeability: --reservoir %g: expected room for the inlet slab between the "
            "probes (the reservoir is %g rc in whole voxels)\n",
            o->reservoir, r);
    return -1;
  }
  int hi_new = yaml_document_add_sequence(d, NULL, YAML_FLOW_SEQUENCE_STYLE);
  for (int k = 0; k < 3; k++)
    yaml_document_append_sequence_item(d, hi_new, number(d, k == axis ? hi[k] + r : hi[k]));
  set(d, box, "hi", hi_new);
  char image[CAMP_PATH];
  camp_padded_image_path(o, axis, image, sizeof image);
  int geo = get(d, root, "geometry");
  set(d, geo, "image", scalar(d, image));
  unset(d, geo, "axis_map"); /* the padded image was written in the box frame */
  unset(d, effects, "body_force");
  const double f = g * ls / (slab_hi - slab_lo);
  int inlet = yaml_document_add_mapping(d, NULL, YAML_FLOW_MAPPING_STYLE);
  for (int i = 0; i < nf; i++) {
    int vec = yaml_document_add_sequence(d, NULL, YAML_FLOW_SEQUENCE_STYLE);
    for (int c = 0; c < 3; c++)
      yaml_document_append_sequence_item(d, vec, number(d, c == axis ? f : 0));
    yaml_document_append_mapping_pair(d, inlet, scalar(d, fluid[i]), vec);
  }
  const char axis_name[2] = {(char)('x' + axis), 0};
  yaml_document_append_mapping_pair(d, inlet, scalar(d, "along"), scalar(d, axis_name));
  yaml_document_append_mapping_pair(d, inlet, scalar(d, "slab"),
                                    pair_of_numbers(d, slab_lo, slab_hi));
  yaml_document_append_mapping_pair(d, inlet, scalar(d, "sample"),
                                    pair_of_numbers(d, lo[axis], lo[axis] + ls));
  yaml_document_append_mapping_pair(d, inlet, scalar(d, "probe_gap"), number(d, CAMP_PROBE_GAP));
  yaml_document_append_mapping_pair(d, inlet, scalar(d, "probe_width"),
                                    number(d, CAMP_PROBE_WIDTH));
  set(d, effects, "inlet_force", inlet);
  return 0;
}

/* Appends `name` to names unless there already (n names so far, at most max). */
static int add_name(const char **names, int n, int max, const char *name) {
  if (!name) return n;
  for (int i = 0; i < n; i++)
    if (!strcmp(names[i], name)) return n;
  if (n < max) names[n++] = name;
  return n;
}

/* The fluid species names: geometry.species.fluid with the species that
 * geometry.fluid_species_labels and geometry.fluid_species_regions give pore voxels (two liquids:
 * `mdpore relperm` drives both), else the species not frozen. */
static int fluid_species(doc_t *d, int root, const char **names, int max) {
  int g = get(d, root, "geometry");
  if (g) {
    const char *f = text_of(d, get(d, get(d, g, "species"), "fluid"));
    if (f) {
      int n = add_name(names, 0, max, f);
      yaml_node_t *labels = yaml_document_get_node(d, get(d, g, "fluid_species_labels"));
      if (labels && labels->type == YAML_MAPPING_NODE)
        for (yaml_node_pair_t *p = labels->data.mapping.pairs.start;
             p < labels->data.mapping.pairs.top; p++)
          n = add_name(names, n, max, text_of(d, p->value));
      yaml_node_t *regions = yaml_document_get_node(d, get(d, g, "fluid_species_regions"));
      if (regions && regions->type == YAML_SEQUENCE_NODE)
        for (yaml_node_item_t *it = regions->data.sequence.items.start;
             it < regions->data.sequence.items.top; it++)
          n = add_name(names, n, max, text_of(d, get(d, *it, "species")));
      return n;
    }
  }
  int n = 0;
  yaml_node_t *sp = yaml_document_get_node(d, get(d, root, "species"));
  if (!sp || sp->type != YAML_SEQUENCE_NODE) return 0;
  for (yaml_node_item_t *it = sp->data.sequence.items.start; it < sp->data.sequence.items.top;
       it++) {
    const char *name = text_of(d, get(d, *it, "name"));
    const char *frozen = text_of(d, get(d, *it, "frozen"));
    if (name && !(frozen && !strcmp(frozen, "true")) && n < max) names[n++] = name;
  }
  return n;
}

char *camp_scene_text(const char *template_path, const camp_opts *o, int axis, double g) {
  ytree_t t;
  if (yt_load(&t, template_path, 0)) return NULL;
  doc_t *d = &t.doc;
  char *out = NULL;
  int root = node_id(d, yt_root(&t));
  if (!root || yt_expect_map(&t, yaml_document_get_node(d, root), "")) goto done;
  char dir[CAMP_PATH];
  snprintf(dir, sizeof dir, "%s", template_path);
  char *slash = strrchr(dir, '/');
  if (slash) *slash = 0;

  /* body force on the fluid */
  const char *names[16];
  int nf = fluid_species(d, root, names, 16);
  if (nf == 0) {
    fprintf(stderr,
            "mdpore permeability: %s: key 'species': expected a mobile (not frozen) fluid "
            "species to drive\n",
            template_path);
    goto done;
  }
  char fluid_copy[16][256];
  for (int i = 0; i < nf; i++) snprintf(fluid_copy[i], 256, "%s", names[i]);
  int effects = child_map(d, root, "effects");
  int bf = yaml_document_add_mapping(d, NULL, YAML_FLOW_MAPPING_STYLE);
  for (int i = 0; i < nf; i++) {
    int vec = yaml_document_add_sequence(d, NULL, YAML_FLOW_SEQUENCE_STYLE);
    for (int c = 0; c < 3; c++)
      yaml_document_append_sequence_item(d, vec, number(d, c == axis ? g : 0));
    yaml_document_append_mapping_pair(d, bf, scalar(d, fluid_copy[i]), vec);
  }
  set(d, effects, "body_force", bf);
  if (mirror_geometry(d, root, o, axis, template_path)) goto done;
  if (o->drive == CAMP_DRIVE_PRESSURE &&
      pressure_drive(d, root, effects, o, axis, g, (const char(*)[256])fluid_copy, nf,
                     template_path))
    goto done;

  const char axis_name[2] = {(char)('x' + axis), 0};
  int geo = get(d, root, "geometry");
  if (geo) {
    set(d, geo, "flow_axis", scalar(d, axis_name));
    absolutize(d, geo, "image", dir); /* the padded image of a pressure drive is absolute */
    int patches = get(d, geo, "patches");
    if (patches && yaml_document_get_node(d, patches)->type == YAML_MAPPING_NODE)
      absolutize(d, patches, "file", dir);
  }
  int initial = get(d, root, "initial");
  if (initial && yaml_document_get_node(d, initial)->type == YAML_MAPPING_NODE) {
    absolutize(d, initial, "lammps_data", dir);
    absolutize(d, initial, "snapshot", dir);
  }

  int output = child_map(d, root, "output");
  int flux = child_map(d, output, "flux");
  set(d, flux, "axis", scalar(d, axis_name));
  set(d, flux, "file", scalar(d, "flux.csv"));
  if (!get(d, flux, "every")) set(d, flux, "every", number(d, o->flux_every));
  /* the standard water's compressibility, so that each run leaves out the pressure-diffusion
   * transient (a liquid of another viscosity, --viscosity, is not that water: its scene sets the
   * key itself or goes without) */
  if (!o->viscosity_given && !get(d, flux, "bulk_modulus"))
    set(d, flux, "bulk_modulus", number(d, CAMP_WATER_BULK_MODULUS));
  set(d, output, "summary", scalar(d, "summary.json"));
  set(d, output, "progress", scalar(d, "false"));

  int run = child_map(d, root, "run");
  if (o->target_error_k > 0) {
    /* the campaign-level rule (campaign_rounds.c): no stop of the run's own; the first round's
     * length, and a checkpoint at the end only (every beyond any run), from which the campaign
     * continues the run */
    unset(d, run, "target_error");
    set(d, run, "steps", number(d, (double)o->round_steps));
    int checkpoint = child_map(d, output, "checkpoint");
    set(d, checkpoint, "every", number(d, (double)CAMP_CHECKPOINT_NEVER));
    set(d, checkpoint, "file", scalar(d, CAMP_CHECKPOINT_FILE));
  } else {
    set(d, run, "target_error", number(d, o->target_error));
    if (o->max_steps > 0) set(d, run, "steps", number(d, (double)o->max_steps));
  }
  if (o->dt > 0) set(d, run, "dt", number(d, o->dt));
  char gtext[64];
  snprintf(gtext, sizeof gtext, "%.15g", g);
  uint64_t hg = camp_fnv1a(14695981039346656037ULL, gtext, strlen(gtext));
  set(d, run, "seed", number(d, (double)(o->seed + (long long)(hg % 1000000ULL))));

  yaml_emitter_t em;
  sbuf b = {0};
  yaml_emitter_initialize(&em);
  yaml_emitter_set_output(&em, write_handler, &b);
  yaml_emitter_set_width(&em, -1);
  yaml_emitter_set_unicode(&em, 1);
  if (!yaml_emitter_open(&em) || !yaml_emitter_dump(&em, d) || !yaml_emitter_close(&em)) {
    fprintf(stderr, "mdpore permeability: %s: could not emit the run's scene (%s)\n", template_path,
            em.problem ? em.problem : "libyaml emitter");
    free(b.s);
  } else
    out = b.s;
  yaml_emitter_delete(&em);
done:
  yt_free(&t);
  return out;
}
