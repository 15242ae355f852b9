/* `mdpore fit relperm TABLE` (see cmd_fit_relperm.h). */
#include "cmd_fit_relperm.h"

#include <math.h>
#include <mpi.h>
#include <petscsys.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/cli_help.h"
#include "common/same_file.h"
#include "kr_outcome.h"
#include "kr_report.h"
#include "kr_select.h"
#include "kr_swof.h"
#include "pc_curve.h"

static const cli_help_option_t fit_relperm_options[] = {
    {"--law L",
     "auto (default: the test decides), corey (Corey only), let (LET, forced); L refused by the "
     "check (or not fitted): no SWOF, exit 3",
     1},
    {"--force", "with --law: take L even when the check refuses it (flagged)", 0},
    {"--swc V, --sor V", "fix the end-point saturations (default: fitted within the data's bounds)",
     1},
    {"--swof FILE",
     "write the SWOF table of the accepted law, else of the measured points (kr > 1 clipped to 1, "
     "listed)",
     1},
    {"--swof-rows N",
     "law grid points from swc to 1 - sor (default " CLI_HELP_STR(KR_SWOF_DEFAULT_ROWS) ")", 0},
    {"--swof-points P", "law (default) or measured (the points, made monotone)", 0},
    {"--pc-morph FILE", "Pcow from the morphological Pc(Sw) curve (else Pcow = 0)", 0},
    {"--json FILE", "the JSON report (default TABLE.fit.json)", 1},
    {"--png FILE", "plot data, fits and residuals (python3 + matplotlib); --plot is the same", 1},
    {"--quiet", "no report or 'wrote' lines on stdout", 0},
    {NULL, NULL, 0}};

static const cli_help_page_t fit_relperm_help = {
    .command = "fit relperm",
    .usage = "usage: mdpore fit relperm TABLE [--law auto|corey|let [--force]] [--swc V]\n"
             "         [--sor V] [--swof FILE] [--swof-rows N] [--swof-points law|measured]\n"
             "         [--pc-morph pc_morph.csv] [--json FILE] [--png FILE] [--quiet]\n",
    .purpose = "Corey/LET fits of a relative-permeability table: the law choice, SWOF export.",
    .about = "Fits Corey and LET relative-permeability laws to TABLE (the relperm.csv of mdpore "
             "relperm: Sw,Sw_err,krw,krw_err,kro,kro_err,...) by weighted least squares (TAO), "
             "chooses LET only when it is significantly better (chi2-drop test at 0.27 % and a "
             "lower BIC), writes JSON (default TABLE.fit.json) and optionally an Eclipse/OPM SWOF "
             "table (Sw krw krow Pcow, METRIC).\n"
             "A law is a result only when each phase follows it within its errors: chi2/dof <= 1 "
             "+ 3 sqrt(2/dof) for krw and for kro. When no law passes (or the kr have no errors, "
             "so chi2 cannot be judged), the report says why with the numbers, prints no law "
             "parameters, and the SWOF table is the measured points (monotone), said so in its "
             "header; exit 0.",
    .options = fit_relperm_options,
    .more = "docs/relperm.md section 5",
};

#ifndef MDPORE_PYTHON_EXE
#define MDPORE_PYTHON_EXE "/usr/bin/python3"
#endif
#ifndef MDPORE_RELPERM_PLOT_SCRIPT
#define MDPORE_RELPERM_PLOT_SCRIPT "plot_relperm.py"
#endif

typedef struct {
  const char *table, *json, *png, *swof, *pc;
  int law; /* -1: auto */
  int swof_rows, measured, quiet, force;
  kr_fit_opts fit;
  int petsc_argc;
  char **petsc_argv;
} relperm_args;

static int parse_number(const char *opt, const char *s, double lo, double hi, double *v) {
  char *end;
  *v = strtod(s, &end);
  if (end == s || *end || !(*v >= lo && *v < hi)) {
    fprintf(stderr, "mdpore fit relperm: %s: expected a number in [%g, %g) (got '%s')\n", opt, lo,
            hi, s);
    return -1;
  }
  return 0;
}

/* Returns 0, CLI_HELP_SHORT or CLI_HELP_ALL (help asked) or -1. */
static int parse_args(int argc, char **argv, relperm_args *a) {
  memset(a, 0, sizeof *a);
  a->law = -1;
  a->swof_rows = KR_SWOF_DEFAULT_ROWS;
  a->fit.swc = a->fit.sor = NAN;
  a->petsc_argv = calloc(argc + 1, sizeof(char *));
  if (!a->petsc_argv) {
    fprintf(stderr, "mdpore fit: out of memory\n");
    return -1;
  }
  a->petsc_argv[a->petsc_argc++] = argv[0];
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    const int has_val = i + 1 < argc;
    if (cli_help_flag(s)) return cli_help_flag(s);
    if (!strcmp(s, "--json") && has_val)
      a->json = argv[++i];
    else if ((!strcmp(s, "--png") || !strcmp(s, "--plot")) && has_val)
      a->png = argv[++i];
    else if (!strcmp(s, "--swof") && has_val)
      a->swof = argv[++i];
    else if (!strcmp(s, "--pc-morph") && has_val)
      a->pc = argv[++i];
    else if (!strcmp(s, "--law") && has_val) {
      const char *v = argv[++i];
      a->law = strcmp(v, "auto") ? kr_law_from_name(v) : -1;
      if (strcmp(v, "auto") && a->law < 0) {
        fprintf(stderr, "mdpore fit relperm: --law: expected auto, corey or let (got '%s')\n", v);
        return -1;
      }
    } else if (!strcmp(s, "--swc") && has_val) {
      if (parse_number(s, argv[++i], 0.0, 1.0, &a->fit.swc)) return -1;
    } else if (!strcmp(s, "--sor") && has_val) {
      if (parse_number(s, argv[++i], 0.0, 1.0, &a->fit.sor)) return -1;
    } else if (!strcmp(s, "--swof-rows") && has_val) {
      char *end;
      const char *v = argv[++i];
      long n = strtol(v, &end, 10);
      if (end == v || *end || n < 2 || n > 10000) {
        fprintf(stderr,
                "mdpore fit relperm: --swof-rows: expected an integer in [2, 10000] (got "
                "'%s')\n",
                v);
        return -1;
      }
      a->swof_rows = (int)n;
    } else if (!strcmp(s, "--swof-points") && has_val) {
      const char *v = argv[++i];
      if (strcmp(v, "law") && strcmp(v, "measured")) {
        fprintf(stderr, "mdpore fit relperm: --swof-points: expected law or measured (got '%s')\n",
                v);
        return -1;
      }
      a->measured = !strcmp(v, "measured");
    } else if (!strcmp(s, "--quiet"))
      a->quiet = 1;
    else if (!strcmp(s, "--force"))
      a->force = 1;
    else if (s[0] == '-' && s[1] == '-') {
      fprintf(stderr, "mdpore fit relperm: unknown or incomplete option '%s'\n", s);
      return -1;
    } else if (s[0] == '-') {
      a->petsc_argv[a->petsc_argc++] = argv[i];
      if (has_val && argv[i + 1][0] != '-') a->petsc_argv[a->petsc_argc++] = argv[++i];
    } else if (!a->table)
      a->table = s;
    else {
      fprintf(stderr, "mdpore fit relperm: unexpected argument '%s'\n", s);
      return -1;
    }
  }
  if (!a->table) {
    fprintf(stderr, "mdpore fit relperm: no TABLE given\n");
    return -1;
  }
  if (a->force && a->law < 0) {
    fprintf(stderr,
            "mdpore fit relperm: --force: expected with --law corey or --law let (it takes the "
            "law asked for even when the data refuse it)\n");
    return -1;
  }
  if (isfinite(a->fit.swc) && isfinite(a->fit.sor) && !(a->fit.swc + a->fit.sor < 1.0)) {
    fprintf(stderr, "mdpore fit relperm: --swc + --sor: expected a sum below 1 (got %g)\n",
            a->fit.swc + a->fit.sor);
    return -1;
  }
  return 0;
}

static int export_swof(const relperm_args *a, const kr_table *t, const kr_fit_result fits[],
                       const kr_choice *c, const kr_outcome *out, kr_swof *s) {
  char err[1024], law_text[3000];
  pc_curve pc;
  if (a->pc && pc_curve_read(a->pc, &pc, err, sizeof err)) {
    fprintf(stderr, "mdpore fit relperm: --pc-morph: %s\n", err);
    return 1;
  }
  const kr_fit_result *r = out->law >= 0 ? &fits[out->law] : NULL;
  int rc = 0;
  if (kr_swof_build(t, r ? &r->law : NULL, a->swof_rows, a->measured, a->pc ? &pc : NULL, s, err,
                    sizeof err)) {
    fprintf(stderr, "mdpore fit relperm: %s\n", err);
    rc = 1;
  } else {
    if (r) {
      kr_law_text(r, law_text, sizeof law_text);
      if (out->text[0]) {
        const size_t n = strlen(law_text);
        snprintf(law_text + n, sizeof law_text - n, " [%s]", out->text);
      }
    } else
      snprintf(law_text, sizeof law_text, "none accepted: %s", out->text);
    if (kr_swof_write(a->swof, s, t, a->pc ? &pc : NULL, law_text, c->text, err, sizeof err)) {
      fprintf(stderr, "mdpore fit relperm: %s\n", err);
      rc = 1;
    } else if (!a->quiet) {
      printf("wrote %s (%d rows, %s", a->swof, s->n,
             s->no_law     ? "the MEASURED POINTS, not a law"
             : s->measured ? "measured points"
                           : "law grid");
      if (s->n_clipped)
        printf("; %d row(s) with kr > 1 clipped to 1, peak %.4g", s->n_clipped, s->kr_peak);
      if (a->pc && !isfinite(s->pc_bar_factor)) printf("; Pcow in reduced units");
      printf(")\n");
    }
  }
  if (a->pc) pc_curve_free(&pc);
  return rc;
}

static int run(const relperm_args *a) {
  char err[1024], json_path[4200];
  if (a->json)
    snprintf(json_path, sizeof json_path, "%s", a->json);
  else
    snprintf(json_path, sizeof json_path, "%s.fit.json", a->table);
  const char *outs[3] = {json_path, a->swof, a->png}, *roles[3] = {"--json", "--swof", "--png"};
  const char *ins[2] = {a->table, a->pc}, *in_roles[2] = {"the table", "--pc-morph"};
  if (mdp_check_outputs(outs, roles, 3, ins, in_roles, a->pc ? 2 : 1, err, sizeof err)) {
    fprintf(stderr, "mdpore fit relperm: %s\n", err);
    return 1;
  }
  kr_table t;
  if (kr_table_read(a->table, &t, err, sizeof err)) {
    fprintf(stderr, "mdpore fit relperm: %s\n", err);
    return 1;
  }
  kr_fit_result fits[KR_LAW_COUNT];
  memset(fits, 0, sizeof fits);
  /* points without errors cannot weight a fit nor judge it: no law is fitted when a phase has
   * none (kr_outcome.h) */
  const int weighted =
      kr_phase_points_with_error(&t, 0) > 0 && kr_phase_points_with_error(&t, 1) > 0;
  for (int k = 0; k < KR_LAW_COUNT; k++) {
    fits[k].kind = k;
    if (!weighted || (k == KR_LET && a->law == KR_COREY)) continue;
    kr_fit_opts o = a->fit; /* LET starts from the Corey fit */
    if (k == KR_LET && fits[KR_COREY].ok) o.corey_start = &fits[KR_COREY].law;
    kr_fit_law(&t, k, &o, &fits[k]);
  }
  kr_choice c;
  kr_choose(fits, a->law, &c);
  kr_outcome out;
  kr_decide(&t, fits, &c, a->law, a->force, &out);
  int rc = out.refused ? KR_EXIT_LAW_REFUSED : 0;
  if (out.refused)
    fprintf(stderr, "mdpore fit relperm: %s: %s%s\n", t.path, out.text,
            a->swof ? "; no SWOF table written" : "");
  kr_swof s = {0};
  const int have_swof = !rc && a->swof;
  if (have_swof) rc = export_swof(a, &t, fits, &c, &out, &s);
  if ((!rc || rc == KR_EXIT_LAW_REFUSED) &&
      kr_write_json(json_path, &t, &a->fit, fits, &c, &out, have_swof ? &s : NULL, a->swof)) {
    fprintf(stderr, "mdpore fit relperm: %s: cannot write the report\n", json_path);
    rc = 1;
  }
  if (!a->quiet) {
    kr_print(stdout, &t, &a->fit, fits, &c, &out);
    if (!rc || rc == KR_EXIT_LAW_REFUSED) printf("wrote %s\n", json_path);
  }
  if (!rc && a->png) {
    char cmd[9000];
    snprintf(cmd, sizeof cmd, "'%s' '%s' '%s' '%s'", MDPORE_PYTHON_EXE, MDPORE_RELPERM_PLOT_SCRIPT,
             json_path, a->png);
    if (system(cmd) != 0) {
      fprintf(stderr, "mdpore fit relperm: plotting failed (%s)\n", cmd);
      rc = 1;
    } else if (!a->quiet)
      printf("wrote %s\n", a->png);
  }
  kr_swof_free(&s);
  kr_table_free(&t);
  return rc;
}

int cmd_fit_relperm(int argc, char **argv) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  relperm_args a;
  const int p = parse_args(argc, argv, &a);
  if (p != 0) {
    if (rank == 0)
      cli_help_print(p > 0 ? stdout : stderr, &fit_relperm_help, p > 0 ? p : CLI_HELP_SHORT);
    free(a.petsc_argv);
    return p > 0 ? 0 : 2;
  }
  if (PetscInitialize(&a.petsc_argc, &a.petsc_argv, NULL, NULL)) {
    free(a.petsc_argv);
    return 1;
  }
  int rc = rank == 0 ? run(&a) : 0; /* a fit is small: one rank does it */
  MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
  PetscFinalize();
  free(a.petsc_argv);
  return rc;
}
