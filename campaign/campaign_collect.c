/* Collect a campaign: per axis the runs the data cannot trust left out and named
 * (campaign_checks.c), the flow table of the others WORKDIR/flow_<axis>.csv (flowdata/ writer), its
 * Darcy range (campaign_linear.c), `mdpore fit` on it when the range exists (subprocess: JSON
 * WORKDIR/fit_<axis>.json, PNG WORKDIR/flow_<axis>.png when python3 has matplotlib), the report on
 * stdout (k in rc^2, m^2, nD and the chosen law, or "no Darcy range", why and what to try) and
 * WORKDIR/permeability.json. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "campaign.h"
#include "common/atomic_file.h"
#include "common/json_out.h"
#include "common/yaml_tree.h"
#include "flowdata/flow_table.h"

#ifndef MDPORE_PYTHON_EXE
#define MDPORE_PYTHON_EXE "python3"
#endif

#define NANODARCY_PER_M2 UNITS_NANODARCY_PER_M2

typedef struct {
  int fitted; /* the fit JSON was read */
  char chosen[32];
  double k, k_err; /* the Darcy k (rc^2) */
  int n_par;
  char par_name[4][16];
  double par[4], par_err[4];
  char par_unit[4][96];
  double chi2_dof; /* of the chosen law */
  int rows;
  camp_linear linear;      /* the Darcy range (campaign_linear.c) */
  int defined;             /* the admissible runs define k (a Darcy range exists) */
  double k_all, k_all_err; /* mdpore fit's Darcy k over every admissible row (context) */
  char undefined_why[512];
  int n_left_out;       /* runs left out by camp_run_admissible */
  int n_no_temperature; /* kept runs whose summary has no temperature (stopped before its window) */
  int n_target_missed;  /* kept runs that missed their target error (no --require-target) */
  int n_missing;        /* runs of the axis without a usable summary */
  double left_out_G[CAMP_MAX_GRADIENTS];
  char left_out_dir[CAMP_MAX_GRADIENTS][1024];
  const char *left_out_check[CAMP_MAX_GRADIENTS]; /* camp_flag.check */
  double left_out_measured[CAMP_MAX_GRADIENTS];   /* camp_flag.measured */
  char left_out_why[CAMP_MAX_GRADIENTS][256];
} axis_result;

/* The steps a run ran: all of its segments for a run continued from its checkpoint. */
static long long run_steps(const camp_run *r) {
  return r->last_step > 0 ? r->last_step : r->steps;
}

static int by_g(const void *a, const void *b) {
  const camp_run *x = *(camp_run *const *)a, *y = *(camp_run *const *)b;
  return (x->G > y->G) - (x->G < y->G);
}

/* Darcy k by weighted least squares (the fallback without `mdpore fit`). */
static void own_darcy(const flow_table *t, double mu, double *k, double *se) {
  double sgq = 0, sgg = 0;
  for (int i = 0; i < t->n; i++) {
    double w = 1.0 / (t->sigma[i] * t->sigma[i]);
    sgq += w * t->G[i] * t->q[i];
    sgg += w * t->G[i] * t->G[i];
  }
  *k = mu * sgq / sgg;
  *se = mu / sqrt(sgg);
}

static double jnum(ytree_t *t, yaml_node_t *map, const char *key) {
  yaml_node_t *n = map ? yt_get(t, map, key) : NULL;
  double v;
  if (!n || yt_is_null(n) || yt_double(t, n, key, &v)) return NAN;
  return v;
}

/* The chosen law, its parameters and the Darcy k from the fit JSON. */
static int read_fit(const char *path, axis_result *ar) {
  ytree_t t;
  if (yt_load(&t, path, 0)) return -1;
  yaml_node_t *root = yt_root(&t), *n;
  if (!root || yt_expect_map(&t, root, "")) {
    yt_free(&t);
    return -1;
  }
  snprintf(ar->chosen, sizeof ar->chosen, "none");
  if ((n = yt_get(&t, root, "chosen")) && !yt_is_null(n))
    yt_string(&t, n, "chosen", ar->chosen, sizeof ar->chosen);
  yaml_node_t *models = yt_get(&t, root, "models");
  for (int i = 0; models && models->type == YAML_SEQUENCE_NODE && i < yt_seq_size(models); i++) {
    yaml_node_t *m = yt_seq_item(&t, models, i);
    char law[32] = "";
    if (!(n = yt_get(&t, m, "law")) || yt_string(&t, n, "law", law, sizeof law)) continue;
    yaml_node_t *pars = yt_get(&t, m, "parameters");
    if (!pars || pars->type != YAML_MAPPING_NODE) continue;
    if (!strcmp(law, "darcy")) {
      yaml_node_t *k = yt_get(&t, pars, "k");
      ar->k = jnum(&t, k, "value");
      ar->k_err = jnum(&t, k, "stderr");
    }
    if (!strcmp(law, ar->chosen)) {
      ar->chi2_dof = jnum(&t, m, "chi2_dof");
      ar->n_par = 0;
      for (int p = 0; p < yt_map_size(pars) && p < 4; p++) {
        const char *name = yt_map_key(&t, pars, p, NULL);
        yaml_node_t *pv = yt_map_value(&t, pars, p);
        snprintf(ar->par_name[p], sizeof ar->par_name[p], "%s", name ? name : "?");
        ar->par[p] = jnum(&t, pv, "value");
        ar->par_err[p] = jnum(&t, pv, "stderr");
        ar->par_unit[p][0] = 0;
        if ((n = yt_get(&t, pv, "unit")))
          yt_string(&t, n, "unit", ar->par_unit[p], sizeof ar->par_unit[p]);
        ar->n_par++;
      }
    }
  }
  yt_free(&t);
  ar->fitted = 1;
  return 0;
}

static int have_matplotlib(void) {
  return system("'" MDPORE_PYTHON_EXE "' -c 'import matplotlib' > /dev/null 2>&1") == 0;
}

/* The axis's result: the runs left out and why, then k from the Darcy range, or the refusal. */
static void report_axis(int axis, const campaign *c, const camp_units *u, axis_result *ar) {
  for (int i = 0; i < ar->n_left_out; i++)
    printf("  left out: G = %.5g (%s): %s\n", ar->left_out_G[i], ar->left_out_dir[i],
           ar->left_out_why[i]);
  if (ar->n_missing)
    printf("  note: %d run(s) of this axis had no result (see stderr)\n", ar->n_missing);
  if (ar->n_target_missed)
    printf("  note: %d kept run(s) missed their target error (marked in the table): their larger "
           "error bars weight them less; --require-target leaves them out\n",
           ar->n_target_missed);
  if (ar->n_no_temperature)
    printf("  note: the temperature of %d kept run(s) was not measured (the run stopped early, "
           "before the second half of its step budget where mdpore run averages thermo): the "
           "heating check did not apply to them\n",
           ar->n_no_temperature);
  ar->k_all = ar->k;
  ar->k_all_err = ar->k_err;
  ar->defined = !ar->undefined_why[0] && ar->linear.accepted;
  if (!ar->defined) {
    printf("  no Darcy range: k_%c%c is not defined by these runs: %s.\n  try: a finer resolution "
           "(--rc-per-voxel, --min-throat) where the liquid cavitated or the throats are narrow; "
           "weaker forcing (--velocity-range, e.g. 0.005,0.05) where it was compressed, heated or "
           "left the linear law; longer runs (--max-steps) where the flux did not settle\n",
           'x' + axis, 'x' + axis, ar->undefined_why[0] ? ar->undefined_why : "no Darcy range");
    /* no law and no k over rows the data reject: permeability.json says none was chosen */
    ar->k = ar->k_err = ar->k_all = ar->k_all_err = NAN;
    snprintf(ar->chosen, sizeof ar->chosen, "none");
    ar->n_par = 0;
    ar->chi2_dof = NAN;
    return;
  }
  /* the permeability is the Darcy range's k: the fit over every admissible row is context */
  ar->k = ar->linear.k;
  ar->k_err = ar->linear.k_err;
  printf("  k_%c%c = %.5g +- %.2g rc^2 = %.4g +- %.2g m^2 = %.4g +- %.2g nD (Darcy range; "
         "superficial velocity q = Q / A_total, k = mu q / G, mu = %g)\n",
         'x' + axis, 'x' + axis, ar->k, ar->k_err, ar->k * u->k_m2, ar->k_err * u->k_m2,
         ar->k * u->k_m2 * NANODARCY_PER_M2, ar->k_err * u->k_m2 * NANODARCY_PER_M2, c->viscosity);
  if (ar->fitted || ar->chosen[0]) {
    printf("  chosen law: %s (chi2/dof %.3g):", ar->chosen, ar->chi2_dof);
    for (int p = 0; p < ar->n_par; p++)
      printf(" %s = %.5g +- %.2g%s%s", ar->par_name[p], ar->par[p], ar->par_err[p],
             ar->par_unit[p][0] ? " " : "", ar->par_unit[p]);
    printf("\n");
  }
}

static int collect_axis(const camp_opts *o, const campaign *c, const char *workdir, int axis,
                        const camp_units *u, axis_result *ar) {
  camp_run *rows[CAMP_MAX_RUNS];
  int n = 0, missing = 0;
  char why[CAMP_PATH + 256];
  char table[CAMP_PATH + 32], fitjson[CAMP_PATH + 32], png[CAMP_PATH + 32], err[1024];
  snprintf(table, sizeof table, "%s/flow_%c.csv", workdir, 'x' + axis);
  snprintf(fitjson, sizeof fitjson, "%s/fit_%c.json", workdir, 'x' + axis);
  snprintf(png, sizeof png, "%s/flow_%c.png", workdir, 'x' + axis);
  for (int i = 0; i < c->n_runs; i++) {
    camp_run *r = (camp_run *)&c->runs[i];
    if (r->axis != axis) continue;
    if (!r->have) camp_read_summary(r, why, sizeof why);
    if (!r->have) {
      fprintf(stderr, "mdpore permeability: axis %c, g = %g: left out of the table: %s\n",
              'x' + axis, r->g, why);
      missing++;
      continue;
    }
    rows[n++] = r;
  }
  memset(ar, 0, sizeof *ar);
  ar->k = ar->k_err = ar->k_all = ar->k_all_err = ar->chi2_dof = NAN;
  ar->n_missing = missing;
  camp_checks lim;
  camp_checks_of(o, c, &lim);
  qsort(rows, n, sizeof rows[0], by_g);
  /* runs whose liquid is not the linear response's are left out */
  camp_run *out[CAMP_MAX_GRADIENTS];
  camp_flag flags[CAMP_MAX_GRADIENTS];
  const int kept = camp_admit_rows(rows, n, &lim, out, flags, &ar->n_left_out);
  for (int i = 0; i < ar->n_left_out; i++) {
    ar->left_out_G[i] = out[i]->G;
    snprintf(ar->left_out_dir[i], 1024, "%.1023s", out[i]->dir);
    ar->left_out_check[i] = flags[i].check;
    ar->left_out_measured[i] = flags[i].measured;
    snprintf(ar->left_out_why[i], 256, "%s", flags[i].why);
  }
  for (int i = 0; i < kept; i++) {
    ar->n_no_temperature += !isfinite(rows[i]->temperature);
    ar->n_target_missed += rows[i]->reached == 0;
  }
  const int usable = n;
  n = kept;
  ar->rows = n;
  if (n < 2) {
    if (usable >= 2) { /* runs there are, but not two the data can trust */
      snprintf(ar->undefined_why, sizeof ar->undefined_why,
               "%d of %d runs left out (each named above with its reason), %d left", ar->n_left_out,
               usable, n);
      /* no table, fit or plot of this axis: none from an earlier collect may stand for it */
      unlink(table);
      unlink(fitjson);
      unlink(png);
      printf("\n== permeability along %c: %s ==\n", 'x' + axis, c->sample);
      report_axis(axis, c, u, ar);
      return 0;
    }
    fprintf(stderr,
            "mdpore permeability: axis %c: %d usable run(s): expected at least 2 to fit "
            "(run the missing ones: %s/commands.txt, or rerun the campaign)\n",
            'x' + axis, n, workdir);
    return -1;
  }
  qsort(rows, n, sizeof rows[0], by_g);
  flow_table t;
  flow_table_init(&t);
  snprintf(t.sample, sizeof t.sample, "%s", c->sample);
  snprintf(t.axis, sizeof t.axis, "%c", 'x' + axis);
  snprintf(t.length_unit, sizeof t.length_unit, "rc");
  t.si = 0;
  t.viscosity = c->viscosity;
  t.density = c->fluid_density; /* particle mass 1 */
  t.length_unit_m = c->length_unit_m;
  if (isfinite(c->rc_per_voxel)) t.voxel_size = c->rc_per_voxel;
  char line[CAMP_PATH + 256];
  if (c->drive == CAMP_DRIVE_PRESSURE) {
    snprintf(
        line, sizeof line,
        "made by mdpore permeability (docs/permeability.md): pressure-driven runs (inlet force "
        "in an open reservoir of %g rc added along the axis); G = (P_in - P_out) / L_sample "
        "measured between probe slabs outside the sample faces (its error per run below); "
        "darcy_velocity_stderr = sqrt(q_err^2 + (q G_err / G)^2), the effective variance "
        "that carries G's error into q's for the fit (q_err alone per run below)",
        c->reservoir);
    flow_table_add_comment(&t, line);
  } else
    flow_table_add_comment(&t,
                           "made by mdpore permeability (docs/permeability.md): body-force runs, "
                           "G = n m g (body force per fluid volume)");
  flow_table_add_comment(&t, "convention: superficial (Darcy) velocity q = Q / A_total, A_total = "
                             "the whole cross-section (solid included); k = mu q / G");
  snprintf(line, sizeof line, "input = %s", c->input);
  flow_table_add_comment(&t, line);
  snprintf(line, sizeof line, "porosity = %.6g (pore voxels / all voxels)", c->porosity);
  flow_table_add_comment(&t, line);
  snprintf(line, sizeof line, "viscosity source = %s", c->viscosity_source);
  flow_table_add_comment(&t, line);
  snprintf(line, sizeof line, "length unit = %s", c->length_source);
  flow_table_add_comment(&t, line);
  if (camp_rounds_done.n_rounds > 0) /* --target-error-k: no run had a target of its own */
    snprintf(line, sizeof line,
             "run_length = steps run (over every round); the campaign stopped on the relative "
             "error of k, target %g (--target-error-k)",
             camp_rounds_done.target);
  else
    snprintf(line, sizeof line, "run_length = steps run; target relative error %g",
             c->target_error);
  flow_table_add_comment(&t, line);
  /* the runs left out are no rows of the table (nor of the fits): named here with the reason */
  for (int i = 0; i < ar->n_left_out; i++) {
    snprintf(line, sizeof line, "left out (%s): G = %.6g: %.1023s: %s", ar->left_out_check[i],
             ar->left_out_G[i], ar->left_out_dir[i], ar->left_out_why[i]);
    flow_table_add_comment(&t, line);
  }
  for (int i = 0; i < n; i++) {
    char measured[160] = "";
    if (c->drive == CAMP_DRIVE_PRESSURE)
      snprintf(measured, sizeof measured,
               ", G = %.6g +- %.2g, q_err = %.3g, dp / (inlet force / A) = %.4g", rows[i]->G,
               rows[i]->G_err, rows[i]->q_err, rows[i]->dp_balance);
    snprintf(line, sizeof line, "run g = %.6g: %s (steady from step %lld, target %s%s)", rows[i]->g,
             rows[i]->dir, rows[i]->steady_from,
             rows[i]->reached < 0 ? "none"
             : rows[i]->reached   ? "reached"
                                  : "NOT reached",
             measured);
    flow_table_add_comment(&t, line);
    /* Pressure drive: G is measured, so its error joins q's (effective variance, linear law) */
    const double rel_G = c->drive == CAMP_DRIVE_PRESSURE && isfinite(rows[i]->G_err)
                             ? rows[i]->G_err / rows[i]->G
                             : 0.0;
    const double sigma =
        sqrt(rows[i]->q_err * rows[i]->q_err + rows[i]->q * rows[i]->q * rel_G * rel_G);
    flow_table_add_row(&t, rows[i]->G, rows[i]->q, sigma, (double)run_steps(rows[i]));
  }
  /* the Darcy range decides whether these rows define k at all, before any law is fitted to them */
  const camp_linear *L = &ar->linear;
  camp_darcy_range(t.G, t.q, t.sigma, t.n, c->viscosity, &ar->linear); /* n >= 2: 0 */
  if (!L->accepted) {
    snprintf(ar->undefined_why, sizeof ar->undefined_why,
             "the %d lowest of %d admissible gradients do not fit a Darcy law (chi2/dof %.3g "
             "above %.3g: the rows scatter beyond their error bars)",
             L->rows, t.n, L->chi2_dof, 1.0 + 3.0 * sqrt(2.0 / (L->rows - 1)));
    snprintf(line, sizeof line, "no Darcy range: %s; no law fitted, k not defined",
             ar->undefined_why);
    flow_table_add_comment(&t, line);
  }
  int rc = flow_table_write(table, &t, err, sizeof err);
  if (rc) fprintf(stderr, "mdpore permeability: %s\n", err);
  printf("\n== permeability along %c: %s ==\n", 'x' + axis, c->sample);
  if (c->boundary[axis])
    printf("  boundary: faces %s (seam continuity %.2f), sides %s (docs/permeability.md, "
           "Boundaries)\n",
           camp_boundary_name(c->boundary[axis]), c->seam_continuity[axis],
           c->sides_mirror ? "mirror" : "periodic");
  printf("  %-12s %-12s %-12s %-12s %-12s %-10s %s\n", "g", "G", "G [Pa/m]", "q", "q_err",
         "q [m/s]", "steps");
  for (int i = 0; i < n; i++)
    printf("  %-12.5g %-12.5g %-12.4g %-12.5g %-12.3g %-10.3g %lld%s%s\n", rows[i]->g, rows[i]->G,
           rows[i]->G * u->G_Pa_per_m, rows[i]->q, rows[i]->q_err, rows[i]->q * u->q_m_per_s,
           run_steps(rows[i]), rows[i]->reached == 0 ? " (target not reached)" : "",
           rows[i]->reused ? " (reused)" : "");
  if (c->drive == CAMP_DRIVE_PRESSURE) {
    printf("  pressure drive (reservoir %g rc): G measured, g = the equivalent body force of the "
           "inlet force;\n  per run G_err and dp / (inlet force / A_total):",
           c->reservoir);
    for (int i = 0; i < n; i++) printf(" %.2g/%.3f", rows[i]->G_err, rows[i]->dp_balance);
    printf("\n");
  }
  printf("  wrote %s\n", table);
  fflush(stdout);
  if (!rc && !L->accepted) { /* no law and no k from rows that a Darcy law does not fit */
    unlink(fitjson);
    unlink(png);
    printf("  mdpore fit not run: these rows define no Darcy range, so no law is chosen for them "
           "(the table stays for inspection: mdpore fit %s)\n",
           table);
  } else if (!rc) {
    char *argv[16];
    int a = 0;
    char fit_word[] = "fit", json_flag[] = "--json", plot_flag[] = "--plot",
         models_flag[] = "--models", darcy[] = "darcy";
    argv[a++] = (char *)o->self_exe;
    argv[a++] = fit_word;
    argv[a++] = table;
    argv[a++] = json_flag;
    argv[a++] = fitjson;
    int plot = have_matplotlib();
    if (plot) {
      argv[a++] = plot_flag;
      argv[a++] = png;
    }
    if (o->models[0]) {
      argv[a++] = models_flag;
      argv[a++] = (char *)o->models;
    } else if (n < 3) {
      argv[a++] = models_flag;
      argv[a++] = darcy;
    }
    argv[a] = NULL;
    unlink(fitjson);
    int st = camp_spawn(NULL, argv, NULL);
    if (!plot) printf("  PNG skipped: python3 with matplotlib not found (%s)\n", MDPORE_PYTHON_EXE);
    if (st == 2 && access(fitjson, R_OK)) {
      fprintf(stderr, "mdpore permeability: mdpore fit is not available (built without PETSc): "
                      "Darcy k by weighted least squares here, no other law\n");
      own_darcy(&t, c->viscosity, &ar->k, &ar->k_err);
      snprintf(ar->chosen, sizeof ar->chosen, "darcy");
      ar->n_par = 1;
      snprintf(ar->par_name[0], sizeof ar->par_name[0], "k");
      ar->par[0] = ar->k;
      ar->par_err[0] = ar->k_err;
      snprintf(ar->par_unit[0], sizeof ar->par_unit[0], "rc^2");
      ar->chi2_dof = NAN;
    } else if (access(fitjson, R_OK) || read_fit(fitjson, ar)) {
      fprintf(stderr, "mdpore permeability: mdpore fit %s failed (exit %d)\n", table, st);
      rc = -1;
    }
  }
  if (!rc && L->accepted)
    printf("  Darcy range: the %d lowest of %d gradients (G <= %.4g) fit a Darcy law (chi2/dof "
           "%.3g): k = %.5g +- %.2g rc^2 = %.4g +- %.2g m^2 = %.4g +- %.2g nD%s\n",
           L->rows, t.n, L->G_max, L->chi2_dof, L->k, L->k_err, L->k * u->k_m2, L->k_err * u->k_m2,
           L->k * u->k_m2 * NANODARCY_PER_M2, L->k_err * u->k_m2 * NANODARCY_PER_M2,
           L->rows < t.n ? "; the gradients above leave the linear law (the fit over all rows "
                           "is pulled by them): this k is the permeability"
                         : "");
  if (!rc) report_axis(axis, c, u, ar);
  flow_table_free(&t);
  return rc;
}

static void write_json(const char *workdir, const campaign *c, const camp_units *u, const int *axes,
                       int n_axes, const axis_result *ar) {
  char path[CAMP_PATH + 32], tmp[CAMP_PATH + 96];
  snprintf(path, sizeof path, "%s/permeability.json", workdir);
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return;
  json_out j;
  json_begin(&j, f);
  json_string(&j, "format", "mdpore-permeability");
  json_int(&j, "version", 1);
  json_string(&j, "sample", c->sample);
  json_string(&j, "input", c->input);
  json_number(&j, "porosity", c->porosity);
  json_number(&j, "rc_per_voxel", c->rc_per_voxel);
  json_number(&j, "viscosity", c->viscosity);
  json_string(&j, "viscosity_source", c->viscosity_source);
  if (isfinite(c->wall_density)) json_number(&j, "wall_density", c->wall_density);
  json_number(&j, "fluid_density", c->fluid_density);
  if (isfinite(c->fill_density)) {
    json_number(&j, "fill_density", c->fill_density);
    json_number(&j, "wall_adsorption", c->wall_adsorption);
  }
  if (c->pair_rng[0]) json_string(&j, "pair_rng", c->pair_rng);
  json_string(&j, "drive", c->drive == CAMP_DRIVE_PRESSURE ? "pressure" : "body");
  if (c->drive == CAMP_DRIVE_PRESSURE) json_number(&j, "reservoir_rc", c->reservoir);
  json_object(&j, "boundary");
  for (int d = 0; d < 3; d++)
    if (c->boundary[d]) {
      const char name[2] = {(char)('x' + d), 0};
      json_object(&j, name);
      json_string(&j, "faces", camp_boundary_name(c->boundary[d]));
      json_number(&j, "seam_continuity", c->seam_continuity[d]);
      json_object_end(&j);
    }
  json_string(&j, "sides", c->sides_mirror ? "mirror" : "periodic");
  json_object_end(&j);
  if (c->rc_per_voxel_source[0]) { /* an IMAGE's resolution (campaign_resolution.c) */
    json_object(&j, "resolution");
    json_array(&j, "critical_throat_voxels");
    for (int d = 0; d < 3; d++) json_int(&j, NULL, c->throat_voxels[d]);
    json_array_end(&j);
    json_number(&j, "min_throat_rc", c->min_throat);
    json_string(&j, "rc_per_voxel_source", c->rc_per_voxel_source);
    json_number(&j, "particles_estimate", c->particles_estimate);
    if (c->regime[0]) json_string(&j, "regime", c->regime);
    if (c->resolution_warning[0]) json_string(&j, "warning", c->resolution_warning);
    json_object_end(&j);
  }
  json_string(&j, "convention",
              "superficial (Darcy) velocity q = Q / A_total, A_total = the "
              "whole cross-section (solid included); k = mu q / G");
  json_object(&j, "units");
  json_number(&j, "rc_m", u->rc_m);
  json_string(&j, "length_source", c->length_source);
  json_number(&j, "temperature_K", c->temperature_K);
  json_number(&j, "particle_mass_kg", u->mass_kg);
  json_number(&j, "water_molecules_per_particle", u->n_molecules);
  json_number(&j, "tau_s", u->tau_s);
  json_number(&j, "G_Pa_per_m", u->G_Pa_per_m);
  json_number(&j, "q_m_per_s", u->q_m_per_s);
  json_number(&j, "viscosity_Pa_s", u->mu_Pa_s);
  json_string(&j, "mapping",
              c->particle_mass_kg > 0 || c->energy_J > 0
                  ? "dimensional, from the scene's units block: tau = rc sqrt(m / kT); "
                    "not viscosity-matched"
                  : "dimensional: kT = kB T, m = rho_water / n, tau = rc sqrt(m / kT); "
                    "not viscosity-matched");
  json_object_end(&j);
  json_object(&j, "axes");
  for (int a = 0; a < n_axes; a++) {
    char key[2] = {(char)('x' + axes[a]), 0};
    json_object(&j, key);
    json_bool(&j, "percolates", c->percolates[axes[a]]);
    json_int(&j, "rows", ar[a].rows);
    json_number(&j, "k_rc2", c->percolates[axes[a]] ? ar[a].k : 0.0);
    json_number(&j, "k_rc2_err", ar[a].k_err);
    json_number(&j, "k_m2", (c->percolates[axes[a]] ? ar[a].k : 0.0) * u->k_m2);
    json_number(&j, "k_nD", (c->percolates[axes[a]] ? ar[a].k : 0.0) * u->k_m2 * NANODARCY_PER_M2);
    json_number(&j, "k_nD_err", ar[a].k_err * u->k_m2 * NANODARCY_PER_M2);
    json_bool(&j, "k_defined", !c->percolates[axes[a]] || ar[a].defined);
    if (c->percolates[axes[a]] && !ar[a].defined)
      json_string(&j, "k_undefined_why",
                  ar[a].undefined_why[0] ? ar[a].undefined_why : "no Darcy range");
    json_int(&j, "runs_without_temperature", ar[a].n_no_temperature);
    json_int(&j, "runs_without_result", ar[a].n_missing);
    json_int(&j, "runs_target_missed_kept", ar[a].n_target_missed);
    json_number(&j, "k_rc2_all_rows", ar[a].k_all);
    json_number(&j, "k_rc2_all_rows_err", ar[a].k_all_err);
    json_array(&j, "left_out");
    for (int i = 0; i < ar[a].n_left_out; i++) {
      json_object(&j, NULL);
      json_number(&j, "G", ar[a].left_out_G[i]);
      json_string(&j, "run", ar[a].left_out_dir[i]);
      json_string(&j, "check", ar[a].left_out_check[i]);
      json_number(&j, "measured", ar[a].left_out_measured[i]);
      json_string(&j, "why", ar[a].left_out_why[i]);
      json_object_end(&j);
    }
    json_array_end(&j);
    if (ar[a].linear.rows >= 2) {
      json_object(&j, "darcy_range");
      json_int(&j, "rows", ar[a].linear.rows);
      json_bool(&j, "accepted", ar[a].linear.accepted);
      json_number(&j, "G_max", ar[a].linear.G_max);
      json_number(&j, "chi2_dof", ar[a].linear.chi2_dof);
      json_number(&j, "chi2_dof_max", 1.0 + 3.0 * sqrt(2.0 / (ar[a].linear.rows - 1)));
      /* a slope the rows reject is no permeability: null, as k_rc2 */
      const double k_range = ar[a].linear.accepted ? ar[a].linear.k : NAN;
      const double k_range_err = ar[a].linear.accepted ? ar[a].linear.k_err : NAN;
      json_number(&j, "k_rc2", k_range);
      json_number(&j, "k_rc2_err", k_range_err);
      json_number(&j, "k_m2", k_range * u->k_m2);
      json_number(&j, "k_nD", k_range * u->k_m2 * NANODARCY_PER_M2);
      json_string(&j, "rule",
                  "the most lowest-G rows (>= 3; 2 with 2 rows) that Darcy through the origin "
                  "fits with chi2/dof <= 1 + 3 sqrt(2 / dof)");
      json_object_end(&j);
    }
    json_string(&j, "chosen", ar[a].chosen[0] ? ar[a].chosen : "none");
    json_object(&j, "parameters");
    for (int p = 0; p < ar[a].n_par; p++) {
      json_object(&j, ar[a].par_name[p]);
      json_number(&j, "value", ar[a].par[p]);
      json_number(&j, "stderr", ar[a].par_err[p]);
      json_string(&j, "unit", ar[a].par_unit[p]);
      json_object_end(&j);
    }
    json_object_end(&j);
    json_object_end(&j);
  }
  json_object_end(&j);
  camp_rounds_json(&j, c); /* --target-error-k: the rounds, the steps and the error budget */
  json_end(&j);
  atomic_commit(f, tmp, path);
}

int camp_collect(const camp_opts *o, campaign *c, const char *workdir) {
  char why[CAMP_PATH + 256];
  for (int i = 0; i < c->n_runs; i++)
    if (!c->runs[i].have) camp_read_summary(&c->runs[i], why, sizeof why);
  if (camp_check_consistency(c)) return -1;
  camp_core_viscosity(c);
  camp_units u;
  camp_units_of(c, &u);
  if (c->rc_per_voxel_source[0])
    printf(
        "resolution: %g rc per voxel (%s); critical throat x %d y %d z %d voxels; %s regime%s%s\n",
        c->rc_per_voxel, c->rc_per_voxel_source, c->throat_voxels[0], c->throat_voxels[1],
        c->throat_voxels[2], c->regime[0] ? c->regime : "unknown",
        c->resolution_warning[0] ? "\nWARNING: " : "", c->resolution_warning);
  printf("units: rc = %.4g m (%s)\n", u.rc_m, c->length_source);
  if (c->energy_J > 0)
    printf("  energy unit %.4g J (the scene's units block); ", u.kT_J);
  else
    printf("  kT = kB x %.2f K; ", c->temperature_K);
  printf("particle mass m = %s = %.4g kg (%.3g water molecules); tau = rc sqrt(m/kT) = %.4g s\n",
         c->particle_mass_kg > 0 ? "the scene's units block" : "rho_water / n", u.mass_kg,
         u.n_molecules, u.tau_s);
  printf("  G: 1 = %.4g Pa/m; q: 1 = %.4g m/s; k: 1 rc^2 = %.4g m^2 = %.4g nD; mu = %g -> %.3g "
         "Pa s (real water 8.9e-4 Pa s: the dimensional mapping, not viscosity-matched; k needs "
         "only rc)\n",
         u.G_Pa_per_m, u.q_m_per_s, u.k_m2, u.k_m2 * NANODARCY_PER_M2, c->viscosity,
         c->viscosity * u.mu_Pa_s);
  int axes[3], n_axes = 0, rc = 0;
  for (int d = 0; d < 3; d++)
    for (int i = 0; i < c->n_runs; i++)
      if (c->runs[i].axis == d) {
        axes[n_axes++] = d;
        break;
      }
  axis_result ar[3];
  for (int a = 0; a < n_axes; a++)
    if (collect_axis(o, c, workdir, axes[a], &u, &ar[a])) rc = -1;
  int undefined = 0;
  double k_min = INFINITY, k_max = 0;
  for (int a = 0; a < n_axes; a++) {
    undefined |= c->percolates[axes[a]] && !ar[a].defined;
    if (ar[a].defined) k_min = fmin(k_min, ar[a].k), k_max = fmax(k_max, ar[a].k);
  }
  if (n_axes > 1 || (o && o->n_axes == 3)) {
    printf("\npermeability tensor diagonal (rc^2):");
    for (int a = 0; a < n_axes; a++)
      if (ar[a].defined)
        printf(" k_%c%c = %.5g +- %.2g", 'x' + axes[a], 'x' + axes[a], ar[a].k, ar[a].k_err);
      else
        printf(" k_%c%c not defined", 'x' + axes[a], 'x' + axes[a]);
    for (int d = 0; d < 3; d++)
      if (!c->percolates[d]) printf(" k_%c%c = 0 (no percolation)", 'x' + d, 'x' + d);
    printf("\n");
    if (!undefined && n_axes == 3 && k_min > 0)
      printf("anisotropy: k_max / k_min = %.3g (%.4g / %.4g rc^2)\n", k_max / k_min, k_max, k_min);
  }
  write_json(workdir, c, &u, axes, n_axes, ar);
  printf("wrote %s/permeability.json\n", workdir);
  if (!rc && undefined) {
    fprintf(stderr, "mdpore permeability: no Darcy range on some axis: k is not defined by these "
                    "runs (see the report)\n");
    return CAMP_EXIT_NO_DARCY_RANGE;
  }
  return rc;
}
