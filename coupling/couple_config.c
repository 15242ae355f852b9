/* The `mdpore couple` config (docs/coupling.md): every key validated, errors as
 * FILE:LINE:COL: key 'PATH': expected WHAT (got WHAT). */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "campaign.h" /* CAMP_MAX_JOBS */
#include "common/yaml_tree.h"
#include "couple.h"
#include "darcy/darcy_units.h"

static const char *const top_keys[] = {
    "workdir", "image",    "image_labels", "image_voxel_size", "blocks", "block_images",
    "axis",    "gradient", "law",          "campaign",         "loop",   "launcher",
    "slurm",   NULL};
static const char *const campaign_keys[] = {
    "rc_per_voxel", "np",       "n_gradients", "velocity_range", "target_error",
    "max_steps",    "accuracy", "seed",        "voxel_size",     "viscosity",
    "mpiexec",      "jobs",     "drive",       "boundary",       "sides",
    "axes",         NULL};
static const char *const loop_keys[] = {"max_passes", "tolerance_sigma", "resolvable_fraction",
                                        "error_samples", NULL};
static const char *const axis_words[] = {"x", "y", "z", NULL};
static const char *const law_words[] = {"darcy", "chosen", NULL};
static const char *const launcher_words[] = {"mpiexec", "slurm", NULL};

/* dir + "/" + rel unless rel is absolute. */
static void resolve(const char *dir, const char *rel, char *out, int len) {
  if (rel[0] == '/')
    snprintf(out, len, "%s", rel);
  else
    snprintf(out, len, "%.2000s/%.2000s", dir, rel);
}

static int number_in(ytree_t *t, yaml_node_t *map, const char *key, const char *path, double lo,
                     double hi, const char *what, double *out) {
  yaml_node_t *n = yt_get(t, map, key);
  if (!n) return 0;
  double v;
  if (yt_double(t, n, path, &v)) return -1;
  if (!(v > lo && v < hi)) return yt_error(t, n, path, "expected %s (got %g)", what, v);
  *out = v;
  return 0;
}

static int integer_in(ytree_t *t, yaml_node_t *map, const char *key, const char *path, long lo,
                      long hi, long *out) {
  yaml_node_t *n = yt_get(t, map, key);
  if (!n) return 0;
  long v;
  if (yt_long(t, n, path, &v)) return -1;
  if (v < lo || v > hi)
    return yt_error(t, n, path, "expected an integer from %ld to %ld (got %ld)", lo, hi, v);
  *out = v;
  return 0;
}

static int read_campaign(ytree_t *t, yaml_node_t *m, couple_config *c) {
  if (yt_expect_map(t, m, "campaign") || yt_check_keys(t, m, "campaign", campaign_keys)) return -1;
  long v;
  if (number_in(t, m, "rc_per_voxel", "campaign.rc_per_voxel", 0, 100, "a number in (0, 100)",
                &c->rc_per_voxel))
    return -1;
  v = c->np;
  if (integer_in(t, m, "np", "campaign.np", 1, 4096, &v)) return -1;
  c->np = (int)v;
  yaml_node_t *jobs = yt_get(t, m, "jobs"); /* N or auto: mdpore permeability --jobs */
  char word[256];
  if (jobs && yt_string(t, jobs, "campaign.jobs", word, sizeof word)) return -1;
  if (jobs && !strcmp(word, "auto"))
    c->jobs = 0;
  else if (jobs) {
    v = c->jobs;
    if (integer_in(t, m, "jobs", "campaign.jobs", 1, CAMP_MAX_JOBS, &v)) return -1;
    c->jobs = (int)v;
  }
  v = c->n_gradients;
  if (integer_in(t, m, "n_gradients", "campaign.n_gradients", 5, COUPLE_MAX_GRADIENTS / 2, &v))
    return -1;
  c->n_gradients = (int)v;
  yaml_node_t *n = yt_get(t, m, "velocity_range");
  if (n) {
    if (yt_expect_seq(t, n, "campaign.velocity_range")) return -1;
    if (yt_seq_size(n) != 2)
      return yt_error(t, n, "campaign.velocity_range", "expected a list [LOW, HIGH]");
    if (yt_double(t, yt_seq_item(t, n, 0), "campaign.velocity_range[0]", &c->u_lo) ||
        yt_double(t, yt_seq_item(t, n, 1), "campaign.velocity_range[1]", &c->u_hi))
      return -1;
    if (!(c->u_lo > 0 && c->u_hi > c->u_lo && c->u_hi < 100))
      return yt_error(t, n, "campaign.velocity_range",
                      "expected 0 < LOW < HIGH < 100 (mean pore velocities)");
  }
  if (number_in(t, m, "target_error", "campaign.target_error", 0, 1, "a number in (0, 1)",
                &c->target_error) ||
      number_in(t, m, "viscosity", "campaign.viscosity", 0, 1e6, "a positive viscosity",
                &c->viscosity))
    return -1;
  v = (long)c->max_steps;
  if (integer_in(t, m, "max_steps", "campaign.max_steps", 1, 1000000000L, &v)) return -1;
  c->max_steps = v;
  c->target_error_given = yt_get(t, m, "target_error") != NULL;
  c->max_steps_given = yt_get(t, m, "max_steps") != NULL;
  static const char *const accuracy_words[] = {"fast", "balanced", "precise", NULL};
  yaml_node_t *acc = yt_get(t, m, "accuracy");
  if (acc) {
    int a = yt_enum(t, acc, "campaign.accuracy", accuracy_words);
    if (a < 0) return -1;
    snprintf(c->accuracy, sizeof c->accuracy, "%s", accuracy_words[a]);
  }
  v = (long)c->seed;
  if (integer_in(t, m, "seed", "campaign.seed", 0, LONG_MAX, &v)) return -1;
  c->seed = v;
  if ((n = yt_get(t, m, "voxel_size"))) {
    double size;
    if (yt_double(t, n, "campaign.voxel_size", &size)) return -1;
    if (!(size > 0 && size < 1))
      return yt_error(t, n, "campaign.voxel_size", "expected a voxel edge in metres in (0, 1)");
    snprintf(c->voxel_size, sizeof c->voxel_size, "%.10g", size);
  }
  static const char *const drive_words[] = {"body", "pressure", NULL};
  if ((n = yt_get(t, m, "drive")) &&
      (c->drive_pressure = yt_enum(t, n, "campaign.drive", drive_words)) < 0)
    return -1;
  if ((n = yt_get(t, m, "mpiexec")) &&
      yt_string(t, n, "campaign.mpiexec", c->mpiexec, sizeof c->mpiexec))
    return -1;
  /* The faces of a block cut from a rock do not continue each other: the block campaigns choose
   * their boundary treatment per block and axis (auto, the campaign's default) unless the config
   * forces one; the words are the campaign's --boundary / --sides (docs/permeability.md). */
  static const char *const boundary_words[] = {"auto", "periodic", "mirror", "reservoir", NULL};
  static const char *const sides_words[] = {"periodic", "mirror", NULL};
  yaml_node_t *bn = yt_get(t, m, "boundary");
  if (bn) {
    int b = yt_enum(t, bn, "campaign.boundary", boundary_words);
    if (b < 0) return -1;
    snprintf(c->boundary, sizeof c->boundary, "%s", boundary_words[b]);
    /* the same pairing rule as the campaign's options, said here with the config's line */
    if (c->drive_pressure && (b == 1 || b == 2))
      return yt_error(t, bn, "campaign.boundary",
                      "auto or reservoir with drive: pressure (the pressure drive joins the faces "
                      "through its reservoir; got %s)",
                      boundary_words[b]);
    if (b == 3) c->drive_pressure = 1; /* a reservoir is what the pressure drive runs in */
  }
  static const char *const axes_words[] = {"flow", "all", "auto", NULL};
  if ((n = yt_get(t, m, "axes")) && (c->axes = yt_enum(t, n, "campaign.axes", axes_words)) < 0)
    return -1;
  if ((n = yt_get(t, m, "sides"))) {
    int sd = yt_enum(t, n, "campaign.sides", sides_words);
    if (sd < 0) return -1;
    snprintf(c->sides, sizeof c->sides, "%s", sides_words[sd]);
  }
  return 0;
}

static int read_loop(ytree_t *t, yaml_node_t *m, couple_config *c) {
  if (yt_expect_map(t, m, "loop") || yt_check_keys(t, m, "loop", loop_keys)) return -1;
  long v = c->max_passes;
  if (integer_in(t, m, "max_passes", "loop.max_passes", 2, 16, &v)) return -1;
  c->max_passes = (int)v;
  v = c->error_samples;
  if (integer_in(t, m, "error_samples", "loop.error_samples", 8, 4096, &v)) return -1;
  c->error_samples = (int)v;
  return number_in(t, m, "tolerance_sigma", "loop.tolerance_sigma", 0, 100,
                   "a positive number of standard errors", &c->tolerance_sigma) ||
                 number_in(t, m, "resolvable_fraction", "loop.resolvable_fraction", 0, 1.000001,
                           "a number in (0, 1]", &c->resolvable_fraction)
             ? -1
             : 0;
}

static int read_gradient(ytree_t *t, yaml_node_t *n, couple_config *c) {
  char text[128], why[256];
  if (yt_string(t, n, "gradient", text, sizeof text)) return -1;
  if (!strcmp(text, "auto")) {
    c->gradient_auto = 1;
    return 0;
  }
  c->gradient_auto = 0;
  double v;
  int had_unit = 0;
  /* a plain number: reduced kT/rc^4; with a unit: SI (Pa/m, MPa/m, bar/m, psi/ft ...) */
  if (darcy_unit_parse(text, QTY_GRADIENT, 0, &v, &had_unit, why, sizeof why) == 0 && !had_unit) {
    c->gradient = v;
  } else if (darcy_unit_parse(text, QTY_GRADIENT, 1, &v, &had_unit, why, sizeof why) == 0 &&
             had_unit) {
    c->gradient_si = 1;
    c->gradient_si_value = v;
  } else {
    char list[256];
    return yt_error(t, n, "gradient",
                    "expected auto, a reduced gradient (kT/rc^4) or a gradient with a unit (%s) "
                    "(got '%s': %s)",
                    darcy_unit_list(QTY_GRADIENT, 1, list, sizeof list), text, why);
  }
  double g = c->gradient_si ? c->gradient_si_value : c->gradient;
  if (!(isfinite(g) && g > 0))
    return yt_error(t, n, "gradient", "expected a positive gradient (got '%s')", text);
  return 0;
}

static void defaults(couple_config *c) {
  memset(c, 0, sizeof *c);
  c->blocks[0] = c->blocks[1] = c->blocks[2] = 1;
  c->gradient_auto = 1;
  c->law_choice = COUPLE_LAW_DARCY;
  c->rc_per_voxel = 0.5;
  c->np = 1;
  c->jobs = 1;
  c->n_gradients = 5;
  c->u_lo = 0.02;
  c->u_hi = 0.2;
  c->target_error = 0.05;
  c->max_steps = 20000;
  c->seed = 12345;
  c->max_passes = 4;
  c->tolerance_sigma = 2.0;
  c->resolvable_fraction = 0.5;
  c->error_samples = 32;
  c->launcher = COUPLE_LAUNCH_MPIEXEC;
}

int couple_config_read(const char *path, couple_config *c) {
  defaults(c);
  if (!realpath(path, c->path)) snprintf(c->path, sizeof c->path, "%s", path);
  char dir[COUPLE_PATH];
  snprintf(dir, sizeof dir, "%s", c->path);
  char *slash = strrchr(dir, '/');
  if (slash)
    *slash = 0;
  else
    snprintf(dir, sizeof dir, ".");
  ytree_t t;
  if (yt_load(&t, path, 0)) return -1;
  yaml_node_t *root = yt_root(&t), *n;
  int rc = -1;
  if (!root || yt_expect_map(&t, root, "") || yt_check_keys(&t, root, "", top_keys)) goto out;
  /* workdir: default CONFIG minus its extension + ".couple", next to the config */
  char text[COUPLE_PATH];
  if ((n = yt_get(&t, root, "workdir"))) {
    if (yt_string(&t, n, "workdir", text, sizeof text)) goto out;
    resolve(dir, text, c->workdir, sizeof c->workdir);
  } else {
    snprintf(c->workdir, sizeof c->workdir, "%s", c->path);
    char *dot = strrchr(c->workdir, '.');
    if (dot && dot > strrchr(c->workdir, '/')) *dot = 0;
    strncat(c->workdir, ".couple", sizeof c->workdir - strlen(c->workdir) - 1);
  }
  if ((n = yt_get(&t, root, "blocks"))) {
    if (yt_int3(&t, n, "blocks", c->blocks)) goto out;
    long total = 1;
    for (int a = 0; a < 3; a++) {
      if (c->blocks[a] < 1 || c->blocks[a] > COUPLE_MAX_BLOCKS) {
        yt_error(&t, n, "blocks", "expected three block counts from 1 to %d", COUPLE_MAX_BLOCKS);
        goto out;
      }
      total *= c->blocks[a];
    }
    if (total > COUPLE_MAX_BLOCKS) {
      yt_error(&t, n, "blocks",
               "expected at most %d blocks in all (got %ld): each block is a pore-scale campaign",
               COUPLE_MAX_BLOCKS, total);
      goto out;
    }
  }
  int n_blocks = c->blocks[0] * c->blocks[1] * c->blocks[2];
  yaml_node_t *img = yt_get(&t, root, "image"), *list = yt_get(&t, root, "block_images");
  if ((img != NULL) == (list != NULL)) {
    yt_error(&t, root, img ? "block_images" : "image",
             "expected exactly one of 'image' (split into 'blocks') and 'block_images' (one image "
             "per block, x fastest)");
    goto out;
  }
  if (img) {
    if (yt_string(&t, img, "image", text, sizeof text)) goto out;
    resolve(dir, text, c->image, sizeof c->image);
    if (access(c->image, R_OK)) {
      yt_error(&t, img, "image", "expected a readable image file (got '%s': not found)", text);
      goto out;
    }
  } else {
    if (yt_expect_seq(&t, list, "block_images")) goto out;
    if (yt_seq_size(list) != n_blocks) {
      yt_error(&t, list, "block_images",
               "expected %d images, one per block of blocks [%d, %d, %d], x fastest (got %d)",
               n_blocks, c->blocks[0], c->blocks[1], c->blocks[2], yt_seq_size(list));
      goto out;
    }
    c->n_block_images = n_blocks;
    c->block_image = calloc((size_t)n_blocks, sizeof *c->block_image);
    if (!c->block_image) goto out;
    for (int b = 0; b < n_blocks; b++) {
      char key[64];
      snprintf(key, sizeof key, "block_images[%d]", b);
      n = yt_seq_item(&t, list, b);
      if (yt_string(&t, n, key, text, sizeof text)) goto out;
      resolve(dir, text, c->block_image[b], COUPLE_PATH);
      if (access(c->block_image[b], R_OK)) {
        yt_error(&t, n, key, "expected a readable image file (got '%s': not found)", text);
        goto out;
      }
    }
  }
  if ((n = yt_get(&t, root, "image_labels")) &&
      yt_string(&t, n, "image_labels", c->image_labels, sizeof c->image_labels))
    goto out;
  if ((n = yt_get(&t, root, "image_voxel_size")) &&
      yt_string(&t, n, "image_voxel_size", c->image_voxel_size, sizeof c->image_voxel_size))
    goto out;
  if (!(n = yt_need(&t, root, "axis", "axis", "the flow axis x, y or z"))) goto out;
  if ((c->axis = yt_enum(&t, n, "axis", axis_words)) < 0) goto out;
  if ((n = yt_get(&t, root, "gradient")) && read_gradient(&t, n, c)) goto out;
  if ((n = yt_get(&t, root, "law")) && (c->law_choice = yt_enum(&t, n, "law", law_words)) < 0)
    goto out;
  if ((n = yt_get(&t, root, "campaign")) && read_campaign(&t, n, c)) goto out;
  if ((n = yt_get(&t, root, "loop")) && read_loop(&t, n, c)) goto out;
  if ((n = yt_get(&t, root, "launcher")) &&
      (c->launcher = yt_enum(&t, n, "launcher", launcher_words)) < 0)
    goto out;
  if ((n = yt_get(&t, root, "slurm"))) {
    static const char *const slurm_keys[] = {"header", NULL};
    yaml_node_t *h;
    if (yt_expect_map(&t, n, "slurm") || yt_check_keys(&t, n, "slurm", slurm_keys)) goto out;
    if ((h = yt_get(&t, n, "header")) &&
        yt_string(&t, h, "slurm.header", c->slurm_header, sizeof c->slurm_header))
      goto out;
  }
  rc = 0;
out:
  yt_free(&t);
  return rc;
}

void couple_config_free(couple_config *c) {
  free(c->block_image);
  c->block_image = NULL;
}
