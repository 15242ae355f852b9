/* mdpore image drainage: the morphological capillary pressure curve Pc(Sw) of an image
 * (image_morph.c; docs/relperm.md section 2): the CSV DIR/pc_morph.csv, its plot DIR/pc_morph.png
 * (plot_pc_morph.py, python3 + matplotlib), and with --at SNW --write-image FILE the phase
 * distribution nearest that saturation as a labelled image. */
#include "common/units.h"
#include "mdpore_image.h"
#include "mdpore_image_cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#ifndef MDPORE_PYTHON_EXE
#define MDPORE_PYTHON_EXE "/usr/bin/python3"
#endif
#ifndef MDPORE_MORPH_PLOT_SCRIPT
#define MDPORE_MORPH_PLOT_SCRIPT "plot_pc_morph.py"
#endif

/* gamma_wo cos(theta_wo) of the standard water/oil pair set (docs/twophase.md: 8.67 +- 0.22
 * reduced units, kT / rc^2). */
#define MORPH_DEFAULT_GAMMA_COS 8.67
/* The depletion the capillary entry brackets of docs/twophase.md section 7 fit: an effective slit
 * width H - 2.3 rc, i.e. each wall's interface radius short by 1.15 rc (an interpretation). */
#define MORPH_DEPLETION_RC 1.15
/* Room temperature of the energy unit kT when converting to Pa (as mdpore permeability). */
#define MORPH_TEMPERATURE_K UNITS_DEFAULT_TEMPERATURE

static const cli_help_option_t drainage_options[] = {
    {"--axis A",
     "x, y, z (inlet: the low face, outlet: the high face) or none (no connectivity rule, no "
     "trapping)",
     1},
    {"--imbibition", "R ascending from a pore space full of non-wetting phase", 1},
    {"--no-trapping", "the defending phase leaves even when cut off from the outlet", 1},
    {"--periodic", "distances measured across the faces of the axes other than --axis", 0},
    {"--gamma-cos V",
     "gamma cos(theta), reduced units kT/rc^2 (default 8.67, the standard water/oil pair set, "
     "docs/twophase.md)",
     0},
    {"--rc-per-voxel R", "voxel edge in rc (default 0.5, as mdpore permeability)", 1},
    {"--k K --phi PHI",
     "permeability and porosity for the Leverett J column; K in rc^2, or with a unit: 2.5vox2, "
     "1e-12m2, 150mD, 0.2D, 500nD",
     0},
    {"-o DIR", "output folder (default .): DIR/pc_morph.csv and DIR/pc_morph.png", 1},
    {"--no-plot", "no PNG", 0},
    {"--at SNW --write-image FILE",
     "the phase distribution nearest non-wetting saturation SNW, its non-wetting voxels labelled "
     "--nw-label (default 3, pore)",
     1},
    {NULL, NULL, 0}};

static const cli_help_page_t drainage_help = {
    .command = "image drainage",
    .usage = "usage: mdpore image drainage IMAGE --axis x|y|z|none [options]\n",
    .purpose = "The morphological (Hilpert-Miller) drainage or imbibition curve of an image.",
    .about = "At sphere radius R the non-wetting phase holds the balls of radius R that fit in "
             "the pore space (and, in drainage, reach them from the low face of --axis). Pc = 2 "
             "gamma cos(theta) / r.",
    .options = drainage_options,
    .options2 = mdp_image_cli_options,
    .notes = "Pa columns when the voxel size is known (the image's or --voxel-size): rc = voxel "
             "size / rc-per-voxel, pressure unit kT/rc^3 at 298.15 K.",
    .more = "docs/relperm.md",
};

typedef struct {
  const char *path, *out_dir, *write_image, *k_text;
  int axis, imbibition, trapping, periodic, plot, nw_label;
  double gamma_cos, rc_per_voxel, phi, at;
} drain_args_t;

/* A positive finite number; 0, or 1 after a message naming the option. */
static int number(const char *opt, const char *v, double lo, double hi, double *out) {
  char *end = NULL;
  errno = 0;
  const double x = strtod(v, &end);
  if (end == v || *end || errno || !isfinite(x) || x < lo || x > hi) {
    fprintf(stderr, "mdpore image drainage: %s '%s': expected a number in [%g, %g]\n", opt, v, lo,
            hi);
    return 1;
  }
  *out = x;
  return 0;
}

/* --k: K in rc^2, or with a unit vox2, m2, D, mD, nD, into rc^2 (rc_m: metres per rc, 0 when the
 * scale is unknown; h: rc per voxel). */
static int k_in_rc2(const char *text, double rc_m, double h, double *k) {
  char *end = NULL;
  const double x = strtod(text, &end);
  double factor = 1; /* rc^2 per given unit */
  const char *unit = end;
  if (!*unit)
    factor = 1;
  else if (!strcmp(unit, "vox2"))
    factor = h * h;
  else if (!strcmp(unit, "m2") || !strcmp(unit, "D") || !strcmp(unit, "mD") ||
           !strcmp(unit, "nD")) {
    if (rc_m <= 0) {
      fprintf(stderr,
              "mdpore image drainage: --k '%s': a permeability in %s needs the voxel size (the "
              "image has none: give --voxel-size, or K in rc^2 or vox2)\n",
              text, unit);
      return 1;
    }
    const double m2 = !strcmp(unit, "m2")   ? 1.0
                      : !strcmp(unit, "D")  ? UNITS_DARCY_M2
                      : !strcmp(unit, "mD") ? 1e-3 * UNITS_DARCY_M2
                                            : 1e-9 * UNITS_DARCY_M2;
    factor = m2 / (rc_m * rc_m);
  } else {
    factor = -1;
  }
  if (end == text || factor < 0 || !(x > 0) || !isfinite(x)) {
    fprintf(stderr,
            "mdpore image drainage: --k '%s': expected a permeability > 0 in rc^2, or with a "
            "unit vox2, m2, D, mD, nD\n",
            text);
    return 1;
  }
  *k = x * factor;
  return 0;
}

static int parse_args(int argc, char **argv, mdp_image_cli_t *cli, drain_args_t *a) {
  char err[MDP_IMAGE_ERR_LEN];
  memset(a, 0, sizeof *a);
  a->axis = -2, a->trapping = 1, a->plot = 1, a->nw_label = 3;
  a->gamma_cos = MORPH_DEFAULT_GAMMA_COS, a->rc_per_voxel = 0.5, a->phi = -1, a->at = -1;
  a->out_dir = ".";
  for (int i = 1; i < argc;) {
    const int r = mdp_image_cli_parse(argc, argv, &i, cli, err);
    if (r < 0) {
      fprintf(stderr, "mdpore image drainage: %s\n", err);
      return 2;
    }
    if (r) continue;
    const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(o, "--imbibition")) {
      a->imbibition = 1;
    } else if (!strcmp(o, "--no-trapping")) {
      a->trapping = 0;
    } else if (!strcmp(o, "--periodic")) {
      a->periodic = 1;
    } else if (!strcmp(o, "--no-plot")) {
      a->plot = 0;
    } else if (o[0] == '-' && o[1] && !v) {
      fprintf(stderr, "mdpore image drainage: option %s needs a value\n", o);
      return 2;
    } else if (!strcmp(o, "--axis")) {
      a->axis = !strcmp(v, "x")      ? 0
                : !strcmp(v, "y")    ? 1
                : !strcmp(v, "z")    ? 2
                : !strcmp(v, "none") ? -1
                                     : -3;
      if (a->axis == -3) {
        fprintf(stderr, "mdpore image drainage: --axis '%s': expected x, y, z or none\n", v);
        return 2;
      }
      i++;
    } else if (!strcmp(o, "--gamma-cos")) {
      if (number(o, v, 1e-300, HUGE_VAL, &a->gamma_cos)) return 2;
      i++;
    } else if (!strcmp(o, "--rc-per-voxel")) {
      if (number(o, v, 1e-300, HUGE_VAL, &a->rc_per_voxel)) return 2;
      i++;
    } else if (!strcmp(o, "--phi")) {
      if (number(o, v, 1e-300, 1, &a->phi)) return 2;
      i++;
    } else if (!strcmp(o, "--k")) {
      a->k_text = v;
      i++;
    } else if (!strcmp(o, "--at")) {
      if (number(o, v, 0, 1, &a->at)) return 2;
      i++;
    } else if (!strcmp(o, "--nw-label")) {
      double x = 0;
      if (number(o, v, 0, 255, &x) || x != floor(x)) {
        fprintf(stderr, "mdpore image drainage: --nw-label '%s': expected an integer 0..255\n", v);
        return 2;
      }
      a->nw_label = (int)x;
      i++;
    } else if (!strcmp(o, "--write-image")) {
      a->write_image = v;
      i++;
    } else if (!strcmp(o, "-o")) {
      a->out_dir = v;
      i++;
    } else if (o[0] == '-') {
      fprintf(stderr,
              "mdpore image drainage: unknown option '%s' (see mdpore image drainage --help)\n", o);
      return 2;
    } else if (!a->path) {
      a->path = o;
    } else {
      fprintf(stderr, "mdpore image drainage: unexpected argument '%s'\n", o);
      return 2;
    }
    i++;
  }
  if (!a->path || a->axis == -2) {
    fprintf(stderr, "mdpore image drainage: expected IMAGE and --axis x|y|z|none\n");
    return 2;
  }
  if (!!a->k_text != (a->phi > 0)) {
    fprintf(stderr, "mdpore image drainage: --k and --phi go together (the Leverett J column)\n");
    return 2;
  }
  if ((a->at >= 0) != !!a->write_image) {
    fprintf(stderr, "mdpore image drainage: --at SNW and --write-image FILE go together\n");
    return 2;
  }
  return 0;
}

static int ends_with(const char *s, const char *ext) {
  const size_t n = strlen(s), m = strlen(ext);
  return n >= m && !strcasecmp(s + n - m, ext);
}

static int write_any(const mdp_image_t *img, const char *out, char *err) {
  if (ends_with(out, ".raw")) return mdp_image_write_raw(img, out, err);
  if (ends_with(out, ".tif") || ends_with(out, ".tiff")) return mdp_image_write_tiff(img, out, err);
  if (ends_with(out, ".h5") || ends_with(out, ".hdf5")) return mdp_image_write_hdf5(img, out, err);
  snprintf(err, MDP_IMAGE_ERR_LEN,
           "--write-image %s: the name must end in .h5, .hdf5, .raw, .tif or .tiff", out);
  return 1;
}

/* The CSV: '#' lines with every definition, then one row per step. */
static int write_csv(const char *path, const drain_args_t *a, const mdp_image_t *img,
                     const mdp_morph_step_t *st, int n, double rc_m, double k_rc2) {
  char tmp[4200];
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *f = fopen(tmp, "w");
  if (!f) {
    fprintf(stderr, "mdpore image drainage: %s: cannot write (%s)\n", tmp, strerror(errno));
    return 1;
  }
  units_si_t u;
  memset(&u, 0, sizeof u);
  if (rc_m > 0) units_make(rc_m, UNITS_KB * MORPH_TEMPERATURE_K, units_water_mass(rc_m, 6.2), &u);
  const char *ax = a->axis < 0 ? "none" : a->axis == 0 ? "x" : a->axis == 1 ? "y" : "z";
  fprintf(f, "# mdpore image drainage: morphological %s (Hilpert & Miller 2001) of %s\n",
          a->imbibition ? "imbibition (R ascending)" : "drainage (R descending)", a->path);
  fprintf(f,
          "# image %d x %d x %d voxels, %lld pore voxels; axis %s (%s); trapping %s; "
          "distances %s\n",
          img->nx, img->ny, img->nz, n ? st[0].pore_voxels : 0LL, ax,
          a->axis < 0     ? "no connectivity rule"
          : a->imbibition ? "the non-wetting phase escapes through the high face"
                          : "invaded from the low face, wetting escapes through the high face",
          a->trapping && a->axis >= 0 ? "on" : "off",
          a->periodic ? "across the faces of the other axes" : "faces open");
  fprintf(f, "# radius_vox: sphere radius R in voxels (ball centres at least R from every solid "
             "voxel centre; the voxels whose centre lies less than R from a centre are covered)\n");
  fprintf(f, "# radius_rc = R * rc_per_voxel, rc_per_voxel = %g\n", a->rc_per_voxel);
  fprintf(f, "# Snw = non-wetting pore voxels / pore voxels; Sw = 1 - Snw; trapped = voxels of "
             "the defending phase cut off from the outlet / pore voxels\n");
  fprintf(f, "# pc = 2 gamma_cos / radius_rc in kT/rc^3, gamma_cos = %g kT/rc^2%s\n", a->gamma_cos,
          a->gamma_cos == MORPH_DEFAULT_GAMMA_COS
              ? " (the standard water/oil pair set, docs/twophase.md: 8.67 +- 0.22)"
              : "");
  fprintf(f,
          "# pc_depleted = 2 gamma_cos / (radius_rc - %g): an interpretation, not a "
          "measurement: the capillary entry brackets of docs/twophase.md section 7 fit an "
          "effective width H - 2.3 rc (empty where radius_rc <= %g)\n",
          MORPH_DEPLETION_RC, MORPH_DEPLETION_RC);
  if (rc_m > 0)
    fprintf(f,
            "# pc_Pa, pc_depleted_Pa: x %.6g Pa per kT/rc^3 (rc = voxel %.6g m / rc_per_voxel "
            "= %.6g m, kT at %g K): the model's pressure at that scale\n",
            u.p_Pa, rc_m * a->rc_per_voxel, rc_m, MORPH_TEMPERATURE_K);
  else
    fprintf(f, "# pc_Pa, pc_depleted_Pa: empty (the image has no physical voxel size; give "
               "--voxel-size)\n");
  if (k_rc2 > 0)
    fprintf(f,
            "# J = pc sqrt(k / phi) / gamma_cos = 2 sqrt(k / phi) / radius_rc (Leverett), k = "
            "%.6g rc^2, phi = %g\n",
            k_rc2, a->phi);
  else
    fprintf(f, "# J: empty (give --k and --phi)\n");
  fprintf(f, "# nw_spans: 1 when a non-wetting cluster touches both faces of the axis\n");
  fprintf(f, "step,radius_vox,radius_rc,Sw,Snw,trapped,nw_spans,pc,pc_depleted,pc_Pa,"
             "pc_depleted_Pa,J\n");
  for (int i = 0; i < n; i++) {
    const double r = st[i].radius * a->rc_per_voxel, pc = 2 * a->gamma_cos / r;
    const double rd = r - MORPH_DEPLETION_RC, pcd = rd > 0 ? 2 * a->gamma_cos / rd : NAN;
    fprintf(f, "%d,%.6g,%.6g,%.8f,%.8f,%.8f,%d,%.8g,", i, st[i].radius, r, 1 - st[i].snw, st[i].snw,
            st[i].pore_voxels ? (double)st[i].trapped_voxels / (double)st[i].pore_voxels : 0.0,
            st[i].nw_spans, pc);
    if (isfinite(pcd)) fprintf(f, "%.8g", pcd);
    fputc(',', f);
    if (rc_m > 0) fprintf(f, "%.8g", pc * u.p_Pa);
    fputc(',', f);
    if (rc_m > 0 && isfinite(pcd)) fprintf(f, "%.8g", pcd * u.p_Pa);
    fputc(',', f);
    if (k_rc2 > 0) fprintf(f, "%.8g", 2 * sqrt(k_rc2 / a->phi) / r);
    fputc('\n', f);
  }
  if (fclose(f) != 0 || rename(tmp, path) != 0) {
    fprintf(stderr, "mdpore image drainage: %s: cannot write (%s)\n", path, strerror(errno));
    remove(tmp);
    return 1;
  }
  return 0;
}

/* mkdir -p: the folder and its missing parents. 0, or -1 with errno. */
static int make_dirs(const char *path) {
  char p[4096];
  if (snprintf(p, sizeof p, "%s", path) >= (int)sizeof p) {
    errno = ENAMETOOLONG;
    return -1;
  }
  for (char *c = p + 1; *c; c++)
    if (*c == '/') {
      *c = 0;
      if (mkdir(p, 0777) != 0 && errno != EEXIST) return -1;
      *c = '/';
    }
  return mkdir(p, 0777) != 0 && errno != EEXIST ? -1 : 0;
}

int cmd_image_drainage(int argc, char **argv) {
  for (int i = 1; i < argc; i++)
    if (cli_help_flag(argv[i])) {
      cli_help_print(stdout, &drainage_help, cli_help_flag(argv[i]));
      return 0;
    }
  mdp_image_cli_t cli;
  mdp_image_cli_init(&cli);
  drain_args_t a;
  int rc = parse_args(argc, argv, &cli, &a);
  if (rc) {
    if (rc == 2 && argc < 2) cli_help_print(stderr, &drainage_help, CLI_HELP_SHORT);
    return rc;
  }
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_t img;
  if (mdp_image_cli_load(a.path, &cli, &img, err)) {
    fprintf(stderr, "mdpore image drainage: %s\n", err);
    return 1;
  }
  const double voxel_m = mdp_image_voxel_size_m(&img);
  const double rc_m = voxel_m > 0 ? voxel_m / a.rc_per_voxel : 0;
  double k_rc2 = 0;
  if (a.k_text && k_in_rc2(a.k_text, rc_m, a.rc_per_voxel, &k_rc2)) {
    mdp_image_free(&img);
    return 2;
  }
  mdp_morph_opts_t o = {.mode = a.imbibition ? MDP_MORPH_IMBIBITION : MDP_MORPH_DRAINAGE,
                        .axis = a.axis,
                        .trapping = a.trapping};
  for (int d = 0; d < 3; d++) o.periodic[d] = a.periodic && d != a.axis;
  int n = 0;
  mdp_morph_step_t *st = NULL;
  rc = mdp_image_morph_curve(&img, &o, NULL, 0, &n, err);
  if (!rc && !(st = malloc((size_t)(n > 0 ? n : 1) * sizeof *st))) {
    snprintf(err, sizeof err, "out of memory for %d steps", n);
    rc = 1;
  }
  if (!rc) rc = mdp_image_morph_curve(&img, &o, st, n, &n, err);
  if (rc) {
    fprintf(stderr, "mdpore image drainage: %s: %s\n", a.path, err);
    free(st);
    mdp_image_free(&img);
    return 1;
  }
  if (make_dirs(a.out_dir) != 0) {
    fprintf(stderr, "mdpore image drainage: -o %s: cannot create the folder (%s)\n", a.out_dir,
            strerror(errno));
    rc = 1;
  }
  char csv[4096], png[4096];
  snprintf(csv, sizeof csv, "%s/pc_morph.csv", a.out_dir);
  snprintf(png, sizeof png, "%s/pc_morph.png", a.out_dir);
  if (!rc) rc = write_csv(csv, &a, &img, st, n, rc_m, k_rc2);
  if (!rc) {
    printf("%s of %s: %d steps, R %.4g..%.4g voxels, Snw %.4f..%.4f",
           a.imbibition ? "imbibition" : "drainage", a.path, n, st[0].radius, st[n - 1].radius,
           st[0].snw, st[n - 1].snw);
    if (o.axis >= 0 && o.trapping)
      printf(", trapped %s at the end %.4f of the pore volume",
             a.imbibition ? "non-wetting" : "wetting",
             (double)st[n - 1].trapped_voxels / (double)st[n - 1].pore_voxels);
    for (int i = 0; i < n && o.axis >= 0 && !a.imbibition; i++)
      if (st[i].nw_spans) {
        printf(", breakthrough (non-wetting spans the axis) at R %.4g voxels, Snw %.4f",
               st[i].radius, st[i].snw);
        break;
      }
    printf("\nwrote %s\n", csv);
    printf("note: pc_depleted (r - %g rc) is an interpretation of the capillary entry brackets "
           "of docs/twophase.md section 7 (effective width H - 2.3 rc), not a measurement\n",
           MORPH_DEPLETION_RC);
  }
  if (!rc && a.plot) {
    char cmd[9000];
    snprintf(cmd, sizeof cmd, "'%s' '%s' '%s' '%s'", MDPORE_PYTHON_EXE, MDPORE_MORPH_PLOT_SCRIPT,
             csv, png);
    if (system(cmd) != 0) {
      fprintf(stderr, "mdpore image drainage: plotting failed (%s)\n", cmd);
      rc = 1;
    } else {
      printf("wrote %s\n", png);
    }
  }
  if (!rc && a.write_image) {
    mdp_image_t out;
    mdp_morph_step_t got;
    if (mdp_image_morph_at(&img, &o, a.at, (uint8_t)a.nw_label, &out, &got, err) ||
        write_any(&out, a.write_image, err)) {
      fprintf(stderr, "mdpore image drainage: %s: %s\n", a.path, err);
      rc = 1;
    } else {
      printf("wrote %s: Snw %.4f (target %g) at R %.4g voxels, non-wetting voxels labelled %d "
             "(pore)\n",
             a.write_image, got.snw, a.at, got.radius, a.nw_label);
    }
    mdp_image_free(&out);
  }
  free(st);
  mdp_image_free(&img);
  return rc;
}
