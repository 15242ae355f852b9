/* `mdpore slip INPUT...` (also `mdpore fit slip`): the slip length b fitted to the permeabilities
 * of one pore shape at several sizes, the apparent-permeability trend k / k_noslip against the size
 * (docs/permeability.md "Slip and apparent permeability"). No PETSc. */
#include <math.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "common/cli_help.h"
#include "common/same_file.h"
#include "slip_fit.h"
#include "slip_input.h"
#include "slip_report.h"

#ifndef MDPORE_PYTHON_EXE
#define MDPORE_PYTHON_EXE "/usr/bin/python3"
#endif
#ifndef MDPORE_SLIP_PLOT_SCRIPT
#define MDPORE_SLIP_PLOT_SCRIPT "plot_slip.py"
#endif

static const cli_help_option_t slip_options[] = {
    {"INPUT",
     "a CSV with columns h,k,k_err (optional shape, porosity; '#' comments), or a campaign's "
     "permeability.json (mdpore permeability) as FILE or FILE@H with the pore size H in rc "
     "(default for a slit: h_hydraulic of its campaign.txt)",
     1},
    {"--shape S", "slit or tube (default: the CSV's shape column; required for JSON inputs)", 1},
    {"--model M",
     "navier (default): Navier slip, exact 1 + 6 b/h (slit), 1 + 4 b/R (tube); shift: no-slip "
     "walls moved by b, (1 + 2 b/h)^3, (1 + b/R)^4",
     1},
    {"--free-scale",
     "also fit a common factor a (viscosity or density off by the same factor at every size); "
     "default a = 1",
     0},
    {"--axis A", "the axis read from permeability.json inputs (default x, or the only one)", 0},
    {"--out PREFIX", "writes PREFIX.csv (trend table), PREFIX.json, PREFIX.png (default: slip)", 1},
    {"--rc-m M", "metres per rc for b in m (default: units.rc_m of the JSON inputs)", 0},
    {"--no-plot", "no PNG (the plot needs python3 with matplotlib)", 1},
    {"--quiet", "no report or 'wrote' lines on stdout", 0},
    {NULL, NULL, 0}};

static const cli_help_page_t slip_help = {
    .command = "slip",
    .usage = "usage: mdpore slip INPUT... [--shape slit|tube] [--model navier|shift]\n"
             "                  [--free-scale] [--axis x|y|z] [--out PREFIX] [--rc-m M]\n"
             "                  [--no-plot] [--quiet]\n",
    .purpose = "The wall slip length b from permeabilities of one pore shape at several sizes.",
    .about = "Fits the wall slip length b to permeabilities of one pore shape at several sizes by "
             "weighted least squares of k = a k_noslip (1 + c b / h) (docs/permeability.md, "
             "\"Slip and apparent permeability\"): slit k_noslip = phi h^2/12, c = 6 (h = width); "
             "tube phi R^2/8, c = 4 (R = radius); phi the porosity (k superficial, q over the "
             "whole cross-section).",
    .options = slip_options,
    .notes = "Exit 0 on a fit, 1 on bad input or no fit (the message names the file, key and what "
             "was expected), 2 on a usage error.",
    .more = "docs/permeability.md, \"Slip and apparent permeability\"",
    .name_width = 14,
};

typedef struct {
  const char **inputs;
  int n_inputs, shape, model, free_scale, plot, quiet;
  const char *axis, *out;
  double rc_m;
} slip_args;

static int parse_args(int argc, char **argv, slip_args *a) {
  memset(a, 0, sizeof *a);
  a->shape = -1;
  a->model = SLIP_NAVIER;
  a->plot = 1;
  a->out = "slip";
  a->rc_m = NAN;
  a->inputs = calloc(argc, sizeof *a->inputs);
  if (!a->inputs) {
    fprintf(stderr, "mdpore slip: out of memory\n");
    return -1;
  }
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (cli_help_flag(s)) return cli_help_flag(s);
    if (!strcmp(s, "--shape") && v) {
      if ((a->shape = slip_shape_from_name(v)) < 0) {
        fprintf(stderr, "mdpore slip: --shape: expected slit or tube, got '%s'\n", v);
        return -1;
      }
      i++;
    } else if (!strcmp(s, "--model") && v) {
      if ((a->model = slip_model_from_name(v)) < 0) {
        fprintf(stderr, "mdpore slip: --model: expected navier or shift, got '%s'\n", v);
        return -1;
      }
      i++;
    } else if (!strcmp(s, "--axis") && v) {
      if (strcmp(v, "x") && strcmp(v, "y") && strcmp(v, "z")) {
        fprintf(stderr, "mdpore slip: --axis: expected x, y or z, got '%s'\n", v);
        return -1;
      }
      a->axis = argv[++i];
    } else if (!strcmp(s, "--out") && v)
      a->out = argv[++i];
    else if (!strcmp(s, "--rc-m") && v) {
      char *end;
      a->rc_m = strtod(v, &end);
      if (*end || !(isfinite(a->rc_m) && a->rc_m > 0)) {
        fprintf(stderr, "mdpore slip: --rc-m: expected a length in metres > 0, got '%s'\n", v);
        return -1;
      }
      i++;
    } else if (!strcmp(s, "--free-scale"))
      a->free_scale = 1;
    else if (!strcmp(s, "--no-plot"))
      a->plot = 0;
    else if (!strcmp(s, "--quiet"))
      a->quiet = 1;
    else if (s[0] == '-' && s[1]) {
      fprintf(stderr, "mdpore slip: unknown or incomplete option '%s'\n", s);
      return -1;
    } else
      a->inputs[a->n_inputs++] = s;
  }
  if (!a->n_inputs) {
    fprintf(stderr, "mdpore slip: no INPUT given\n");
    return -1;
  }
  return 0;
}

static int run_slip(const slip_args *a) {
  char err[2048], path[4096];
  slip_points ps;
  slip_points_init(&ps, a->shape);
  int rc = 1;
  {
    char csv_out[4096], json_out[4096], png_out[4096];
    snprintf(csv_out, sizeof csv_out, "%s.csv", a->out);
    snprintf(json_out, sizeof json_out, "%s.json", a->out);
    snprintf(png_out, sizeof png_out, "%s.png", a->out);
    const char *outs[3] = {csv_out, json_out, a->plot ? png_out : NULL};
    const char *out_roles[3] = {"--out (.csv)", "--out (.json)", "--out (.png)"};
    for (int i = 0; i < a->n_inputs; i++) {
      const char *in_role[1] = {"the input"};
      /* the file of FILE@SIZE */
      char in_file[4096];
      const char *at = slip_input_size(a->inputs[i]);
      snprintf(in_file, sizeof in_file, "%.*s", at ? (int)(at - a->inputs[i]) : 4095, a->inputs[i]);
      const char *in[1] = {in_file};
      if (mdp_check_outputs(outs, out_roles, 3, in, in_role, 1, err, sizeof err)) {
        fprintf(stderr, "mdpore slip: %s\n", err);
        return 1;
      }
    }
  }
  for (int i = 0; i < a->n_inputs; i++)
    if (slip_read_input(&ps, a->inputs[i], a->axis, err, sizeof err)) goto fail;
  if (ps.shape < 0) {
    snprintf(err, sizeof err,
             "no pore shape: expected --shape slit|tube or a CSV column 'shape' (inputs: %s%s)",
             a->inputs[0], a->n_inputs > 1 ? ", ..." : "");
    goto fail;
  }
  const slip_setup s = {ps.shape, a->model, a->free_scale};
  slip_result r;
  if (slip_fit(ps.p, ps.n, &s, &r, err, sizeof err)) goto fail;
  const double rc_m = slip_rc_m(ps.p, ps.n, a->rc_m);
  if (!a->quiet) slip_print(stdout, ps.p, ps.n, &s, &r, rc_m);
  snprintf(path, sizeof path, "%s.csv", a->out);
  if (slip_write_csv(path, ps.p, ps.n, &s, &r)) goto fail_quiet;
  if (!a->quiet) printf("wrote %s\n", path);
  snprintf(path, sizeof path, "%s.json", a->out);
  if (slip_write_json(path, ps.p, ps.n, &s, &r, rc_m)) goto fail_quiet;
  if (!a->quiet) printf("wrote %s\n", path);
  if (a->plot) {
    char cmd[9000];
    snprintf(cmd, sizeof cmd, "'%s' '%s' '%s' '%s.png'", MDPORE_PYTHON_EXE, MDPORE_SLIP_PLOT_SCRIPT,
             path, a->out);
    if (system(cmd) != 0)
      fprintf(stderr, "mdpore slip: warning: no plot (%s failed; python3 with matplotlib?)\n", cmd);
    else if (!a->quiet)
      printf("wrote %s.png\n", a->out);
  }
  rc = 0;
  goto done;
fail:
  fprintf(stderr, "mdpore slip: %s\n", err);
fail_quiet:
done:
  slip_points_free(&ps);
  return rc;
}

int cmd_slip(int argc, char **argv) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  slip_args a;
  int p = parse_args(argc, argv, &a);
  int rc;
  if (p != 0) {
    if (rank == 0) cli_help_print(p > 0 ? stdout : stderr, &slip_help, p > 0 ? p : CLI_HELP_SHORT);
    rc = p > 0 ? 0 : 2;
  } else {
    rc = rank == 0 ? run_slip(&a) : 0; /* a few points: one rank does it */
    MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
  }
  free(a.inputs);
  return rc;
}
