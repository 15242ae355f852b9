/* mdpore image info|convert|make: report porosity and connectivity, convert to HDF5/raw/TIFF, and
 * generate synthetic images. */
#include "mdpore_image.h"
#include "mdpore_image_cli.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

static const cli_help_option_t image_options[] = {
    {"--axis x|y|z",
     "info: fail when that axis does not percolate; stack: the images one after another along it",
     1},
    {"--sizes", "info: add the pore-size distribution and the critical throat per axis", 1},
    {"--periodic", "info --sizes: distances measured across the faces, as a periodic run sees them",
     0},
    {"--json", "info: the report as JSON", 1},
    {"-o OUT", "convert, stack, make: the output image (.h5, .raw or .tif)", 1},
    {NULL, NULL, 0}};

static const cli_help_page_t image_help = {
    .command = "image",
    .usage = "usage: mdpore image info IMAGE [options] [--axis x|y|z] [--sizes [--periodic]]\n"
             "                         [--json]\n"
             "       mdpore image convert IMAGE -o OUT.h5|OUT.raw|OUT.tif [options]\n"
             "       mdpore image stack IMAGE IMAGE [...] --axis x|y|z -o OUT\n"
             "       mdpore image drainage IMAGE --axis x|y|z|none [...]  (its own --help)\n"
             "       mdpore image make slit --width N [--wall W] [--length L] [--depth D]\n"
             "                              -o OUT\n"
             "       mdpore image make cylinders --cell L --c C [--cells N] [--depth D] -o OUT\n"
             "       mdpore image make spheres --cell L --c C [--cells N] -o OUT\n"
             "       mdpore image make random-spheres --size N --radius R --porosity P -o OUT\n"
             "                                        [--seed S]\n"
             "       mdpore image make sphere-file (--box LX,LY,LZ | --box-file FILE) --dx DX\n"
             "                                     --centres FILE --radius R -o OUT\n",
    .purpose = "Segmented 3D images: report, convert, stack, drain and make them.",
    .about = "drainage: the morphological Pc(Sw) curve (see mdpore image drainage --help).\n"
             "info prints porosity, connected porosity per axis, isolated pores and how periodic "
             "the image is per axis (end-slice pore overlap, percolation with and without the "
             "wrap). make labels pore 0 and solid 1; --voxel-size sets the voxel size of made "
             "images.",
    .options = image_options,
    .options2 = mdp_image_cli_options,
    .more = "docs/images.md",
};

static double now_seconds(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int ends_with(const char *s, const char *ext) {
  size_t n = strlen(s), m = strlen(ext);
  return n >= m && !strcasecmp(s + n - m, ext);
}

static int write_any(const mdp_image_t *img, const char *out, char *err) {
  if (ends_with(out, ".raw")) return mdp_image_write_raw(img, out, err);
  if (ends_with(out, ".tif") || ends_with(out, ".tiff")) return mdp_image_write_tiff(img, out, err);
  if (ends_with(out, ".h5") || ends_with(out, ".hdf5")) return mdp_image_write_hdf5(img, out, err);
  snprintf(err, MDP_IMAGE_ERR_LEN, "%s: output name must end in .h5, .hdf5, .raw, .tif or .tiff",
           out);
  return 1;
}

static void print_info(const char *path, const mdp_image_t *img, const mdp_image_stats_t *st,
                       int json) {
  char map[512];
  mdp_image_format_labels(img->phase_of, map, sizeof map);
  double n = (double)st->n_voxels;
  if (json) {
    printf("{\"file\": \"%s\", \"dims\": [%d, %d, %d], \"voxel_size\": %.12g, \"unit\": \"%s\", "
           "\"label_map\": \"%s\", \"voxels\": %lld, \"pore_voxels\": %lld, \"organic_fraction\": "
           "%.12g, \"inorganic_fraction\": %.12g, \"porosity\": %.12g, \"clusters\": %d, "
           "\"connected_porosity\": {\"x\": %.12g, \"y\": %.12g, \"z\": %.12g}, "
           "\"percolates\": {\"x\": %s, \"y\": %s, \"z\": %s}, "
           "\"isolated\": {\"clusters\": %d, \"porosity\": %.12g}, "
           "\"non_spanning\": {\"clusters\": %d, \"porosity\": %.12g}",
           path, img->nx, img->ny, img->nz, img->voxel_size, img->unit, map, st->n_voxels,
           st->n_pore, st->n_organic / n, st->n_inorganic / n, st->porosity, st->n_clusters,
           st->connected_porosity[0], st->connected_porosity[1], st->connected_porosity[2],
           st->spans[0] ? "true" : "false", st->spans[1] ? "true" : "false",
           st->spans[2] ? "true" : "false", st->n_isolated_clusters, st->isolated_voxels / n,
           st->n_nonspanning_clusters, st->nonspanning_voxels / n);
    return;
  }
  printf("image        %s\n", path);
  printf("dims         %d x %d x %d voxels (x fastest), voxel %.6g %s\n", img->nx, img->ny, img->nz,
         img->voxel_size, img->unit);
  printf("label map    %s\n", map);
  printf("phases       pore %.6f  organic %.6f  inorganic %.6f (volume fractions)\n", st->porosity,
         st->n_organic / n, st->n_inorganic / n);
  printf("porosity     %.6f (%lld of %lld voxels), %d pore clusters (6-connected)\n", st->porosity,
         st->n_pore, st->n_voxels, st->n_clusters);
  for (int a = 0; a < 3; a++)
    printf("axis %c       %s, connected porosity %.6f\n", 'x' + a,
           st->spans[a] ? "percolates" : "does NOT percolate", st->connected_porosity[a]);
  printf("isolated     %d clusters touching no face, porosity %.6f\n", st->n_isolated_clusters,
         st->isolated_voxels / n);
  printf("non-spanning %d clusters spanning no axis (isolated + dead ends), porosity %.6f\n",
         st->n_nonspanning_clusters, st->nonspanning_voxels / n);
}

/* Periodicity (always) and sizes (with --sizes) after the basic report; closes the JSON object. */
static void print_extras(const mdp_image_t *img, const mdp_image_axis_periodicity_t *per,
                         const mdp_image_pore_sizes_t *ps, double seconds, int json) {
  const double n = (double)mdp_image_count(img);
  if (json) {
    printf(", \"periodicity\": {");
    for (int a = 0; a < 3; a++) {
      const mdp_image_axis_periodicity_t *p = &per[a];
      printf("%s\"%c\": {\"face_voxels\": %lld, \"pore_first\": %lld, \"pore_last\": %lld, "
             "\"pore_both\": %lld, \"pore_either\": %lld, \"overlap\": %.12g, "
             "\"overlap_face\": %.12g, \"percolates_open\": %s, \"percolates_wrap\": %s, "
             "\"connected_porosity_open\": %.12g, \"connected_porosity_wrap\": %.12g, "
             "\"wrap_only\": {\"clusters\": %d, \"porosity\": %.12g}, "
             "\"seam_blocked\": {\"clusters\": %d, \"porosity\": %.12g}}",
             a ? ", " : "", 'x' + a, p->face_voxels, p->pore_first, p->pore_last, p->pore_both,
             p->pore_either, p->overlap, p->overlap_face, p->percolates_open ? "true" : "false",
             p->percolates_wrap ? "true" : "false", p->connected_open / n, p->connected_wrap / n,
             p->wrap_only_clusters, p->wrap_only_voxels / n, p->seam_blocked_clusters,
             p->seam_blocked_voxels / n);
    }
    printf("}");
    if (ps) {
      printf(", \"sizes\": {\"periodic\": [%s, %s, %s], \"voxels\": %lld, \"no_solid\": %s, ",
             ps->periodic[0] ? "true" : "false", ps->periodic[1] ? "true" : "false",
             ps->periodic[2] ? "true" : "false", ps->voxels, ps->no_solid ? "true" : "false");
      if (ps->no_solid || ps->voxels == 0)
        printf("\"diameter_voxels\": null, ");
      else
        printf("\"diameter_voxels\": {\"p10\": %.6g, \"p25\": %.6g, \"p50\": %.6g, \"p75\": "
               "%.6g, \"p90\": %.6g, \"mean\": %.6g, \"max\": %.6g}, ",
               ps->diameter_q[0], ps->diameter_q[1], ps->diameter_q[2], ps->diameter_q[3],
               ps->diameter_q[4], ps->diameter_mean, ps->diameter_max);
      printf("\"critical_throat_voxels\": {\"x\": %d, \"y\": %d, \"z\": %d}, \"labellings\": %d, "
             "\"seconds\": %.3f}",
             ps->throat[0], ps->throat[1], ps->throat[2], ps->labellings, seconds);
    }
    printf("}\n");
    return;
  }
  for (int a = 0; a < 3; a++) {
    const mdp_image_axis_periodicity_t *p = &per[a];
    printf("periodic %c   end slices: pore on both %lld of %lld pore on either (overlap %.4f), "
           "%.4f of the face\n",
           'x' + a, p->pore_both, p->pore_either, p->overlap, p->overlap_face);
    printf("             wrapped: %s, connected porosity %.6f (face to face %.6f); the wrap adds "
           "%d clusters (%.6f), the seam blocks %d (%.6f)\n",
           p->percolates_wrap ? "percolates" : "does NOT percolate", p->connected_wrap / n,
           p->connected_open / n, p->wrap_only_clusters, p->wrap_only_voxels / n,
           p->seam_blocked_clusters, p->seam_blocked_voxels / n);
  }
  if (!ps) return;
  const char *across = ps->periodic[0] || ps->periodic[1] || ps->periodic[2]
                           ? "distances across the faces (periodic)"
                           : "faces open";
  if (ps->voxels == 0) {
    printf("sizes        no pore cluster spans an axis: no percolating pore space\n");
  } else if (ps->no_solid) {
    printf("sizes        no solid voxel: pore sizes unbounded\n");
  } else {
    printf("pore size    inscribed diameter of the percolating pore space (voxels, by volume): "
           "p10 %.3g  p25 %.3g  p50 %.3g  p75 %.3g  p90 %.3g  mean %.3g  max %.3g\n",
           ps->diameter_q[0], ps->diameter_q[1], ps->diameter_q[2], ps->diameter_q[3],
           ps->diameter_q[4], ps->diameter_mean, ps->diameter_max);
  }
  printf("throat       critical (breakthrough) diameter, voxels: x %d  y %d  z %d (%s; %d "
         "labellings, %.2f s)\n",
         ps->throat[0], ps->throat[1], ps->throat[2], across, ps->labellings, seconds);
}

static int axis_of(const char *s) {
  return !strcmp(s, "x") ? 0 : !strcmp(s, "y") ? 1 : !strcmp(s, "z") ? 2 : -1;
}

static int cmd_info_or_convert(int argc, char **argv, int convert) {
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_cli_t cli;
  mdp_image_cli_init(&cli);
  const char *path = NULL, *out = NULL;
  int json = 0, axis = -1, sizes = 0, periodic = 0;
  for (int i = 1; i < argc;) {
    int r = mdp_image_cli_parse(argc, argv, &i, &cli, err);
    if (r < 0) {
      fprintf(stderr, "mdpore image: %s\n", err);
      return 2;
    }
    if (r) continue;
    if (!strcmp(argv[i], "--json")) {
      json = 1;
    } else if (!strcmp(argv[i], "--sizes")) {
      sizes = 1;
    } else if (!strcmp(argv[i], "--periodic")) {
      periodic = 1;
    } else if (!strcmp(argv[i], "--axis") && i + 1 < argc) {
      if ((axis = axis_of(argv[++i])) < 0) {
        fprintf(stderr, "mdpore image: --axis '%s': expected x, y or z\n", argv[i]);
        return 2;
      }
    } else if (!strcmp(argv[i], "-o") && i + 1 < argc) {
      out = argv[++i];
    } else if (argv[i][0] == '-') {
      fprintf(stderr, "mdpore image: unknown option '%s' (see mdpore image --help)\n", argv[i]);
      return 2;
    } else if (!path) {
      path = argv[i];
    } else {
      fprintf(stderr, "mdpore image: unexpected argument '%s'\n", argv[i]);
      return 2;
    }
    i++;
  }
  if (!path || (convert && !out)) {
    cli_help_print(stderr, &image_help, CLI_HELP_SHORT);
    return 2;
  }
  mdp_image_t img;
  if (mdp_image_cli_load(path, &cli, &img, err)) {
    fprintf(stderr, "mdpore image: %s\n", err);
    return 1;
  }
  int rc = 0;
  if (convert) {
    if (write_any(&img, out, err)) {
      fprintf(stderr, "mdpore image: %s\n", err);
      rc = 1;
    } else {
      printf("wrote %s (%d x %d x %d)\n", out, img.nx, img.ny, img.nz);
    }
  } else {
    mdp_image_stats_t st;
    mdp_image_axis_periodicity_t per[3];
    mdp_image_pore_sizes_t ps;
    const int across[3] = {periodic, periodic, periodic};
    double t0 = 0, t1 = 0;
    if (mdp_image_stats(&img, &st, err) || mdp_image_periodicity(&img, per, err) ||
        (t0 = now_seconds(), sizes && mdp_image_pore_sizes(&img, across, &ps, err))) {
      fprintf(stderr, "mdpore image: %s\n", err);
      rc = 1;
    } else {
      t1 = now_seconds();
      print_info(path, &img, &st, json);
      print_extras(&img, per, sizes ? &ps : NULL, t1 - t0, json);
      if (st.n_pore == 0 || axis >= 0) {
        if (mdp_image_require_percolation(&img, &st, axis < 0 ? 0 : axis, path, err) &&
            (axis >= 0 || st.n_pore == 0)) {
          fprintf(stderr, "mdpore image: %s\n", err);
          rc = 1;
        }
      }
    }
  }
  mdp_image_free(&img);
  return rc;
}

static int read_box_file(const char *path, double box[3], char *err) {
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: cannot open box file", path);
    return 1;
  }
  char line[512];
  int found = 0;
  while (fgets(line, sizeof line, f)) { /* "Relaxed State: Lx:55.18 Ly:55.40 Lz:55.54" wins */
    char *lx = strstr(line, "Lx:"), *ly = strstr(line, "Ly:"), *lz = strstr(line, "Lz:");
    if (!lx || !ly || !lz) continue;
    if (found && !strstr(line, "Relaxed")) continue;
    box[0] = atof(lx + 3), box[1] = atof(ly + 3), box[2] = atof(lz + 3);
    if (!(isfinite(box[0]) && isfinite(box[1]) && isfinite(box[2]))) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s: 'Lx: Ly: Lz:' box sizes: expected finite numbers",
               path);
      fclose(f);
      return 1;
    }
    found = 1;
  }
  fclose(f);
  if (!found) snprintf(err, MDP_IMAGE_ERR_LEN, "%s: no line with 'Lx: Ly: Lz:' box sizes", path);
  return !found;
}

/* A whole-text integer 0..INT_MAX of option `opt`; 0, or 2 (usage) after a message naming it. */
static int make_int(const char *opt, const char *v, int *out) {
  char *end;
  errno = 0;
  const long x = strtol(v, &end, 10);
  if (errno || end == v || *end || x < 0 || x > INT_MAX) {
    fprintf(stderr, "mdpore image make: %s '%s': expected an integer 0 to %d\n", opt, v, INT_MAX);
    return 2;
  }
  *out = (int)x;
  return 0;
}

/* A whole-text finite number of option `opt`; 0, or 2 (usage) after a message naming it. */
static int make_num(const char *opt, const char *v, double *out) {
  char *end;
  errno = 0;
  const double x = strtod(v, &end);
  if (errno || end == v || *end || !isfinite(x)) {
    fprintf(stderr, "mdpore image make: %s '%s': expected a finite number\n", opt, v);
    return 2;
  }
  *out = x;
  return 0;
}

static int cmd_make(int argc, char **argv) {
  char err[MDP_IMAGE_ERR_LEN];
  if (argc < 2) {
    cli_help_print(stderr, &image_help, CLI_HELP_SHORT);
    return 2;
  }
  const char *kind = argv[1], *out = NULL, *centres = NULL, *box_file = NULL;
  int width = 0, wall = 1, length = 4, depth = 1, cell = 0, cells = 1, size = 0;
  double c = 0, radius = 0, porosity = 0, dx = 0, box[3] = {0, 0, 0}, vsize = 0;
  char unit[8] = "";
  unsigned long long seed = 1;
  const struct {
    const char *opt;
    int *to;
  } ints[] = {{"--width", &width}, {"--wall", &wall},   {"--length", &length}, {"--depth", &depth},
              {"--cell", &cell},   {"--cells", &cells}, {"--size", &size}};
  const struct {
    const char *opt;
    double *to;
  } nums[] = {{"--c", &c}, {"--radius", &radius}, {"--porosity", &porosity}, {"--dx", &dx}};
  for (int i = 2; i < argc; i++) {
    const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!v) {
      fprintf(stderr, "mdpore image make: option %s needs a value\n", o);
      return 2;
    }
    i++;
    int done = 0;
    for (size_t k = 0; k < sizeof ints / sizeof ints[0] && !done; k++)
      if (!strcmp(o, ints[k].opt)) {
        if (make_int(o, v, ints[k].to)) return 2;
        done = 1;
      }
    for (size_t k = 0; k < sizeof nums / sizeof nums[0] && !done; k++)
      if (!strcmp(o, nums[k].opt)) {
        if (make_num(o, v, nums[k].to)) return 2;
        done = 1;
      }
    if (done) continue;
    if (!strcmp(o, "-o"))
      out = v;
    else if (!strcmp(o, "--seed")) {
      char *end;
      errno = 0;
      seed = strtoull(v, &end, 10);
      if (errno || end == v || *end || v[0] == '-') {
        fprintf(stderr, "mdpore image make: --seed '%s': expected an integer 0 to 2^64-1\n", v);
        return 2;
      }
    } else if (!strcmp(o, "--centres") || !strcmp(o, "--centers"))
      centres = v;
    else if (!strcmp(o, "--box-file"))
      box_file = v;
    else if (!strcmp(o, "--box")) {
      int end = 0;
      if (sscanf(v, "%lf,%lf,%lf%n", &box[0], &box[1], &box[2], &end) != 3 || v[end] ||
          !(isfinite(box[0]) && isfinite(box[1]) && isfinite(box[2]))) {
        fprintf(stderr, "mdpore image make: --box '%s': expected LX,LY,LZ, three finite numbers\n",
                v);
        return 2;
      }
    } else if (!strcmp(o, "--voxel-size")) {
      if (mdp_image_parse_voxel_size(v, &vsize, unit, err)) {
        fprintf(stderr, "mdpore image make: option --voxel-size: %s\n", err);
        return 2;
      }
    } else {
      fprintf(stderr, "mdpore image make: unknown option '%s'\n", o);
      return 2;
    }
  }
  if (!out) {
    fprintf(stderr, "mdpore image make: -o OUT is required\n");
    return 2;
  }
  mdp_image_t img;
  double achieved = -1;
  int rc;
  if (!strcmp(kind, "slit"))
    rc = mdp_make_slit(&img, width, wall, length, depth, err);
  else if (!strcmp(kind, "cylinders"))
    rc = mdp_make_cylinders(&img, cell, c, cells, depth, &achieved, err);
  else if (!strcmp(kind, "spheres"))
    rc = mdp_make_spheres(&img, cell, c, cells, &achieved, err);
  else if (!strcmp(kind, "random-spheres"))
    rc = mdp_make_random_spheres(&img, size, radius, porosity, seed, err);
  else if (!strcmp(kind, "sphere-file")) {
    rc = (!centres ? (snprintf(err, MDP_IMAGE_ERR_LEN, "sphere-file needs --centres FILE"), 1) : 0);
    if (!rc && box_file) rc = read_box_file(box_file, box, err);
    if (!rc) rc = mdp_make_sphere_file(&img, centres, box, radius, dx, err);
  } else {
    fprintf(stderr,
            "mdpore image make: unknown kind '%s' (slit, cylinders, spheres, random-spheres, "
            "sphere-file)\n",
            kind);
    return 2;
  }
  if (rc) {
    fprintf(stderr, "mdpore image make: %s\n", err);
    return 1;
  }
  if (vsize > 0) img.voxel_size = vsize;
  if (unit[0]) memcpy(img.unit, unit, sizeof unit);
  mdp_image_stats_t st;
  rc = mdp_image_stats(&img, &st, err) || write_any(&img, out, err);
  if (rc) {
    fprintf(stderr, "mdpore image make: %s\n", err);
  } else {
    printf("{\"made\": \"%s\", \"file\": \"%s\", \"dims\": [%d, %d, %d], \"porosity\": %.8f", kind,
           out, img.nx, img.ny, img.nz, st.porosity);
    if (achieved >= 0)
      printf(", \"solid_fraction\": %.8f, \"requested_solid_fraction\": %.8f", achieved, c);
    printf("}\n");
  }
  mdp_image_free(&img);
  return rc;
}

/* mdpore image stack A B [C ...] --axis x|y|z -o OUT: the images one after another along an axis
 * (a layered sample, e.g. for mdpore couple). */
static int cmd_stack(int argc, char **argv) {
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_cli_t cli;
  mdp_image_cli_init(&cli);
  const char *out = NULL, *inputs[64];
  int n = 0, axis = -1;
  for (int i = 1; i < argc;) {
    int r = mdp_image_cli_parse(argc, argv, &i, &cli, err);
    if (r < 0) {
      fprintf(stderr, "mdpore image stack: %s\n", err);
      return 2;
    }
    if (r) continue;
    if (!strcmp(argv[i], "--axis") && i + 1 < argc) {
      if ((axis = axis_of(argv[++i])) < 0) {
        fprintf(stderr, "mdpore image stack: --axis '%s': expected x, y or z\n", argv[i]);
        return 2;
      }
    } else if (!strcmp(argv[i], "-o") && i + 1 < argc) {
      out = argv[++i];
    } else if (argv[i][0] == '-') {
      fprintf(stderr, "mdpore image stack: unknown option '%s'\n", argv[i]);
      return 2;
    } else if (n < 64) {
      inputs[n++] = argv[i];
    } else {
      fprintf(stderr, "mdpore image stack: at most 64 images\n");
      return 2;
    }
    i++;
  }
  if (n < 2 || axis < 0 || !out) {
    fprintf(stderr, "mdpore image stack: expected two or more images, --axis x|y|z and -o OUT\n");
    return 2;
  }
  mdp_image_t acc;
  if (mdp_image_cli_load(inputs[0], &cli, &acc, err)) {
    fprintf(stderr, "mdpore image stack: %s\n", err);
    return 1;
  }
  for (int i = 1; i < n; i++) {
    mdp_image_t next, joined;
    if (mdp_image_cli_load(inputs[i], &cli, &next, err)) {
      fprintf(stderr, "mdpore image stack: %s\n", err);
      mdp_image_free(&acc);
      return 1;
    }
    int bad = mdp_image_concat(&acc, &next, axis, &joined, err);
    mdp_image_free(&next);
    mdp_image_free(&acc);
    if (bad) {
      fprintf(stderr, "mdpore image stack: %s: %s\n", inputs[i], err);
      return 1;
    }
    acc = joined;
  }
  int rc = write_any(&acc, out, err);
  if (rc)
    fprintf(stderr, "mdpore image stack: %s\n", err);
  else
    printf("wrote %s (%d x %d x %d)\n", out, acc.nx, acc.ny, acc.nz);
  mdp_image_free(&acc);
  return rc ? 1 : 0;
}

int cmd_image(int argc, char **argv) {
  if (argc < 2 || cli_help_flag(argv[1])) {
    cli_help_print(argc < 2 ? stderr : stdout, &image_help,
                   argc < 2 ? CLI_HELP_SHORT : cli_help_flag(argv[1]));
    return argc < 2 ? 2 : 0;
  }
  /* info, convert, make and stack share this page (drainage has its own) */
  if (strcmp(argv[1], "drainage"))
    for (int i = 2; i < argc; i++)
      if (cli_help_flag(argv[i])) {
        cli_help_print(stdout, &image_help, cli_help_flag(argv[i]));
        return 0;
      }
  if (!strcmp(argv[1], "info")) return cmd_info_or_convert(argc - 1, argv + 1, 0);
  if (!strcmp(argv[1], "convert")) return cmd_info_or_convert(argc - 1, argv + 1, 1);
  if (!strcmp(argv[1], "make")) return cmd_make(argc - 1, argv + 1);
  if (!strcmp(argv[1], "stack")) return cmd_stack(argc - 1, argv + 1);
  if (!strcmp(argv[1], "drainage")) return cmd_image_drainage(argc - 1, argv + 1);
  fprintf(stderr, "mdpore image: unknown subcommand '%s' (info, convert, make, stack, drainage)\n",
          argv[1]);
  return 2;
}
