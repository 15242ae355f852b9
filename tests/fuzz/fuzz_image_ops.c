/* Fuzz entry: the image operations whose numbers are sizes, over a fixed 6x5x4 image (labels 0, 1,
 * 2 of the default map, written once as a raw file). The input is argv tokens, one a line (a NUL
 * ends a token too); the first picks the operation:
 *   image ...          the transforming options of `mdpore image` (--crop, --downsample, --pad,
 *                      --mirror; mdp_image_cli_parse, then mdp_image_cli_load on the file; other
 *                      reading options are parsed but the file is read as written)
 *   stack AXIS ...     images joined along AXIS as `mdpore image stack` does (mdp_image_concat),
 *                      each the fixed image under its own `image` options, the groups separated by
 *                      a token "+"
 *   permeability ...   `mdpore permeability` options on the image (camp_parse_args), then the
 *                      image of each flow axis under its boundary treatment (camp_boundary_image:
 *                      mirror, --sides mirror, the --reservoir padding at --rc-per-voxel)
 * The entry computes the expected size from the option text with its own arithmetic (and, for
 * `image`, every voxel of a small result). A result must have that size (and those voxels); a
 * refusal must come with a message naming the option (or the file), and is expected where the
 * arithmetic says the options do not fit the image. With the fuzzers' memory limit (32 MiB) a
 * result of more than 64M voxels must be refused before it is allocated; one above 4M voxels may
 * be. Else abort: a finding. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign.h"
#include "fuzz_util.h"
#include "mdpore_image.h"
#include "mdpore_image_cli.h"

#define MAX_ARGS 64
#define MAY_REFUSE 4e6   /* voxels above which the memory limit may refuse a result */
#define MUST_REFUSE 64e6 /* voxels the 32 MiB limit must refuse */

static const int fixed_n[3] = {6, 5, 4};
static mdp_image_t fixed;
static char image_path[300];
static camp_opts co; /* large: not on the stack */
static campaign camp;

static void finding(const char *what, const char *detail) {
  fprintf(stderr, "fuzz: image_ops: %s (%s)\n", what, detail);
  abort();
}

static void make_fixed(void) {
  char err[MDP_IMAGE_ERR_LEN];
  if (fixed.label) return;
  if (mdp_image_alloc(&fixed, fixed_n[0], fixed_n[1], fixed_n[2], err)) finding("alloc", err);
  mdp_image_parse_labels(MDP_IMAGE_DEFAULT_LABELS, fixed.phase_of, err);
  for (int k = 0; k < fixed_n[2]; k++)
    for (int j = 0; j < fixed_n[1]; j++)
      for (int i = 0; i < fixed_n[0]; i++) /* pore channels along x and z in a mixed solid */
        fixed.label[mdp_image_index(&fixed, i, j, k)] =
            (uint8_t)((j == 2 || (i == 3 && j > 0)) ? 0 : 1 + (i * 7 + j * 3 + k * 5) % 2);
  fuzz_path("fixed.raw", image_path, sizeof image_path);
  if (mdp_image_write_raw(&fixed, image_path, err)) finding("write", err);
}

/* ---- the `image` options: the expected result, from the option text ---- */
typedef struct {
  long long lo[3], hi[3]; /* crop */
  long long f;            /* downsample (1: none) */
  long long w[3];         /* pad layers on both faces */
  int label;              /* pad label (-1: the smallest pore label) */
  int mirror[3];
  int invalid; /* the options do not fit the image: a refusal is expected */
} expect_t;

static long long number(const char *s, const char **end) {
  char *e;
  errno = 0;
  long long v = strtoll(s, &e, 10);
  if (e == s)
    *end = NULL;
  else
    *end = e;
  return errno ? LLONG_MAX : v;
}

/* --crop X0:X1,Y0:Y1,Z0:Z1, each bound may be left out (0, the end) */
static void expect_crop(const char *v, expect_t *e) {
  const char *s = v, *end;
  for (int a = 0; a < 3; a++) {
    e->lo[a] = 0, e->hi[a] = fixed_n[a];
    if (*s != ':') {
      e->lo[a] = number(s, &end);
      if (!end) return; /* a parse error: refused by the parser */
      s = end;
    }
    if (*s++ != ':') return;
    if (*s && *s != ',') {
      e->hi[a] = number(s, &end);
      if (!end) return;
      s = end;
    }
    if (a < 2 && *s++ != ',') return;
  }
}

static void expect_pad(const char *v, expect_t *e) {
  int axis = -1;
  if ((v[0] == 'x' || v[0] == 'y' || v[0] == 'z') && v[1] == '=') axis = v[0] - 'x', v += 2;
  const char *end;
  const long long w = number(v, &end);
  if (!end) return;
  if (*end == ':') e->label = (int)number(end + 1, &end);
  for (int a = 0; a < 3; a++)
    if (axis < 0 || axis == a) e->w[a] = w;
}

/* The model's size after each step; voxels: the largest image on the way. */
static void expect_sizes(expect_t *e, long long n[3], double *voxels) {
  *voxels = 0;
  for (int a = 0; a < 3; a++) {
    if (e->lo[a] < 0 || e->hi[a] <= e->lo[a] || e->hi[a] > fixed_n[a]) e->invalid = 1;
    n[a] = e->hi[a] - e->lo[a];
  }
  if (e->invalid) return;
  for (int a = 0; a < 3; a++)
    if (e->f > n[a]) e->invalid = 1;
  if (e->invalid) return;
  for (int a = 0; a < 3; a++) n[a] /= e->f;
  const int any_pad = e->w[0] || e->w[1] || e->w[2];
  if (any_pad && e->label >= 0 && fixed.phase_of[e->label] == MDP_PHASE_UNSET) e->invalid = 1;
  double v = 1;
  for (int a = 0; a < 3; a++) {
    n[a] += 2 * e->w[a];
    v *= (double)n[a];
    if (n[a] > INT_MAX) e->invalid = 1;
  }
  *voxels = v;
  for (int a = 0; a < 3; a++)
    if (e->mirror[a]) n[a] *= 2, v *= 2;
  for (int a = 0; a < 3; a++)
    if (n[a] > INT_MAX) e->invalid = 1;
  if (v > *voxels) *voxels = v;
}

/* The label the operations put at (i, j, k) of the result. */
static int expect_voxel(const expect_t *e, const long long n[3], const int x[3]) {
  long long p[3];
  for (int a = 0; a < 3; a++) {
    const long long padded = e->mirror[a] ? n[a] / 2 : n[a];
    p[a] = x[a] < padded ? x[a] : 2 * padded - 1 - x[a];
    p[a] -= e->w[a];
    if (p[a] < 0 || p[a] >= padded - 2 * e->w[a]) return e->label < 0 ? 0 : e->label;
  }
  int count[256] = {0};
  for (long long c = 0; c < e->f; c++)
    for (long long b = 0; b < e->f; b++)
      for (long long a = 0; a < e->f; a++)
        count[fixed.label[mdp_image_index(&fixed, (int)(e->lo[0] + e->f * p[0] + a),
                                          (int)(e->lo[1] + e->f * p[1] + b),
                                          (int)(e->lo[2] + e->f * p[2] + c))]]++;
  int best = 0;
  for (int v = 1; v < 256; v++)
    if (count[v] > count[best]) best = v;
  return best;
}

/* Parses the `image` options of argv[from, to) into c and the model; 0, or -1 after checking the
 * parser's message names the option. */
static int parse_image_options(int to, char **argv, int from, mdp_image_cli_t *c, expect_t *e) {
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_cli_init(c);
  memset(e, 0, sizeof *e);
  e->f = 1;
  e->label = -1;
  for (int a = 0; a < 3; a++) e->hi[a] = fixed_n[a];
  for (int i = from; i < to; i++) {
    const int at = i;
    err[0] = 0;
    const int r = mdp_image_cli_parse(to, argv, &i, c, err);
    if (r < 0) {
      if (!strstr(err, argv[at])) finding("a bad value refused without naming the option", err);
      return -1;
    }
    if (r == 0) continue; /* not an image option: ignored */
    const char *v = argv[at + 1];
    if (!strcmp(argv[at], "--crop")) expect_crop(v, e);
    if (!strcmp(argv[at], "--downsample")) e->f = number(v, &v);
    if (!strcmp(argv[at], "--pad")) expect_pad(v, e);
    if (!strcmp(argv[at], "--mirror"))
      for (int a = 0; a < 3; a++) e->mirror[a] |= strchr(v, 'x' + a) != NULL;
    i--; /* the loop's i++ */
  }
  mdp_image_read_opts_init(&c->read); /* the file as written */
  return 0;
}

/* Loads the fixed image under argv[from, to) and checks the result against the model. 0 with
 * *img, 1 refused (message checked), -1 the parser refused. */
static int image_ops(int to, char **argv, int from, mdp_image_t *img, int check_voxels) {
  mdp_image_cli_t c;
  expect_t e;
  char err[MDP_IMAGE_ERR_LEN] = "";
  if (parse_image_options(to, argv, from, &c, &e)) return -1;
  long long n[3];
  double voxels;
  expect_sizes(&e, n, &voxels);
  const int rc = mdp_image_cli_load(image_path, &c, img, err);
  char detail[MDP_IMAGE_ERR_LEN + 200];
  snprintf(detail, sizeof detail, "expected %lldx%lldx%lld (%s), got %s", n[0], n[1], n[2],
           e.invalid ? "invalid" : "valid", rc ? err : "a result");
  if (rc) {
    if (!strstr(err, image_path)) finding("a refusal without naming the file", detail);
    if (!e.invalid && voxels <= MAY_REFUSE) finding("options that fit were refused", detail);
    return 1;
  }
  if (e.invalid || voxels > MUST_REFUSE) finding("options that do not fit were accepted", detail);
  if (img->nx != n[0] || img->ny != n[1] || img->nz != n[2])
    finding("the result's size differs from the arithmetic", detail);
  if (check_voxels && voxels <= 2e5)
    for (int k = 0; k < img->nz; k++)
      for (int j = 0; j < img->ny; j++)
        for (int i = 0; i < img->nx; i++) {
          const int x[3] = {i, j, k};
          if (img->label[mdp_image_index(img, i, j, k)] != expect_voxel(&e, n, x))
            finding("a voxel differs from the operations' definition", detail);
        }
  return 0;
}

/* stack AXIS OPTIONS [+ OPTIONS]...: the fixed image under each group, joined along AXIS. 1 when
 * every group was joined. */
static int stack(int argc, char **argv) {
  if (argc < 3 || strlen(argv[2]) != 1 || argv[2][0] < 'x' || argv[2][0] > 'z') return 0;
  const int axis = argv[2][0] - 'x';
  mdp_image_t acc = {0}, next, joined;
  int have = 0, all = 1;
  for (int from = 3; from <= argc;) {
    int to = from;
    while (to < argc && strcmp(argv[to], "+")) to++;
    const int rc = image_ops(to, argv, from, &next, 0);
    if (rc) {
      all = 0;
      break;
    }
    if (!have) {
      acc = next, have = 1;
    } else {
      char err[MDP_IMAGE_ERR_LEN] = "", detail[MDP_IMAGE_ERR_LEN + 200];
      const int na[3] = {acc.nx, acc.ny, acc.nz}, nb[3] = {next.nx, next.ny, next.nz};
      int fits = (long long)na[axis] + nb[axis] <= INT_MAX;
      double voxels = (double)na[axis] + nb[axis];
      for (int d = 0; d < 3; d++)
        if (d != axis) fits &= na[d] == nb[d], voxels *= na[d];
      fits &= acc.voxel_size == next.voxel_size; /* --downsample scales it */
      const int bad = mdp_image_concat(&acc, &next, axis, &joined, err);
      snprintf(detail, sizeof detail, "%dx%dx%d and %dx%dx%d along %c: %s", na[0], na[1], na[2],
               nb[0], nb[1], nb[2], 'x' + axis, bad ? err : "joined");
      mdp_image_free(&next);
      if (bad) {
        if (!strstr(err, "stack")) finding("a stack refused without naming it", detail);
        if (fits && voxels <= MAY_REFUSE) finding("images that fit were not stacked", detail);
        all = 0;
        break;
      }
      if (!fits || voxels > MUST_REFUSE) finding("images that do not fit were stacked", detail);
      const int n[3] = {joined.nx, joined.ny, joined.nz};
      for (int d = 0; d < 3; d++)
        if (n[d] != (d == axis ? na[d] + nb[d] : na[d]))
          finding("a stack of the wrong size", detail);
      mdp_image_free(&acc);
      acc = joined;
    }
    from = to + 1;
  }
  if (have) mdp_image_free(&acc);
  return all;
}

/* permeability OPTIONS: the boundary image of each flow axis. 1 when the options were accepted and
 * every axis's image built (or the image itself serves). */
static int boundary(int argc, char **argv) {
  char *args[MAX_ARGS + 4], workdir[300];
  int n = 0;
  fuzz_path("campaign", workdir, sizeof workdir);
  args[n++] = "permeability";
  args[n++] = image_path;
  for (int i = 2; i < argc; i++) args[n++] = argv[i];
  args[n++] = "--workdir";
  args[n++] = workdir; /* never written: the images are built, not written */
  args[n] = NULL;
  fuzz_capture_begin();
  int rc = camp_parse_args(n, args, &co);
  fuzz_capture_end(); /* the campaign_args entry checks these messages */
  if (rc || co.collect_dir[0]) return 0;
  int all = 1;
  memset(&camp, 0, sizeof camp);
  camp_resolve_boundaries(&co, &camp, &fixed);
  for (int a = 0; a < co.n_axes; a++) {
    const int ax = co.axes[a];
    const int reservoir = co.boundary_of_axis[ax] == CAMP_BOUNDARY_RESERVOIR;
    double len[3], voxels = 1;
    for (int d = 0; d < 3; d++) len[d] = fixed_n[d] * (camp_mirrored_along(&co, ax, d) ? 2 : 1);
    const double layers = reservoir ? round(co.reservoir / co.rc_per_voxel) : 0;
    len[ax] += layers;
    for (int d = 0; d < 3; d++) voxels *= len[d];
    const int fits = len[ax] <= INT_MAX;
    mdp_image_t out;
    fuzz_capture_begin();
    rc = camp_boundary_image(&co, &fixed, ax, &out);
    const char *msg = fuzz_capture_end();
    char detail[9000];
    snprintf(detail, sizeof detail,
             "axis %c, %s, reservoir %g rc at %g rc per voxel: expected %.0fx%.0fx%.0f, got %s",
             'x' + ax, camp_boundary_name(co.boundary_of_axis[ax]), co.reservoir, co.rc_per_voxel,
             len[0], len[1], len[2],
             rc < 0 ? msg
             : rc   ? "the image itself"
                    : "an image");
    if (rc < 0) {
      if (!strstr(msg, image_path) ||
          !(strstr(msg, "--reservoir") || strstr(msg, "--boundary") || strstr(msg, "--drive")))
        finding("a boundary image refused without naming the input and the option", detail);
      if (fits && voxels <= MAY_REFUSE) finding("a boundary image that fits was refused", detail);
      all = 0;
      continue;
    }
    if (rc > 0) {
      if (voxels != (double)fixed_n[0] * fixed_n[1] * fixed_n[2])
        finding("a treatment that changes the image built none", detail);
      continue;
    }
    if (!fits || voxels > MUST_REFUSE)
      finding("a boundary image that does not fit was built", detail);
    if (out.nx != len[0] || out.ny != len[1] || out.nz != len[2])
      finding("a boundary image of the wrong size", detail);
    mdp_image_free(&out);
  }
  return all;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char *argv[MAX_ARGS + 1];
  make_fixed();
  const int argc = fuzz_argv(data, size, "image_ops", argv, MAX_ARGS);
  int accepted = 0;
  if (argc >= 2 && !strcmp(argv[1], "stack"))
    accepted = stack(argc, argv);
  else if (argc >= 2 && !strcmp(argv[1], "permeability"))
    accepted = boundary(argc, argv);
  else {
    mdp_image_t img;
    if (image_ops(argc, argv, 1, &img, 1) == 0) {
      mdp_image_free(&img);
      accepted = 1;
    }
  }
  fuzz_last_accepted = accepted; /* replay: ok_* seeds give a result, bad_* a refusal */
  return 0;
}
