/* `mdpore fit TABLE`: fit every flow law to a flow-data table, choose one, write JSON (+ optional
 * PNG). */
#include <mpi.h>
#include <petscsys.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd_fit_relperm.h"
#include "commands.h"
#include "common/cli_help.h"
#include "common/same_file.h"
#include "fit_check.h"
#include "fit_report.h"
#include "fit_tao.h"
#include "flowdata/flow_table.h"

static const cli_help_option_t fit_options[] = {
    {"--json OUT.json", "the JSON report (default: TABLE with .fit.json)", 1},
    {"--models LIST", "comma-separated subset of darcy,threshold,forchheimer,power", 1},
    {"--criterion C", "model selection by bic (default) or aic", 1},
    {"--plot PNG", "plot data, fits and residuals (python3 + matplotlib)", 1},
    {"--quiet", "no table or 'wrote' lines on stdout", 1},
    {NULL, NULL, 0}};

static const cli_help_page_t fit_help = {
    .command = "fit",
    .usage = "usage: mdpore fit TABLE [--json OUT.json] [--plot OUT.png] [--models LIST]\n"
             "                        [--criterion bic|aic] [--quiet]\n"
             "       [PETSc/TAO options with prefix -fit_, e.g. -fit_tao_monitor]\n"
             "       mdpore fit relperm TABLE ...   (see mdpore fit relperm --help)\n",
    .purpose = "Fit Darcy and non-Darcy flow laws to a flow-data table and choose one.",
    .about = "Fits Darcy, threshold (Darcy with intercept), Forchheimer and power laws to TABLE "
             "(docs/flow-table.md) by weighted least squares (TAO), prints a table and writes "
             "JSON (default: TABLE with .fit.json).",
    .options = fit_options,
    .notes = "mdpore fit relperm TABLE ...: Corey/LET fits of a relative-permeability table and "
             "the SWOF export (mdpore fit relperm --help; docs/relperm.md section 5)",
    .more = "docs/flow-table.md",
};

#ifndef MDPORE_PYTHON_EXE
#define MDPORE_PYTHON_EXE "/usr/bin/python3"
#endif
#ifndef MDPORE_FIT_PLOT_SCRIPT
#define MDPORE_FIT_PLOT_SCRIPT "plot_fit.py"
#endif

typedef struct {
  const char *table, *json, *plot;
  flow_law_kind kinds[LAW_COUNT];
  int nk, quiet;
  fit_criterion crit;
  int petsc_argc;
  char **petsc_argv;
} fit_args;

static int parse_models(const char *list, fit_args *a) {
  char buf[256];
  snprintf(buf, sizeof buf, "%s", list);
  a->nk = 0;
  for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
    int k = flow_law_from_name(tok);
    if (k < 0) {
      fprintf(stderr,
              "mdpore fit: --models: unknown law '%s' (expected darcy, threshold, "
              "forchheimer or power)\n",
              tok);
      return -1;
    }
    for (int i = 0; i < a->nk; i++)
      if (a->kinds[i] == (flow_law_kind)k) k = -1;
    if (k >= 0 && a->nk < LAW_COUNT) a->kinds[a->nk++] = k;
  }
  return a->nk ? 0 : -1;
}

/* Our options are --long; single-dash options (and their values) go to PETSc. Returns 0, 1 (help),
 * -1. */
static int parse_args(int argc, char **argv, fit_args *a) {
  memset(a, 0, sizeof *a);
  for (int k = 0; k < LAW_COUNT; k++) a->kinds[k] = k;
  a->nk = LAW_COUNT;
  a->petsc_argv = calloc(argc + 1, sizeof(char *));
  if (!a->petsc_argv) {
    fprintf(stderr, "mdpore fit: out of memory\n");
    return -1;
  }
  a->petsc_argv[a->petsc_argc++] = argv[0];
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    int has_val = i + 1 < argc;
    if (cli_help_flag(s)) return cli_help_flag(s);
    if (!strcmp(s, "--json") && has_val)
      a->json = argv[++i];
    else if (!strcmp(s, "--plot") && has_val)
      a->plot = argv[++i];
    else if (!strcmp(s, "--models") && has_val) {
      if (parse_models(argv[++i], a)) return -1;
    } else if (!strcmp(s, "--criterion") && has_val) {
      const char *c = argv[++i];
      if (!strcmp(c, "bic"))
        a->crit = SELECT_BIC;
      else if (!strcmp(c, "aic"))
        a->crit = SELECT_AIC;
      else {
        fprintf(stderr, "mdpore fit: --criterion: expected bic or aic, got '%s'\n", c);
        return -1;
      }
    } else if (!strcmp(s, "--quiet"))
      a->quiet = 1;
    else if (s[0] == '-' && s[1] == '-') {
      fprintf(stderr, "mdpore fit: unknown or incomplete option '%s'\n", s);
      return -1;
    } else if (s[0] == '-') {
      a->petsc_argv[a->petsc_argc++] = argv[i];
      if (has_val && argv[i + 1][0] != '-') a->petsc_argv[a->petsc_argc++] = argv[++i];
    } else if (!a->table)
      a->table = s;
    else {
      fprintf(stderr, "mdpore fit: unexpected argument '%s'\n", s);
      return -1;
    }
  }
  if (!a->table) {
    fprintf(stderr, "mdpore fit: no TABLE given\n");
    return -1;
  }
  return 0;
}

/* The work, on one rank. */
static int run_fit(const fit_args *a) {
  char err[1024], json_path[1100];
  flow_table t;
  const char *outs[2] = {a->json, a->plot}, *out_roles[2] = {"--json", "--plot"};
  const char *ins[1] = {a->table}, *in_roles[1] = {"the table"};
  if (mdp_check_outputs(outs, out_roles, 2, ins, in_roles, 1, err, sizeof err)) {
    fprintf(stderr, "mdpore fit: %s\n", err);
    return 1;
  }
  if (flow_table_read(a->table, &t, err, sizeof err)) {
    fprintf(stderr, "mdpore fit: %s\n", err);
    return 1;
  }
  if (fit_check_table(&t, a->kinds, a->nk, err, sizeof err)) {
    fprintf(stderr, "mdpore fit: %s\n", err);
    flow_table_free(&t);
    return 1;
  }
  fit_data d = {t.n, t.G, t.q, t.sigma};
  fluid_props fl = {t.viscosity, t.density};
  fit_result r[LAW_COUNT];
  int chosen = fit_all(&d, &fl, a->kinds, a->nk, a->crit, r);
  if (a->json)
    snprintf(json_path, sizeof json_path, "%s", a->json);
  else
    snprintf(json_path, sizeof json_path, "%s.fit.json", a->table);
  int rc = fit_write_json(json_path, &t, r, a->nk, chosen, a->crit) ? 1 : 0;
  if (!a->quiet) {
    fit_print_table(stdout, &t, r, a->nk, chosen, a->crit);
    printf("wrote %s\n", json_path);
  }
  if (!rc && a->plot) {
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "'%s' '%s' '%s' '%s'", MDPORE_PYTHON_EXE, MDPORE_FIT_PLOT_SCRIPT,
             json_path, a->plot);
    if (system(cmd) != 0) {
      fprintf(stderr, "mdpore fit: plotting failed (%s)\n", cmd);
      rc = 1;
    } else if (!a->quiet)
      printf("wrote %s\n", a->plot);
  }
  if (chosen < 0) {
    fprintf(stderr, "mdpore fit: no law could be fitted to %s\n", t.path);
    rc = 1;
  }
  flow_table_free(&t);
  return rc;
}

int cmd_fit(int argc, char **argv) {
  if (argc > 1 && !strcmp(argv[1], "relperm")) return cmd_fit_relperm(argc - 1, argv + 1);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  fit_args a;
  int p = parse_args(argc, argv, &a);
  if (p != 0) {
    if (rank == 0) cli_help_print(p > 0 ? stdout : stderr, &fit_help, p > 0 ? p : CLI_HELP_SHORT);
    free(a.petsc_argv);
    return p > 0 ? 0 : 2;
  }
  if (PetscInitialize(&a.petsc_argc, &a.petsc_argv, NULL, NULL)) {
    free(a.petsc_argv);
    return 1;
  }
  int rc = rank == 0 ? run_fit(&a) : 0; /* a fit is small: one rank does it */
  MPI_Bcast(&rc, 1, MPI_INT, 0, MPI_COMM_WORLD);
  PetscFinalize();
  free(a.petsc_argv);
  return rc;
}
