/* Options of `mdpore relperm` (docs/relperm.md section 3). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "relperm.h"

static const cli_help_option_t rp_options[] = {
    {"--axis A", "flow axis x, y or z", 1},
    {"--saturations LIST", "target water saturations in (0, 1) (default 0.2,0.35,0.5,0.65,0.8)", 1},
    {"--mode M",
     "drainage (default: the non-wetting liquid invades from the inlet face) or imbibition", 1},
    {"--no-trapping",
     "the morphology without trapping of the defending phase (with it a small crop keeps the "
     "wetting clusters cut off from the outlet face)",
     0},
    {"--phase-images LIST",
     "labelled images of the phase distributions instead of the morphology (the IMAGE's pore "
     "space, the non-wetting voxels labelled --nw-label; e.g. from mdpore image drainage "
     "--write-image)",
     0},
    {"--nw-label L",
     "the non-wetting label of --phase-images (default: the one pore label they add to the "
     "IMAGE's)",
     0},
    {"--force G",
     "body force per particle on both liquids (default: auto from the image's hydraulic size)", 1},
    {"--wetting W", "water (default: water-wall A -40, oil-wall A -20) or oil (swapped)", 0},
    {"--viscosity-ratio M", "1 (default), 2 or 5: the oil's thermostat (docs/twophase.md)", 1},
    {"--cross-attraction A",
     "water-oil A (default -20; -30 removes the interfacial slip of the layered slit, "
     "docs/twophase.md section 5)",
     0},
    {"--template SCENE",
     "a scene whose pairs block (with species water and oil) replaces the standard liquids'", 0},
    {"--rc-per-voxel R",
     "voxel edge in rc (default: from the critical throat, as mdpore permeability; refused below "
     "--min-throat unless --allow-coarse)",
     0},
    {"--min-throat RC", "least critical throat in rc (default 4)", 0},
    {"--allow-coarse", "run a --rc-per-voxel below --min-throat (with a warning)", 0},
    {"--boundary B", "auto (default), mirror or periodic (docs/permeability.md)", 0},
    {"--steps N", "run.steps of every run (default 20000)", 1},
    {"--target-error E", "run.target_error of every run (default 0.05)", 1},
    {"--seed S", "base seed (default 12345)", 0},
    {"--jobs N|auto", "runs at once (default 1)", 1},
    {"--emit-scenes DIR", "write the phase images, scenes and commands.txt, run nothing", 1},
    {"--collect DIR", "read a campaign folder back: relperm.csv, .json, .png, .txt", 1},
    {NULL, NULL, 0}};

const cli_help_page_t rp_help = {
    .command = "relperm",
    .usage = "usage: mdpore relperm IMAGE --axis x|y|z [options] WORKDIR\n"
             "       mdpore relperm IMAGE --axis x|y|z [options] --emit-scenes DIR\n"
             "       mdpore relperm --collect DIR\n",
    .purpose = "Relative permeabilities kr of water and oil in an image, per water saturation.",
    .about = "Steady co-current relative permeability of water and oil in an image "
             "(docs/relperm.md): per target water saturation the phase distribution of the "
             "image's morphological drainage (or imbibition), both liquids driven by the same "
             "body force along the axis; two single-phase runs (all water, all oil) as "
             "references; kr_i = q_i / q_i^(1). Writes WORKDIR/relperm.csv, relperm.json, "
             "relperm.png and relperm.txt.",
    .options = rp_options,
    .notes = "Exit: 0 every run used; 1 runs left out (the report says why) or an error; 2 bad "
             "usage.",
    .more = "docs/relperm.md",
    .name_width = 20,
};

static int bad(const char *opt, const char *expected, const char *got) {
  fprintf(stderr, "mdpore relperm: %s: expected %s (got '%s')\n", opt, expected, got);
  return -1;
}

static void absolute(const char *p, char *out, int len) {
  if (p[0] == '/') {
    snprintf(out, len, "%s", p);
    return;
  }
  char cwd[CAMP_PATH];
  if (!getcwd(cwd, sizeof cwd)) cwd[0] = 0;
  snprintf(out, len, "%.2000s/%.2000s", cwd, p);
}

static int parse_double(const char *opt, const char *v, double lo, double hi, const char *what,
                        double *out) {
  char *end;
  errno = 0;
  const double x = strtod(v, &end);
  if (end == v || *end || errno || !(x > lo) || !(x < hi)) return bad(opt, what, v);
  *out = x;
  return 0;
}

static int parse_ll(const char *opt, const char *v, long long lo, const char *what,
                    long long *out) {
  char *end;
  errno = 0;
  const long long x = strtoll(v, &end, 10);
  if (end == v || *end || errno || x < lo) return bad(opt, what, v);
  *out = x;
  return 0;
}

static int cmp_double(const void *a, const void *b) {
  const double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* "a,b,c" of water saturations, each in (0, 1), sorted. */
static int parse_saturations(const char *v, rp_opts *o) {
  char buf[1024];
  snprintf(buf, sizeof buf, "%s", v);
  o->n_sw = 0;
  for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
    char *end;
    const double x = strtod(tok, &end);
    if (end == tok || *end || !(x > 0) || !(x < 1))
      return bad("--saturations",
                 "a list of water saturations, each strictly between 0 and 1 (the end points "
                 "are the single-phase references, run anyway)",
                 v);
    if (o->n_sw >= RP_MAX_SATURATIONS) return bad("--saturations", "at most 32 saturations", v);
    o->sw[o->n_sw++] = x;
  }
  if (o->n_sw == 0) return bad("--saturations", "at least one water saturation", v);
  qsort(o->sw, (size_t)o->n_sw, sizeof o->sw[0], cmp_double);
  for (int i = 1; i < o->n_sw; i++)
    if (o->sw[i] == o->sw[i - 1]) return bad("--saturations", "each saturation once", v);
  return 0;
}

static int parse_list(const char *v, rp_opts *o) {
  char buf[8 * CAMP_PATH];
  snprintf(buf, sizeof buf, "%s", v);
  o->n_phase_images = 0;
  for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
    if (o->n_phase_images >= RP_MAX_SATURATIONS)
      return bad("--phase-images", "at most 32 images", v);
    if (access(tok, R_OK)) {
      fprintf(stderr, "mdpore relperm: --phase-images: %s: cannot read it (%s)\n", tok,
              strerror(errno));
      return -1;
    }
    absolute(tok, o->phase_images[o->n_phase_images++], CAMP_PATH);
  }
  return 0;
}

/* 1 when opt is an option that takes a value (the others are refused before their value is
 * looked for, so an unknown one at the end is named as unknown). */
static int takes_value(const char *opt) {
  static const char *const with_value[] = {"--axis",
                                           "--saturations",
                                           "--mode",
                                           "--phase-images",
                                           "--nw-label",
                                           "--force",
                                           "--wetting",
                                           "--viscosity-ratio",
                                           "--cross-attraction",
                                           "--template",
                                           "--rc-per-voxel",
                                           "--min-throat",
                                           "--boundary",
                                           "--steps",
                                           "--target-error",
                                           "--seed",
                                           "--jobs",
                                           "--emit-scenes",
                                           "--collect",
                                           NULL};
  for (int i = 0; with_value[i]; i++)
    if (!strcmp(opt, with_value[i])) return 1;
  return 0;
}

int rp_parse_args(int argc, char **argv, rp_opts *o) {
  memset(o, 0, sizeof *o);
  camp_opts *co = &o->co;
  /* the campaign's defaults (campaign_args.c) for what relperm shares */
  co->target_error = 0.05;
  co->np = 1;
  co->jobs = 1;
  co->rc_per_voxel = 0.5;
  co->min_throat = 4.0;
  co->viscosity = 5.41;
  co->wall_density = CAMP_DEFAULT_WALL_DENSITY;
  co->wall_adsorption = CAMP_DEFAULT_WALL_ADSORPTION;
  snprintf(co->rng, sizeof co->rng, "philox");
  co->temperature_K = 298.15;
  co->seed = 12345;
  co->flux_every = 10;
  co->drive = CAMP_DRIVE_BODY;
  co->reservoir = 4.0;
  co->boundary = CAMP_BOUNDARY_AUTO;
  co->density_tolerance = CAMP_DEFAULT_DENSITY_TOLERANCE;
  co->temperature_tolerance = CAMP_DEFAULT_TEMPERATURE_TOLERANCE;
  co->cavitation_tolerance = CAMP_DEFAULT_CAVITATION_TOLERANCE;
  snprintf(co->mpiexec, sizeof co->mpiexec, "mpiexec");
  o->axis = -1;
  o->ratio = 1;
  o->trapping = 1;
  o->a_wo = RP_A_WO;
  parse_saturations("0.2,0.35,0.5,0.65,0.8", o);
  const char *pos[2] = {NULL, NULL};
  int n_pos = 0;
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    if (cli_help_flag(s)) return cli_help_flag(s);
    if (!strcmp(s, "--no-trapping")) {
      o->trapping = 0;
      continue;
    }
    if (!strcmp(s, "--allow-coarse")) {
      co->force = 1;
      continue;
    }
    if (s[0] != '-') {
      if (n_pos >= 2) {
        fprintf(stderr, "mdpore relperm: unexpected argument '%s' (IMAGE and WORKDIR given)\n", s);
        return -1;
      }
      pos[n_pos++] = s;
      continue;
    }
    if (!takes_value(s)) {
      fprintf(stderr, "mdpore relperm: unexpected option '%s'\n", s);
      return -1;
    }
    if (i + 1 >= argc) {
      fprintf(stderr, "mdpore relperm: %s: expected a value after it\n", s);
      return -1;
    }
    const char *v = argv[++i];
    long long ll;
    if (!strcmp(s, "--axis")) {
      if (strlen(v) != 1 || v[0] < 'x' || v[0] > 'z') return bad(s, "x, y or z", v);
      o->axis = v[0] - 'x';
    } else if (!strcmp(s, "--saturations")) {
      if (parse_saturations(v, o)) return -1;
    } else if (!strcmp(s, "--mode")) {
      if (!strcmp(v, "drainage"))
        o->mode = MDP_MORPH_DRAINAGE;
      else if (!strcmp(v, "imbibition"))
        o->mode = MDP_MORPH_IMBIBITION;
      else
        return bad(s, "drainage or imbibition", v);
    } else if (!strcmp(s, "--phase-images")) {
      if (parse_list(v, o)) return -1;
    } else if (!strcmp(s, "--nw-label")) {
      if (parse_ll(s, v, 1, "a label value 1..255", &ll) || ll > 255)
        return bad(s, "a label value 1..255", v);
      o->nw_label = (int)ll;
      o->nw_label_given = 1;
    } else if (!strcmp(s, "--force")) {
      if (parse_double(s, v, 0, 1, "a body force per particle 0 < G < 1", &o->g)) return -1;
    } else if (!strcmp(s, "--wetting")) {
      if (!strcmp(v, "water"))
        o->wetting = RP_WET_WATER;
      else if (!strcmp(v, "oil"))
        o->wetting = RP_WET_OIL;
      else
        return bad(s, "water or oil (the liquid the walls attract strongly)", v);
    } else if (!strcmp(s, "--viscosity-ratio")) {
      rp_liquids l;
      if (parse_ll(s, v, 1, "1, 2 or 5 (the documented oils, docs/twophase.md section 4)", &ll) ||
          ll > 5 || rp_liquids_of((int)ll, &l))
        return bad(s, "1, 2 or 5 (the documented oils, docs/twophase.md section 4)", v);
      o->ratio = (int)ll;
    } else if (!strcmp(s, "--cross-attraction")) {
      if (parse_double(s, v, -1e3, 0, "a water-oil A < 0", &o->a_wo)) return -1;
    } else if (!strcmp(s, "--template")) {
      if (access(v, R_OK)) {
        fprintf(stderr, "mdpore relperm: --template: %s: cannot read it (%s)\n", v,
                strerror(errno));
        return -1;
      }
      absolute(v, o->template_path, sizeof o->template_path);
    } else if (!strcmp(s, "--rc-per-voxel")) {
      if (parse_double(s, v, 0, 100, "a voxel edge in rc > 0", &co->rc_per_voxel)) return -1;
      co->rc_per_voxel_given = 1;
    } else if (!strcmp(s, "--min-throat")) {
      if (parse_double(s, v, 0, 1e6, "a throat in rc > 0", &co->min_throat)) return -1;
    } else if (!strcmp(s, "--boundary")) {
      const int b = camp_boundary_parse(v);
      if (b != CAMP_BOUNDARY_AUTO && b != CAMP_BOUNDARY_MIRROR && b != CAMP_BOUNDARY_PERIODIC)
        return bad(s, "auto, mirror or periodic", v);
      co->boundary = b;
    } else if (!strcmp(s, "--steps")) {
      if (parse_ll(s, v, 1, "a positive number of steps", &co->max_steps)) return -1;
    } else if (!strcmp(s, "--target-error")) {
      if (parse_double(s, v, 0, 1, "a relative error 0 < E < 1", &co->target_error)) return -1;
    } else if (!strcmp(s, "--seed")) {
      if (parse_ll(s, v, 0, "a seed >= 0", &co->seed)) return -1;
    } else if (!strcmp(s, "--jobs")) {
      if (!strcmp(v, "auto"))
        co->jobs = 0;
      else if (parse_ll(s, v, 1, "a positive number of runs at once, or auto", &ll) ||
               ll > CAMP_MAX_JOBS)
        return bad(s, "1..64 runs at once, or auto", v);
      else
        co->jobs = (int)ll;
    } else if (!strcmp(s, "--emit-scenes")) {
      absolute(v, co->emit_dir, sizeof co->emit_dir);
    } else if (!strcmp(s, "--collect")) {
      absolute(v, co->collect_dir, sizeof co->collect_dir);
    } else {
      fprintf(stderr, "mdpore relperm: unexpected option '%s'\n", s);
      return -1;
    }
  }
  if (co->collect_dir[0]) {
    if (n_pos || co->emit_dir[0]) {
      fprintf(stderr, "mdpore relperm: --collect DIR reads a campaign folder: give no IMAGE, "
                      "WORKDIR or --emit-scenes with it\n");
      return -1;
    }
    return 0;
  }
  if (!pos[0]) {
    fprintf(stderr, "mdpore relperm: expected an IMAGE argument\n");
    return -1;
  }
  if (o->axis < 0) {
    fprintf(stderr, "mdpore relperm: expected --axis x|y|z\n");
    return -1;
  }
  const char *img = pos[0];
  const size_t L = strlen(img);
  if ((L > 5 && !strcmp(img + L - 5, ".yaml")) || (L > 4 && !strcmp(img + L - 4, ".yml"))) {
    fprintf(stderr,
            "mdpore relperm: %s: expected a segmented IMAGE (a scene's liquids go with "
            "--template SCENE)\n",
            img);
    return -1;
  }
  if (access(img, R_OK)) {
    fprintf(stderr, "mdpore relperm: %s: cannot read the IMAGE (%s)\n", img, strerror(errno));
    return -1;
  }
  absolute(img, co->input, sizeof co->input);
  co->axes[0] = o->axis;
  co->n_axes = 1;
  const char *b = strrchr(co->input, '/');
  snprintf(co->sample, sizeof co->sample, "%.255s", b ? b + 1 : co->input);
  char *dot = strrchr(co->sample, '.');
  if (dot && dot != co->sample) *dot = 0;
  if (co->emit_dir[0]) {
    if (pos[1]) {
      fprintf(stderr, "mdpore relperm: --emit-scenes DIR is the work folder: give no WORKDIR "
                      "with it\n");
      return -1;
    }
    snprintf(co->workdir, sizeof co->workdir, "%s", co->emit_dir);
  } else if (pos[1]) {
    absolute(pos[1], co->workdir, sizeof co->workdir);
  } else {
    fprintf(stderr, "mdpore relperm: expected a WORKDIR (the campaign folder) after the IMAGE\n");
    return -1;
  }
  return 0;
}
