/* JSON and text reports of the fits (see fit_report.h). */
#include "fit_report.h"

#include <math.h>
#include <string.h>

#include "common/atomic_file.h"
#include "common/json_out.h"

void fit_param_unit(const flow_table *t, flow_law_kind kind, int i, char *buf, int len) {
  const char *L = t->si ? "m" : t->length_unit;
  const char *grad = t->si ? "Pa/m" : "reduced pressure/length";
  switch (kind) {
  case LAW_DARCY:
  case LAW_THRESHOLD:
  case LAW_FORCHHEIMER:
    if (i == 0)
      snprintf(buf, len, "%s^2", L);
    else if (kind == LAW_THRESHOLD)
      snprintf(buf, len, "%s", grad);
    else
      snprintf(buf, len, "1/%s", L);
    break;
  case LAW_POWER:
    if (i == 0)
      snprintf(buf, len, "%s / (%s)^n", t->si ? "m/s" : "reduced velocity", grad);
    else
      snprintf(buf, len, "1");
    break;
  default:
    snprintf(buf, len, "?");
  }
}

double fit_k_in_m2(const flow_table *t, double k) {
  if (t->si) return k;
  if (isfinite(t->length_unit_m)) return k * t->length_unit_m * t->length_unit_m;
  return NAN;
}

static const char *criterion_name(fit_criterion c) {
  return c == SELECT_AIC ? "aic" : "bic";
}

/* "beta = 0 (at its bound >= 0: the data do not support this term)" for a parameter at a bound. */
static void bound_text(const flow_table *t, const fit_result *r, int p, char *buf, int len) {
  char unit[96];
  fit_param_unit(t, r->kind, p, unit, sizeof unit);
  /* a bound where the law reduces to the nested simpler one (beta = 0, G0 = 0, n = 1): the term is
   * absent */
  const double nested_at = r->kind == LAW_POWER ? 1.0 : 0.0;
  const int vanishes = p == 1 && fit_nested_law(r->kind, NULL) >= 0 && r->bound[p] == nested_at;
  const double v = r->theta[p] + 0.0, b = r->bound[p] + 0.0; /* + 0.0: no "-0" */
  snprintf(buf, len, "%s = %.4g%s%s (at its bound %s %.4g%s%s: %s)", fit_param_name(r->kind, p), v,
           v != 0 ? " " : "", v != 0 ? unit : "", r->bound_upper[p] ? "<=" : ">=", b,
           b != 0 ? " " : "", b != 0 ? unit : "",
           vanishes ? "the data do not support this term"
                    : "the bound, not the data, sets its value");
}

/* Why the chosen law is the chosen one, for the text and JSON reports: the rule, the support test
 * of every law beyond Darcy, and the law an information criterion alone would have picked. */
static void chosen_text(const fit_result *r, int nr, int chosen, fit_criterion crit, char *buf,
                        int len) {
  const char *cn = crit == SELECT_AIC ? "AIC" : "BIC";
  int n = 0;
  buf[0] = 0;
  if (chosen < 0) {
    snprintf(buf, len, "no eligible fit converged");
    return;
  }
  if (fit_has_darcy(r, nr))
    n += snprintf(buf, len,
                  "lowest %s among darcy and the laws beyond it that pass the support test (extra "
                  "parameter >= %g sigma from its darcy value, the error scaled up by "
                  "sqrt(chi2/dof) when above 1; G0 > 0, beta > 0, |n-1| > %g)",
                  cn, FIT_SUPPORT_SIGMA, FIT_POWER_MIN_DEVIATION);
  else
    n += snprintf(buf, len,
                  "lowest %s among the %s laws; darcy was not fitted, so an unsupported law may "
                  "be chosen (add darcy to --models to test the laws against it)",
                  cn, r[chosen].supported ? "supported" : "eligible");
  for (int i = 0; i < nr && n < len; i++)
    if (r[i].ok && r[i].converged && fit_nested_law(r[i].kind, NULL) >= 0)
      n += snprintf(buf + n, len - n, "; %s %s: %s", flow_law_name(r[i].kind),
                    r[i].supported ? "supported" : "not supported", r[i].support);
  const int lowest = fit_lowest(r, nr, crit);
  if (lowest >= 0 && lowest != chosen && n < len)
    n += snprintf(buf + n, len - n, "; %s alone would have picked %s", cn,
                  flow_law_name(r[lowest].kind));
  const int np = flow_law_nparams(r[chosen].kind);
  if ((r[chosen].at_bound[0] || (np > 1 && r[chosen].at_bound[1])) && n < len)
    snprintf(buf + n, len - n,
             "; the chosen law has a parameter at its bound (no simpler nested law was fitted: "
             "add darcy to --models to compare)");
}

static void write_model(json_out *j, const flow_table *t, const fit_result *r) {
  char unit[96];
  int np = flow_law_nparams(r->kind);
  json_object(j, NULL);
  json_string(j, "law", flow_law_name(r->kind));
  json_bool(j, "ok", r->ok);
  json_bool(j, "converged", r->converged);
  if (!r->ok || !r->converged) json_string(j, "why", r->why);
  if (!r->ok) {
    json_object_end(j);
    return;
  }
  json_int(j, "iterations", r->iterations);
  json_bool(j, "eligible", r->eligible);
  if (!r->eligible && r->converged) json_string(j, "not_eligible_why", r->not_eligible);
  if (r->converged) {
    json_bool(j, "supported", r->supported);
    json_string(j, "support_test", r->support);
    if (fit_nested_law(r->kind, NULL) >= 0) json_number(j, "support_sigma", r->support_sigma);
  }
  json_object(j, "parameters");
  for (int i = 0; i < np; i++) {
    json_object(j, fit_param_name(r->kind, i));
    json_number(j, "value", r->theta[i]);
    json_number(j, "stderr", r->se[i]);
    fit_param_unit(t, r->kind, i, unit, sizeof unit);
    json_string(j, "unit", unit);
    json_bool(j, "at_bound", r->at_bound[i]);
    if (r->at_bound[i]) {
      json_number(j, "bound", r->bound[i]);
      json_string(j, "bound_side", r->bound_upper[i] ? "upper" : "lower");
    }
    json_object_end(j);
  }
  json_object_end(j);
  json_array(j, "covariance");
  for (int a = 0; a < np; a++) json_numbers(j, NULL, r->cov[a], np);
  json_array_end(j);
  if (r->kind != LAW_POWER) {
    double m2 = fit_k_in_m2(t, r->theta[0]), se = fit_k_in_m2(t, r->se[0]);
    json_object(j, "permeability_physical");
    json_number(j, "m2", m2);
    json_number(j, "m2_stderr", se);
    json_number(j, "mD", m2 * MD_PER_M2);
    json_number(j, "mD_stderr", se * MD_PER_M2);
    json_number(j, "nD", m2 * MD_PER_M2 * 1e6);
    json_number(j, "nD_stderr", se * MD_PER_M2 * 1e6);
    json_object_end(j);
  }
  if (r->kind == LAW_POWER) json_number(j, "g_ref", r->model.g_ref);
  json_number(j, "chi2", r->chi2);
  json_int(j, "dof", r->dof);
  json_number(j, "chi2_dof", r->chi2_dof);
  json_number(j, "aic", r->aic);
  json_number(j, "bic", r->bic);
  json_number(j, "bic_weight", r->weight);
  /* a sampled curve so that plotting needs no copy of the law formulas */
  double gmax = 0, cg[FIT_CURVE_POINTS], cq[FIT_CURVE_POINTS];
  for (int i = 0; i < t->n; i++) gmax = fmax(gmax, fabs(t->G[i]));
  fluid_props fl = {t->viscosity, t->density};
  for (int i = 0; i < FIT_CURVE_POINTS; i++) { /* the same samples fit_law checked to be finite */
    cg[i] = 1.1 * gmax * i / (FIT_CURVE_POINTS - 1.0);
    cq[i] = flow_law_q_exact(&r->law, &fl, cg[i]);
  }
  json_object(j, "curve");
  json_numbers(j, "G", cg, FIT_CURVE_POINTS);
  json_numbers(j, "q", cq, FIT_CURVE_POINTS);
  json_object_end(j);
  double res[t->n];
  for (int i = 0; i < t->n; i++)
    res[i] = (t->q[i] - flow_law_q_exact(&r->law, &fl, t->G[i])) / t->sigma[i];
  json_numbers(j, "normalised_residuals", res, t->n);
  json_object_end(j);
}

int fit_write_json(const char *path, const flow_table *t, const fit_result *r, int nr, int chosen,
                   fit_criterion crit) {
  char tmp[4200];
  FILE *fp = atomic_open(path, tmp, sizeof tmp);
  if (!fp) return -1;
  json_out j;
  json_begin(&j, fp);
  json_string(&j, "format", "mdpore-fit");
  json_int(&j, "version", 1);
  json_string(&j, "table", t->path);
  json_string(&j, "sample", t->sample);
  json_string(&j, "axis", t->axis);
  json_string(&j, "unit_system", t->si ? "SI" : "reduced");
  json_string(&j, "length_unit", t->length_unit);
  json_number(&j, "length_unit_m", t->length_unit_m);
  json_number(&j, "voxel_size", t->voxel_size);
  json_number(&j, "viscosity", t->viscosity);
  json_number(&j, "density", t->density);
  json_string(&j, "driving_column", t->driving_column);
  json_string(
      &j, "convention",
      "G = -dp/dx (or body force per volume); q = superficial Darcy velocity Q/A with A the "
      "whole cross-section (solid included); k = mu q / G; standard errors from the table's "
      "stated errors (covariance not rescaled by chi2/dof)");
  json_string(&j, "criterion", criterion_name(crit));
  json_object(&j, "support_rule");
  json_number(&j, "level_sigma", FIT_SUPPORT_SIGMA);
  json_number(&j, "power_min_deviation", FIT_POWER_MIN_DEVIATION);
  json_string(&j, "statistic",
              "z = (p - p_darcy) / (stderr * sqrt(max(1, chi2/dof))) for the extra parameter p "
              "(G0, beta, n); a law beyond darcy is supported if p is not at a bound, G0 > 0, "
              "beta > 0, |z| >= level_sigma and |n-1| > power_min_deviation");
  json_object_end(&j);
  if (chosen >= 0)
    json_string(&j, "chosen", flow_law_name(r[chosen].kind));
  else
    json_null(&j, "chosen");
  char why[2048];
  chosen_text(r, nr, chosen, crit, why, sizeof why);
  json_string(&j, "chosen_why", why);
  json_object(&j, "data");
  json_numbers(&j, "G", t->G, t->n);
  json_numbers(&j, "q", t->q, t->n);
  json_numbers(&j, "sigma", t->sigma, t->n);
  json_numbers(&j, "run_length", t->run_length, t->n);
  json_object_end(&j);
  json_array(&j, "models");
  for (int i = 0; i < nr; i++) write_model(&j, t, &r[i]);
  json_array_end(&j);
  json_end(&j);
  return atomic_commit(fp, tmp, path);
}

void fit_print_table(FILE *out, const flow_table *t, const fit_result *r, int nr, int chosen,
                     fit_criterion crit) {
  char unit[96], text[2048];
  fprintf(out, "mdpore fit: %s  (sample '%s', axis %s, %s units, %d points, mu = %g, rho = %g)\n",
          t->path, t->sample, t->axis, t->si ? "SI" : "reduced", t->n, t->viscosity, t->density);
  fprintf(out, "%-12s %-58s %9s %10s %10s %7s\n", "law", "parameters (value +- standard error)",
          "chi2/dof", "AIC", "BIC", "weight");
  for (int i = 0; i < nr; i++) {
    if (!r[i].ok) {
      fprintf(out, "%-12s not fitted: %s\n", flow_law_name(r[i].kind), r[i].why);
      continue;
    }
    char params[256] = "";
    int np = flow_law_nparams(r[i].kind), len = 0;
    for (int p = 0; p < np && len < (int)sizeof params; p++) {
      fit_param_unit(t, r[i].kind, p, unit, sizeof unit);
      if (r[i].at_bound[p]) /* no "+- error": at a bound it is not a confidence interval */
        len += snprintf(params + len, sizeof params - len, "%s%s = %.4g [at bound]", p ? "; " : "",
                        fit_param_name(r[i].kind, p), r[i].theta[p] + 0.0);
      else
        len += snprintf(params + len, sizeof params - len, "%s%s = %.4g +- %.2g %s", p ? "; " : "",
                        fit_param_name(r[i].kind, p), r[i].theta[p] + 0.0, r[i].se[p], unit);
    }
    const char *mark = !r[i].converged   ? "  (not converged)"
                       : !r[i].supported ? "  (not supported)"
                       : !r[i].eligible  ? "  (not eligible)"
                                         : "";
    fprintf(out, "%-12s %-58s %9.3g %10.4g %10.4g %7.3f%s%s\n", flow_law_name(r[i].kind), params,
            r[i].chi2_dof, r[i].aic, r[i].bic, r[i].weight, i == chosen ? "  <- chosen" : "", mark);
    for (int p = 0; p < np; p++)
      if (r[i].at_bound[p]) {
        bound_text(t, &r[i], p, text, sizeof text);
        fprintf(out, "%-12s   %s\n", "", text);
      }
    if (r[i].converged && !r[i].eligible)
      fprintf(out, "%-12s   not eligible: %s\n", "", r[i].not_eligible);
    else if (r[i].converged && fit_nested_law(r[i].kind, NULL) >= 0)
      fprintf(out, "%-12s   %s: %s\n", "", r[i].supported ? "supported" : "not supported",
              r[i].support);
    double m2 = r[i].kind != LAW_POWER ? fit_k_in_m2(t, r[i].theta[0]) : NAN;
    double se_nd = fit_k_in_m2(t, r[i].se[0]) * MD_PER_M2 * 1e6;
    if (isfinite(m2) && isfinite(m2 * MD_PER_M2 * 1e6) && isfinite(se_nd)) {
      fprintf(out, "%-12s   k = %.4g m^2 = %.4g mD = %.4g nD", "", m2, m2 * MD_PER_M2,
              m2 * MD_PER_M2 * 1e6);
      if (r[i].at_bound[0])
        fprintf(out, " (at its bound)\n");
      else
        fprintf(out, " (+- %.2g nD)\n", se_nd);
    }
  }
  fprintf(out, "chosen by %s: %s", crit == SELECT_AIC ? "AIC" : "BIC",
          chosen >= 0 ? flow_law_name(r[chosen].kind) : "none (no eligible fit converged)");
  chosen_text(r, nr, chosen, crit, text, sizeof text);
  if (chosen >= 0) fprintf(out, "\n  why: %s", text);
  fprintf(out,
          "\nnote: a threshold or Forchheimer term fitted at strong pore-scale forcing may be a "
          "forcing artefact (physics.md section 4).\n");
}
