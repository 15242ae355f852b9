/* Shared image options of the command line (see mdpore_image_cli.h and docs/images.md). */
#include "image_internal.h"
#include "mdpore_image_cli.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void mdp_image_cli_init(mdp_image_cli_t *c) {
  memset(c, 0, sizeof *c);
  mdp_image_read_opts_init(&c->read);
  c->pad_label = -1;
}

const cli_help_option_t mdp_image_cli_options[] = {
    {NULL,
     "reading (raw files also take these from a sidecar IMAGE.hdr; HDF5 from attributes):", 0},
    {"--dims NXxNYxNZ", "raw: dimensions", 0},
    {"--type T", "raw: uint8 (default), int8, uint16, int16, uint32, int32", 0},
    {"--byte-order little|big", "raw: byte order of multi-byte types (default little)", 0},
    {"--order xyz", "raw: axes fastest first (default xyz = x fastest; zyx = z fastest)", 0},
    {"--header-bytes N", "raw: bytes to skip before the data", 0},
    {"--format raw|hdf5|tiff", "override the format guessed from the name (folder = TIFF slices)",
     0},
    {"--dataset PATH", "HDF5 dataset (default /labels)", 0},
    {"--labels MAP", "e.g. pore=0,organic=2,inorganic=1,3-5 (default " MDP_IMAGE_DEFAULT_LABELS ")",
     0},
    {"--voxel-size SIZE", "e.g. 10um, 5nm, 1e-5m", 0},
    {NULL, "transforming (applied in this order):", 0},
    {"--crop X0:X1,Y0:Y1,Z0:Z1", "keep voxels X0 <= i < X1 etc. (':' keeps a whole axis)", 0},
    {"--downsample F", "majority label over F^3 blocks", 0},
    {"--pad [AXIS=]W[:LABEL]",
     "add W layers of LABEL (default the smallest pore label) on both faces of AXIS (x, y or z; "
     "all axes when omitted); repeatable",
     0},
    {"--mirror AXES",
     "follow the image by its reflection along each axis given (e.g. x or x,y,z): a periodic "
     "image in which each face meets itself",
     0},
    {NULL, NULL, 0}};

static int parse_int(const char *s, int *v) {
  char *end;
  long x = strtol(s, &end, 10);
  if (end == s || *end || x < 0 || x > 1000000000L) return 1;
  *v = (int)x;
  return 0;
}

/* A crop bound: a voxel index 0 .. INT_MAX (a negative one or one beyond an int would otherwise be
 * read as "to the end" or wrapped). 0, or 1 when it is not one. */
static int crop_bound(const char **s, int *v) {
  char *end;
  errno = 0;
  const long long x = strtoll(*s, &end, 10);
  if (end == *s || errno || x < 0 || x > INT_MAX) return 1;
  *v = (int)x;
  *s = end;
  return 0;
}

static int parse_crop(const char *text, mdp_image_cli_t *c) {
  const char *s = text;
  for (int a = 0; a < 3; a++) {
    c->crop_lo[a] = 0, c->crop_hi[a] = -1; /* -1 = to the end */
    if (*s != ':' && crop_bound(&s, &c->crop_lo[a])) return 1;
    if (*s++ != ':') return 1;
    if (*s && *s != ',' && crop_bound(&s, &c->crop_hi[a])) return 1;
    if (a < 2 && *s++ != ',') return 1;
  }
  c->crop = 1;
  return *s != 0;
}

static int parse_pad(const char *text, mdp_image_cli_t *c) {
  const char *s = text;
  int axis = -1;
  if ((s[0] == 'x' || s[0] == 'y' || s[0] == 'z') && s[1] == '=') axis = s[0] - 'x', s += 2;
  char *end;
  long w = strtol(s, &end, 10);
  if (end == s || w < 0 || w > INT_MAX) return 1;
  if (*end == ':') {
    char *e2;
    long lab = strtol(end + 1, &e2, 10);
    if (e2 == end + 1 || *e2 || lab < 0 || lab > 255) return 1;
    c->pad_label = (int)lab;
  } else if (*end) {
    return 1;
  }
  for (int a = 0; a < 3; a++)
    if (axis < 0 || axis == a) c->pad[2 * a] = c->pad[2 * a + 1] = (int)w;
  return 0;
}

static const char *const raw_types[] = {"uint8",  "int8",  "uint16", "int16",
                                        "uint32", "int32", NULL};
static const char *const byte_orders[] = {"little", "big", NULL};
static const char *const formats[] = {"raw", "hdf5", "tiff", NULL};

static int one_of(const char *v, const char *const *words) {
  for (int i = 0; words[i]; i++)
    if (!strcmp(v, words[i])) return 1;
  return 0;
}

/* "option OPT: " before a reader's message (which names the value, not the option); -1. */
static int prefix_option(const char *opt, char *err) {
  char msg[MDP_IMAGE_ERR_LEN];
  snprintf(msg, sizeof msg, "%s", err);
  snprintf(err, MDP_IMAGE_ERR_LEN, "option %.32s: %.960s", opt, msg);
  return -1;
}

int mdp_image_cli_parse(int argc, char **argv, int *i, mdp_image_cli_t *c, char *err) {
  const char *opt = argv[*i];
  static const char *with_value[] = {"--dims",         "--type",   "--byte-order", "--order",
                                     "--header-bytes", "--format", "--dataset",    "--labels",
                                     "--voxel-size",   "--crop",   "--downsample", "--pad",
                                     "--mirror"};
  int known = 0;
  for (size_t k = 0; k < sizeof with_value / sizeof with_value[0]; k++)
    known |= !strcmp(opt, with_value[k]);
  if (!known) return 0;
  if (*i + 1 >= argc) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "option %s needs a value", opt);
    return -1;
  }
  const char *v = argv[++*i];
  mdp_image_read_opts_t *o = &c->read;
  int bad = 0;
  if (!strcmp(opt, "--dims")) {
    int d[3];
    bad = mdp_image_parse_dims(v, d);
    o->nx = d[0], o->ny = d[1], o->nz = d[2];
  } else if (!strcmp(opt, "--type")) { /* checked here: an HDF5 or TIFF input ignores it */
    bad = !one_of(v, raw_types);
    snprintf(o->type, sizeof o->type, "%s", v);
  } else if (!strcmp(opt, "--byte-order")) {
    bad = !one_of(v, byte_orders);
    snprintf(o->byte_order, sizeof o->byte_order, "%s", v);
  } else if (!strcmp(opt, "--order")) {
    bad = strlen(v) != 3 || !strchr(v, 'x') || !strchr(v, 'y') || !strchr(v, 'z');
    snprintf(o->axis_order, sizeof o->axis_order, "%s", v);
  } else if (!strcmp(opt, "--header-bytes")) {
    int h = 0;
    bad = parse_int(v, &h);
    o->header_bytes = h;
  } else if (!strcmp(opt, "--format")) {
    bad = !one_of(v, formats);
    snprintf(o->format, sizeof o->format, "%s", v);
  } else if (!strcmp(opt, "--dataset")) {
    snprintf(o->dataset, sizeof o->dataset, "%s", v);
  } else if (!strcmp(opt, "--labels")) {
    uint8_t map[256];
    if (mdp_image_parse_labels(v, map, err)) return prefix_option(opt, err);
    snprintf(o->labels, sizeof o->labels, "%s", v);
  } else if (!strcmp(opt, "--voxel-size")) {
    if (mdp_image_parse_voxel_size(v, &o->voxel_size, o->unit, err)) return prefix_option(opt, err);
  } else if (!strcmp(opt, "--crop")) {
    bad = parse_crop(v, c);
  } else if (!strcmp(opt, "--downsample")) {
    bad = parse_int(v, &c->downsample) || c->downsample < 1;
  } else if (!strcmp(opt, "--pad")) {
    bad = parse_pad(v, c);
  } else if (!strcmp(opt, "--mirror")) {
    for (const char *p = v; !bad && *p; p++)
      if (*p >= 'x' && *p <= 'z' && (p[1] == ',' || !p[1]) && (p == v || p[-1] == ','))
        c->mirror[*p - 'x'] = 1;
      else
        bad = *p != ',' || p == v || !p[1] || p[-1] == ',';
  }
  if (bad) {
    const char *expected =
        !strcmp(opt, "--pad")    ? "[AXIS=]W[:LABEL], W from 0 to 2147483647 layers, LABEL 0-255"
        : !strcmp(opt, "--crop") ? "X0:X1,Y0:Y1,Z0:Z1 of voxel indices 0 to 2147483647 (a bound "
                                   "may be left out: ':' keeps an axis)"
        : !strcmp(opt, "--downsample") ? "an integer factor >= 1"
        : !strcmp(opt, "--mirror")     ? "axes x, y, z separated by commas"
        : !strcmp(opt, "--type")       ? "uint8, int8, uint16, int16, uint32 or int32"
        : !strcmp(opt, "--byte-order") ? "little or big"
        : !strcmp(opt, "--order")      ? "a permutation of xyz, e.g. zyx"
        : !strcmp(opt, "--format")     ? "raw, hdf5 or tiff"
                                       : "a valid value (see --help)";
    snprintf(err, MDP_IMAGE_ERR_LEN, "option %s: bad value '%s' (expected %s)", opt, v, expected);
    return -1;
  }
  (*i)++;
  return 1;
}

int mdp_image_cli_load(const char *path, const mdp_image_cli_t *c, mdp_image_t *img, char *err) {
  if (mdp_image_read(path, &c->read, img, err)) return 1;
  mdp_image_t tmp;
  const char *step = "--crop";
  if (c->crop) {
    const int n[3] = {img->nx, img->ny, img->nz};
    int lo[3], size[3];
    for (int a = 0; a < 3; a++) {
      lo[a] = c->crop_lo[a];
      size[a] = (c->crop_hi[a] < 0 ? n[a] : c->crop_hi[a]) - lo[a];
    }
    if (mdp_image_crop(img, lo, size, &tmp, err)) goto fail;
    mdp_image_free(img);
    *img = tmp;
  }
  step = "--downsample";
  if (c->downsample > 1) {
    if (mdp_image_downsample(img, c->downsample, &tmp, err)) goto fail;
    mdp_image_free(img);
    *img = tmp;
  }
  step = "--pad";
  int any_pad = 0;
  for (int s = 0; s < 6; s++) any_pad |= c->pad[s] > 0;
  if (any_pad) {
    int label = c->pad_label;
    for (int v = 0; v < 256 && label < 0; v++)
      if (img->phase_of[v] == MDP_PHASE_PORE) label = v;
    if (mdp_image_pad(img, c->pad, (uint8_t)label, &tmp, err)) goto fail;
    mdp_image_free(img);
    *img = tmp;
  }
  step = "--mirror";
  if (c->mirror[0] || c->mirror[1] || c->mirror[2]) {
    if (mdp_image_mirror(img, c->mirror, &tmp, err)) goto fail;
    mdp_image_free(img);
    *img = tmp;
  }
  return 0;
fail:
  mdp_image_free(img);
  /* name the file and the option whose transformation failed */
  char inner[MDP_IMAGE_ERR_LEN];
  snprintf(inner, sizeof inner, "%s", err);
  snprintf(err, MDP_IMAGE_ERR_LEN, "%.300s: %s: %.600s", path, step, inner);
  return 1;
}
