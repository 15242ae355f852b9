/* Options of `mdpore permeability` (docs/permeability.md). */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "campaign.h"

static const cli_help_option_t camp_options[] = {
    {"--axis A", "x, y, z or all (the diagonal of the permeability tensor)", 1},
    {"--gradients G",
     "auto (default: --n-gradients points, mean pore velocity log-spaced over --velocity-range) "
     "or a list of body forces per particle g, e.g. 0.05,0.1,0.2",
     0},
    {"--n-gradients N", "auto: number of gradients (>= 5, default 5)", 0},
    {"--velocity-range L,H", "auto: mean pore velocity range (default 0.02,0.2)", 0},
    {"--target-error E", "run.target_error of every run (0 < E < 1, default 0.05)", 1},
    {"--max-steps N", "run.steps, the step budget of every run (default 20000; a scene: its own)",
     1},
    {"--target-error-k E",
     "stop the campaign, not each run, on the relative error of k (0 < E < 1): every run for "
     "--round-steps, then in rounds the runs that lower the error of k most per particle-step "
     "continued from their checkpoints, until E or --budget-steps (replaces --target-error; "
     "docs/permeability.md)",
     0},
    {"--round-steps N",
     "--target-error-k: the first round's steps of every run (default --max-steps / 20, at least "
     "100 flux samples)",
     0},
    {"--budget-steps N",
     "--target-error-k: the steps of all runs together (default: runs x --max-steps, the most "
     "the per-run rule could spend)",
     0},
    {"--dt DT", "run.dt of every run (default: the template's, 0.01 for an image)", 0},
    {"--accuracy P",
     "fast | balanced | precise: dt, target error and step budget from the measured accuracy "
     "table (docs/accuracy.md); explicit options win",
     1},
    {"--np N", "ranks per run: mpiexec -n N mdpore run (default 1: plain mdpore run)", 1},
    {"--mpiexec CMD", "launcher and its flags (default: mpiexec)", 0},
    {"--jobs N|auto",
     "runs executed at once, each its own process (default 1: one after another, as on a CPU CI "
     "machine). auto: on a CUDA build with a GPU, as many as fit in its free memory (at most 8); "
     "else cores / --np. Every run's result is the same at any N",
     0},
    {"--job-mode M",
     "auto (default): replicas when the runs at once share a GPU, else process; process: each "
     "run of --jobs its own process; replicas: the runs at once stepped in one process (mdpore "
     "run --replicas: one start-up, one GPU context; one-rank runs without --target-error-k)",
     0},
    {"--workdir DIR", "campaign folder (default permeability-SAMPLE)", 1},
    {"--emit-scenes DIR", "write the scenes, the manifest and commands.txt, run nothing", 1},
    {"--collect DIR", "read a campaign folder back: tables, fits, report", 1},
    {"--rc-per-voxel R",
     "image: voxel edge in rc (default: the critical throat along the flow axes made "
     "--min-throat wide; refused below that unless --force)",
     1},
    {"--min-throat RC", "image: least critical throat along a flow axis, in rc (default 4)", 0},
    {"--force", "image: run a --rc-per-voxel below --min-throat (with a warning)", 0},
    {"--voxel-size M",
     "voxel edge in metres (default: the image's own, else the mDPD water mapping rc = 0.82 nm)",
     0},
    {"--viscosity MU",
     "fluid viscosity in reduced units (default 5.41: mDPD A=-40 B=25 gamma=4.5 rd=0.75, "
     "validation/engine/viscosity.py)",
     0},
    {"--wall-density W",
     "image: wall patch density, particles per rc^3 (default " CAMP_WALL_DENSITY_TEXT
     ": no slip on slits, docs/walls.md section 16)",
     0},
    {"--wall-adsorption G",
     "image: particles per rc^2 of wall face that the walls hold beyond the core's density; the "
     "pores are filled at 6.2 + G S / V so that the core is at 6.2 "
     "(default " CAMP_WALL_ADSORPTION_TEXT ", measured at wall density " CAMP_WALL_DENSITY_TEXT
     "; 0 at another --wall-density unless given; 0: a uniform fill at 6.2)",
     0},
    {"--rng R",
     "image: generator of the pair random numbers, philox (default), philox2x32 or fast "
     "(dpd_thermostat rng; the same statistics, a cheaper step: docs/accuracy.md)",
     0},
    {"--temperature K", "temperature of kT for the SI units (default 298.15)", 0},
    {"--seed S", "base seed (default 12345; each gradient gets its own)", 0},
    {"--flux-every N", "flux sample interval in steps (default 10)", 0},
    {"--models LIST", "laws passed to mdpore fit (default: its default set)", 0},
    {"--sample NAME", "sample name in the tables (default: the input's file name)", 0},
    {"--drive body|pressure",
     "body: a body force on every fluid particle (default); pressure: the image padded along the "
     "axis with an open reservoir, an inlet force in it, G measured from the pressure drop across "
     "the sample (an IMAGE, or a SCENE whose particles come from geometry.image)",
     0},
    {"--reservoir R", "pressure drive: reservoir length along the axis in rc (default 4, >= 3)", 0},
    {"--boundary B",
     "the faces normal to the flow: auto (default: periodic where the image's end slices "
     "continue each other, else mirror), periodic (the image is one period), mirror (the image "
     "and its reflection: each face meets itself) or reservoir (= --drive pressure)",
     0},
    {"--cavitation-tolerance F",
     "a run whose pore-core density departs from the fill by more than F (the liquid cavitated "
     "or is compressed) is left out of the Darcy range and the fits (default 0.08; an IMAGE's "
     "fill adds what the walls adsorb, a scene's uniform fill leaves the core 2-3% below)",
     0},
    {"--density-tolerance F",
     "a run whose pore-core density departs by more than F from the liquid at rest (the core of "
     "the weakest admissible run) is left out (the forcing compressed or expanded it; default "
     "0.03)",
     0},
    {"--temperature-tolerance F",
     "a run whose temperature departs from kT by more than F (viscous heating) is left out "
     "(default 0.05)",
     0},
    {"--require-target",
     "a run that missed its target error is left out too (default: kept, its larger error bar "
     "weighting it less; an unsteady run is out)",
     0},
    {"--sides S",
     "the lateral faces: periodic (default) or mirror (symmetry planes, as mdpore foam --sides "
     "symmetry; four times the particles)",
     0},
    {NULL, NULL, 0}};

const cli_help_page_t camp_help = {
    .command = "permeability",
    .usage = "usage: mdpore permeability IMAGE|SCENE --axis x|y|z|all [options]\n"
             "       mdpore permeability IMAGE|SCENE --axis ... --emit-scenes DIR [options]\n"
             "       mdpore permeability --collect DIR [--models LIST] [--*-tolerance F]\n"
             "                           [--require-target]\n",
    .purpose = "The permeability k of an image or scene from a ladder of mdpore runs and a fit.",
    .about = "A ladder of body-force runs (one `mdpore run` each, cached by a hash of its "
             "inputs), the flow table (docs/flow-table.md), `mdpore fit` on it, k in rc^2, m^2 "
             "and nD, a PNG (docs/permeability.md).",
    .options = camp_options,
    .notes = "Exit status: 0 k reported on every axis; 3 the runs define no Darcy range on some "
             "axis (k is not reported there: the report says why and what to try); 1 an error; 2 "
             "bad usage.",
    .more = "docs/permeability.md, docs/tutorial.md",
};

static int bad(const char *opt, const char *expected, const char *got) {
  fprintf(stderr, "mdpore permeability: %s: expected %s, got '%s'\n", opt, expected, got);
  return -1;
}

/* --models: a comma-separated list of the laws mdpore fit knows, checked here so that a typo is
 * refused before any run, not by the fit at --collect. 0 or -1 (message printed). */
static int check_models(const char *list) {
  static const char *const laws[] = {"darcy", "threshold", "forchheimer", "power", NULL};
  const char *p = list;
  do {
    const size_t len = strcspn(p, ",");
    int known = 0;
    for (int i = 0; laws[i] && !known; i++)
      known = len == strlen(laws[i]) && !strncmp(p, laws[i], len);
    if (!known) {
      fprintf(stderr,
              "mdpore permeability: --models: unknown law '%.*s' in '%s' (expected a "
              "comma-separated list of darcy, threshold, forchheimer, power)\n",
              (int)(len > 64 ? 64 : len), p, list);
      return -1;
    }
    p += len;
  } while (*p++ == ',');
  return 0;
}

static int parse_double(const char *opt, const char *s, double lo, double hi, const char *what,
                        double *out) {
  char *end;
  errno = 0;
  double v = strtod(s, &end);
  if (errno || end == s || *end || !isfinite(v) || v <= lo || v >= hi) return bad(opt, what, s);
  *out = v;
  return 0;
}

static int parse_ll(const char *opt, const char *s, long long lo, const char *what,
                    long long *out) {
  char *end;
  errno = 0;
  long long v = strtoll(s, &end, 10);
  if (errno || end == s || *end || v < lo) return bad(opt, what, s);
  *out = v;
  return 0;
}

/* --target-error-k and the options that go with it (campaign_rounds.c): what it cannot be combined
 * with refused, naming both options and why; the first round's length and the budget's defaults. */
static int check_rounds(camp_opts *o, int error_given) {
  const char *k_opt = "mdpore permeability: --target-error-k";
  if (!(o->target_error_k > 0)) {
    if (o->round_steps || o->budget_steps) {
      fprintf(stderr, "mdpore permeability: %s: applies with --target-error-k E only\n",
              o->round_steps ? "--round-steps" : "--budget-steps");
      return -1;
    }
    return 0;
  }
  const char *with = o->collect_dir[0]                 ? "--collect"
                     : o->emit_dir[0]                  ? "--emit-scenes"
                     : error_given                     ? "--target-error"
                     : o->require_target               ? "--require-target"
                     : o->drive == CAMP_DRIVE_PRESSURE ? "--drive pressure"
                                                       : NULL;
  if (with) {
    static const char *const why[] = {
        "--collect reads a campaign folder as it is: run the campaign with the option, or collect "
        "without it",
        "the campaign runs in rounds that continue runs from their checkpoints, which one command "
        "per run (commands.txt) cannot do: use --target-error for emitted scenes",
        "each run's own stop would end it before its round does: the campaign sets every run's "
        "length; give one or the other",
        "the runs have no target error of their own",
        "a continued run does not carry its measured pressure drop across the continuation: use "
        "the body drive"};
    const int w = !strcmp(with, "--collect")          ? 0
                  : !strcmp(with, "--emit-scenes")    ? 1
                  : !strcmp(with, "--target-error")   ? 2
                  : !strcmp(with, "--require-target") ? 3
                                                      : 4;
    fprintf(stderr, "%s: not supported with %s: %s\n", k_opt, with, why[w]);
    return -1;
  }
  if (!(o->max_steps > 0)) o->max_steps = 20000; /* the budget's unit, for a scene too */
  if (!o->round_steps) { /* a twentieth of a run's budget, >= 100 flux samples */
    o->round_steps = o->max_steps / 20 / o->flux_every * o->flux_every;
    if (o->round_steps < 100LL * o->flux_every) o->round_steps = 100LL * o->flux_every;
  }
  if (o->round_steps > o->max_steps) {
    fprintf(stderr,
            "mdpore permeability: --round-steps %lld: expected at most --max-steps (%lld): the "
            "first round is a part of a run's budget\n",
            o->round_steps, o->max_steps);
    return -1;
  }
  return 0;
}

static int ends_with(const char *s, const char *suffix) {
  size_t n = strlen(s), m = strlen(suffix);
  return n >= m && !strcmp(s + n - m, suffix);
}

static void absolute(const char *path, char *out, int len) {
  if (path[0] == '/') {
    snprintf(out, len, "%s", path);
    return;
  }
  char cwd[CAMP_PATH];
  if (!getcwd(cwd, sizeof cwd)) cwd[0] = 0;
  snprintf(out, len, "%s/%s", cwd, path);
}

static int parse_axis(const char *s, camp_opts *o) {
  if (!strcmp(s, "all")) {
    o->n_axes = 3;
    for (int d = 0; d < 3; d++) o->axes[d] = d;
    return 0;
  }
  if (strlen(s) == 1 && s[0] >= 'x' && s[0] <= 'z') {
    o->n_axes = 1;
    o->axes[0] = s[0] - 'x';
    return 0;
  }
  return bad("--axis", "x, y, z or all", s);
}

int camp_parse_args(int argc, char **argv, camp_opts *o) {
  memset(o, 0, sizeof *o);
  o->grad_auto = 1;
  o->n_grads = 5;
  o->u_lo = 0.02;
  o->u_hi = 0.2;
  o->target_error = 0.05;
  o->np = 1;
  o->jobs = 1;
  o->job_replicas = -1; /* --job-mode auto */
  o->rc_per_voxel = 0.5;
  o->min_throat = 4.0;
  o->viscosity = 5.41;
  o->wall_density = CAMP_DEFAULT_WALL_DENSITY;
  o->wall_adsorption = CAMP_DEFAULT_WALL_ADSORPTION;
  snprintf(o->rng, sizeof o->rng, "philox");
  o->temperature_K = 298.15;
  o->seed = 12345;
  o->flux_every = 10;
  o->drive = CAMP_DRIVE_BODY;
  o->reservoir = 4.0;
  o->boundary = CAMP_BOUNDARY_AUTO;
  o->density_tolerance = CAMP_DEFAULT_DENSITY_TOLERANCE;
  o->temperature_tolerance = CAMP_DEFAULT_TEMPERATURE_TOLERANCE;
  o->cavitation_tolerance = CAMP_DEFAULT_CAVITATION_TOLERANCE;
  snprintf(o->mpiexec, sizeof o->mpiexec, "mpiexec");
  const char *input = NULL, *workdir = NULL, *accuracy = NULL;
  int have_axis = 0, dt_given = 0, error_given = 0, steps_given = 0;
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    if (cli_help_flag(s)) return cli_help_flag(s);
    if (!strcmp(s, "--force")) { /* no value */
      o->force = 1;
      continue;
    }
    if (!strcmp(s, "--require-target")) { /* no value */
      o->require_target = 1;
      continue;
    }
    if (s[0] == '-' && s[1] == '-' && i + 1 >= argc) {
      fprintf(stderr, "mdpore permeability: %s: expected a value after it\n", s);
      return -1;
    }
    const char *v = i + 1 < argc ? argv[i + 1] : NULL;
    long long ll;
    if (!strcmp(s, "--axis")) {
      if (parse_axis(v, o)) return -1;
      have_axis = 1;
    } else if (!strcmp(s, "--gradients")) {
      if (!strcmp(v, "auto"))
        o->grad_auto = 1;
      else {
        char err[512];
        o->grad_auto = 0;
        if (camp_parse_gradient_list(v, o->grads, &o->n_grads, err, sizeof err)) {
          fprintf(stderr, "mdpore permeability: --gradients: %s\n", err);
          return -1;
        }
      }
    } else if (!strcmp(s, "--n-gradients")) {
      if (parse_ll(s, v, 5, "an integer >= 5", &ll)) return -1;
      if (ll > CAMP_MAX_GRADIENTS) return bad(s, "at most 64 gradients", v);
      o->n_grads = (int)ll;
    } else if (!strcmp(s, "--velocity-range")) {
      int end = 0;
      if (sscanf(v, "%lf,%lf%n", &o->u_lo, &o->u_hi, &end) != 2 || v[end] || !(o->u_lo > 0) ||
          !(o->u_hi > o->u_lo) || !isfinite(o->u_hi))
        return bad(s, "LO,HI with 0 < LO < HI, finite (mean pore velocities)", v);
    } else if (!strcmp(s, "--target-error")) {
      if (parse_double(s, v, 0, 1, "a relative error 0 < E < 1", &o->target_error)) return -1;
      error_given = 1;
    } else if (!strcmp(s, "--target-error-k")) {
      if (parse_double(s, v, 0, 1, "a relative error of k 0 < E < 1", &o->target_error_k))
        return -1;
    } else if (!strcmp(s, "--round-steps")) {
      if (parse_ll(s, v, 1, "a positive number of steps", &o->round_steps)) return -1;
    } else if (!strcmp(s, "--budget-steps")) {
      if (parse_ll(s, v, 1, "a positive number of steps", &o->budget_steps)) return -1;
    } else if (!strcmp(s, "--max-steps")) {
      if (parse_ll(s, v, 1, "a positive number of steps", &o->max_steps)) return -1;
      steps_given = 1;
    } else if (!strcmp(s, "--dt")) {
      if (parse_double(s, v, 0, 0.1, "a time step 0 < DT < 0.1", &o->dt)) return -1;
      dt_given = 1;
    } else if (!strcmp(s, "--accuracy")) {
      accuracy = v;
    } else if (!strcmp(s, "--np")) {
      if (parse_ll(s, v, 1, "a positive number of ranks", &ll)) return -1;
      if (ll > INT_MAX) return bad(s, "a number of ranks", v);
      o->np = (int)ll;
    } else if (!strcmp(s, "--jobs")) {
      if (!strcmp(v, "auto"))
        o->jobs = 0;
      else {
        if (parse_ll(s, v, 1, "a positive number of runs at once, or auto", &ll)) return -1;
        if (ll > CAMP_MAX_JOBS) return bad(s, "at most 64 runs at once, or auto", v);
        o->jobs = (int)ll;
      }
    } else if (!strcmp(s, "--job-mode")) {
      if (!strcmp(v, "auto"))
        o->job_replicas = -1;
      else if (!strcmp(v, "process"))
        o->job_replicas = 0;
      else if (!strcmp(v, "replicas"))
        o->job_replicas = 1;
      else
        return bad(s, "auto, process or replicas", v);
    } else if (!strcmp(s, "--mpiexec"))
      snprintf(o->mpiexec, sizeof o->mpiexec, "%s", v);
    else if (!strcmp(s, "--workdir"))
      workdir = v;
    else if (!strcmp(s, "--emit-scenes"))
      absolute(v, o->emit_dir, sizeof o->emit_dir);
    else if (!strcmp(s, "--collect"))
      absolute(v, o->collect_dir, sizeof o->collect_dir);
    else if (!strcmp(s, "--rc-per-voxel")) {
      if (parse_double(s, v, 0, HUGE_VAL, "a voxel edge in rc > 0", &o->rc_per_voxel)) return -1;
      o->rc_per_voxel_given = 1;
    } else if (!strcmp(s, "--min-throat")) {
      if (parse_double(s, v, 0, 1e6, "a throat width in rc > 0", &o->min_throat)) return -1;
    } else if (!strcmp(s, "--voxel-size")) {
      if (parse_double(s, v, 0, 1, "a voxel edge in metres (0 < M < 1)", &o->voxel_size_m))
        return -1;
    } else if (!strcmp(s, "--wall-density")) {
      if (parse_double(s, v, 0, 1000, "a wall density 0 < W < 1000 (particles per rc^3)",
                       &o->wall_density))
        return -1;
      o->wall_density_given = 1;
    } else if (!strcmp(s, "--wall-adsorption")) {
      if (parse_double(s, v, -1e-300, 100, "an adsorption 0 <= G < 100 (particles per rc^2)",
                       &o->wall_adsorption))
        return -1;
      o->wall_adsorption_given = 1;
    } else if (!strcmp(s, "--rng")) {
      if (strcmp(v, "philox") && strcmp(v, "philox2x32") && strcmp(v, "fast")) {
        fprintf(stderr,
                "mdpore permeability: --rng: expected philox, philox2x32 or fast (got '%s')\n", v);
        return -1;
      }
      snprintf(o->rng, sizeof o->rng, "%s", v);
      o->rng_given = 1;
    } else if (!strcmp(s, "--viscosity")) {
      if (parse_double(s, v, 0, HUGE_VAL, "a viscosity > 0 (reduced units)", &o->viscosity))
        return -1;
      o->viscosity_given = 1;
    } else if (!strcmp(s, "--temperature")) {
      if (parse_double(s, v, 0, HUGE_VAL, "a temperature in K > 0", &o->temperature_K)) return -1;
      o->temperature_given = 1;
    } else if (!strcmp(s, "--seed")) {
      if (parse_ll(s, v, 0, "a seed >= 0", &o->seed)) return -1;
    } else if (!strcmp(s, "--flux-every")) {
      if (parse_ll(s, v, 1, "a positive number of steps", &ll)) return -1;
      if (ll > INT_MAX) return bad(s, "a number of steps", v);
      o->flux_every = (int)ll;
    } else if (!strcmp(s, "--models")) {
      if (check_models(v)) return -1;
      snprintf(o->models, sizeof o->models, "%s", v);
    } else if (!strcmp(s, "--sample"))
      snprintf(o->sample, sizeof o->sample, "%s", v);
    else if (!strcmp(s, "--drive")) {
      if (!strcmp(v, "body"))
        o->drive = CAMP_DRIVE_BODY;
      else if (!strcmp(v, "pressure"))
        o->drive = CAMP_DRIVE_PRESSURE;
      else
        return bad(s, "body or pressure", v);
    } else if (!strcmp(s, "--boundary")) {
      o->boundary = camp_boundary_parse(v);
      if (o->boundary < 0) return bad(s, "auto, periodic, mirror or reservoir", v);
    } else if (!strcmp(s, "--density-tolerance")) {
      if (parse_double(s, v, 0, 1, "a relative tolerance 0 < F < 1", &o->density_tolerance))
        return -1;
    } else if (!strcmp(s, "--cavitation-tolerance")) {
      if (parse_double(s, v, 0, 1, "a relative tolerance 0 < F < 1", &o->cavitation_tolerance))
        return -1;
    } else if (!strcmp(s, "--temperature-tolerance")) {
      if (parse_double(s, v, 0, 1, "a relative tolerance 0 < F < 1", &o->temperature_tolerance))
        return -1;
    } else if (!strcmp(s, "--sides")) {
      if (strcmp(v, "periodic") && strcmp(v, "mirror")) return bad(s, "periodic or mirror", v);
      o->sides_mirror = !strcmp(v, "mirror");
    } else if (!strcmp(s, "--reservoir")) {
      if (parse_double(s, v, 2.999999, 1e6, "a reservoir length >= 3 rc", &o->reservoir)) return -1;
    } else if (s[0] == '-') {
      fprintf(stderr, "mdpore permeability: unknown option '%s'\n", s);
      return -1;
    } else if (!input) {
      input = s;
      i--; /* no value */
    } else {
      fprintf(stderr, "mdpore permeability: unexpected argument '%s'\n", s);
      return -1;
    }
    i++;
  }
  if (o->boundary == CAMP_BOUNDARY_RESERVOIR) o->drive = CAMP_DRIVE_PRESSURE;
  if (o->drive == CAMP_DRIVE_PRESSURE &&
      (o->boundary == CAMP_BOUNDARY_PERIODIC || o->boundary == CAMP_BOUNDARY_MIRROR)) {
    fprintf(stderr,
            "mdpore permeability: --boundary %s: the pressure drive joins the faces "
            "through its reservoir (--boundary reservoir); give one or the other\n",
            camp_boundary_name(o->boundary));
    return -1;
  }
  if (o->collect_dir[0] && check_rounds(o, error_given)) return -1;
  if (o->collect_dir[0]) {
    if (input || o->emit_dir[0]) {
      fprintf(stderr, "mdpore permeability: --collect DIR reads a campaign folder: give no "
                      "IMAGE|SCENE and no --emit-scenes with it\n");
      return -1;
    }
    return 0;
  }
  if (!input) {
    fprintf(stderr, "mdpore permeability: expected an IMAGE or SCENE argument\n");
    return -1;
  }
  if (!have_axis) {
    fprintf(stderr, "mdpore permeability: expected --axis x|y|z|all\n");
    return -1;
  }
  if (accuracy && camp_accuracy_preset(accuracy, o, dt_given, error_given, steps_given)) return -1;
  if (check_rounds(o, error_given)) return -1;
  if (access(input, R_OK)) {
    fprintf(stderr,
            "mdpore permeability: %s: cannot read the input (%s): expected a segmented "
            "image or a scene file\n",
            input, strerror(errno));
    return -1;
  }
  absolute(input, o->input, sizeof o->input);
  o->input_is_scene = ends_with(input, ".yaml") || ends_with(input, ".yml");
  if (o->input_is_scene && o->wall_adsorption_given) {
    fprintf(stderr,
            "mdpore permeability: --wall-adsorption: applies to an IMAGE input only (got the "
            "scene %s: set geometry.fluid_density in it)\n",
            input);
    return -1;
  }
  if (o->input_is_scene && o->wall_density_given) {
    fprintf(stderr,
            "mdpore permeability: --wall-density: applies to an IMAGE input only (got the scene "
            "%s: set geometry.wall_density in it)\n",
            input);
    return -1;
  }
  if (o->input_is_scene && o->rng_given) {
    fprintf(stderr,
            "mdpore permeability: --rng: applies to an IMAGE input only (got the scene %s: set "
            "effects.dpd_thermostat.rng in it)\n",
            input);
    return -1;
  }
  if (!o->sample[0]) {
    const char *b = strrchr(o->input, '/');
    snprintf(o->sample, sizeof o->sample, "%.255s", b ? b + 1 : o->input);
    char *dot = strrchr(o->sample, '.');
    if (dot && dot != o->sample) *dot = 0;
  }
  if (o->emit_dir[0])
    snprintf(o->workdir, sizeof o->workdir, "%s", o->emit_dir);
  else if (workdir)
    absolute(workdir, o->workdir, sizeof o->workdir);
  else {
    char name[512];
    snprintf(name, sizeof name, "permeability-%s", o->sample);
    absolute(name, o->workdir, sizeof o->workdir);
  }
  return 0;
}
