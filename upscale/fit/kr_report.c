/* JSON and text reports of the relative-permeability fits (see kr_report.h). */
#include "kr_report.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "common/atomic_file.h"
#include "common/json_out.h"

void kr_law_text(const kr_fit_result *r, char *buf, int len) {
  int n = snprintf(buf, len, "%s:", kr_law_name(r->kind));
  for (int p = 0; p < kr_law_nparams(r->kind) && n < len; p++) {
    const char *name = kr_law_param_name(r->kind, p);
    if (r->fixed[p])
      n += snprintf(buf + n, len - n, " %s = %.4g (fixed),", name, r->law.p[p]);
    else if (r->at_bound[p])
      n += snprintf(buf + n, len - n, " %s = %.4g (at its bound),", name, r->law.p[p]);
    else
      n += snprintf(buf + n, len - n, " %s = %.4g +- %.2g,", name, r->law.p[p], r->se_inflated[p]);
  }
  if (n < len)
    snprintf(buf + n, len - n, " chi2/dof = %.3g (%d points, %d dof)", r->chi2_dof, r->n_points,
             r->dof);
}

static const char *endpoint_rule(const kr_fit_opts *o) {
  if (isfinite(o->swc) && isfinite(o->sor)) return "swc and sor fixed (--swc, --sor)";
  if (isfinite(o->swc))
    return "swc fixed (--swc); sor fitted below 1 - the highest Sw where oil flows";
  if (isfinite(o->sor))
    return "sor fixed (--sor); swc fitted below the lowest Sw where water flows";
  return "swc and sor fitted, swc below the lowest Sw where water flows and sor below 1 - the "
         "highest Sw where oil flows (kr > 3 errors above 0): the table's end points are where "
         "the campaign stopped, not residual saturations";
}

static void json_check(json_out *j, const kr_judgement *g) {
  json_object(j, "check");
  json_bool(j, "judged", g->judged);
  json_bool(j, "accepted", g->accepted);
  for (int ph = 0; ph < 2; ph++) {
    const kr_phase_check *p = &g->phase[ph];
    char text[400];
    kr_phase_text(p, ph, text, sizeof text);
    json_object(j, ph ? "kro" : "krw");
    json_int(j, "points", p->n);
    json_number(j, "chi2", p->chi2);
    json_number(j, "dof", p->dof);
    json_number(j, "chi2_dof", p->chi2_dof);
    json_number(j, "chi2_dof_max", p->limit);
    json_number(j, "chi2_dof_monotone", p->chi2_dof_monotone);
    json_string(j, "verdict", kr_verdict_name(p->verdict));
    json_string(j, "text", text);
    json_object_end(j);
  }
  json_object_end(j);
}

static void json_fit(json_out *j, const kr_fit_result *r, const kr_judgement *g) {
  json_object(j, NULL);
  json_string(j, "law", kr_law_name(r->kind));
  json_bool(j, "ok", r->ok);
  json_bool(j, "converged", r->converged);
  json_bool(j, "accepted", g->accepted);
  if (r->why[0]) json_string(j, "why", r->why);
  json_check(j, g);
  if (r->ok) {
    json_int(j, "iterations", r->iterations);
    json_int(j, "starts", r->starts);
    json_number(j, "chi2", r->chi2);
    json_int(j, "dof", r->dof);
    json_number(j, "chi2_dof", r->chi2_dof);
    json_number(j, "error_inflation", r->inflation);
    json_number(j, "bic", r->bic);
    json_int(j, "n_points", r->n_points);
    json_int(j, "n_krw", r->n_krw);
    json_int(j, "n_kro", r->n_kro);
    json_int(j, "left_out_krw", r->left_out_krw);
    json_int(j, "left_out_kro", r->left_out_kro);
    json_object(j, "params");
    for (int p = 0; p < kr_law_nparams(r->kind); p++) {
      json_object(j, kr_law_param_name(r->kind, p));
      json_number(j, "value", r->law.p[p]);
      json_number(j, "se", r->se[p]);
      json_number(j, "se_inflated", r->se_inflated[p]);
      json_bool(j, "fixed", r->fixed[p]);
      json_bool(j, "at_bound", r->at_bound[p]);
      json_number(j, "lower", r->lower[p]);
      json_number(j, "upper", r->upper[p]);
      json_object_end(j);
    }
    json_object_end(j);
  }
  json_object_end(j);
}

static void json_curves(json_out *j, const kr_fit_result fits[KR_LAW_COUNT]) {
  double sw[KR_CURVE_POINTS], krw[KR_CURVE_POINTS], kro[KR_CURVE_POINTS];
  for (int i = 0; i < KR_CURVE_POINTS; i++) sw[i] = i / (KR_CURVE_POINTS - 1.0);
  json_object(j, "curves");
  json_numbers(j, "sw", sw, KR_CURVE_POINTS);
  for (int k = 0; k < KR_LAW_COUNT; k++) {
    if (!fits[k].ok) continue;
    for (int i = 0; i < KR_CURVE_POINTS; i++) kr_law_eval(&fits[k].law, sw[i], &krw[i], &kro[i]);
    json_object(j, kr_law_name(k));
    json_numbers(j, "krw", krw, KR_CURVE_POINTS);
    json_numbers(j, "kro", kro, KR_CURVE_POINTS);
    json_object_end(j);
  }
  json_object_end(j);
}

int kr_write_json(const char *path, const kr_table *t, const kr_fit_opts *o,
                  const kr_fit_result fits[KR_LAW_COUNT], const kr_choice *c,
                  const kr_outcome *outcome, const kr_swof *swof, const char *swof_path) {
  char tmp[4200];
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  json_out j;
  json_begin(&j, f);
  json_string(&j, "table", t->path);
  json_int(&j, "rows", t->n);
  json_number(&j, "rc_m", t->rc_m);
  json_number(&j, "temperature_K", t->temperature_K);
  json_number(&j, "M", t->M);
  json_string(&j, "endpoints", endpoint_rule(o));
  json_array(&j, "fits");
  for (int k = 0; k < KR_LAW_COUNT; k++)
    if (fits[k].ok || fits[k].why[0]) json_fit(&j, &fits[k], &outcome->judge[k]);
  json_array_end(&j);
  json_object(&j, "choice");
  if (outcome->law >= 0)
    json_string(&j, "law", kr_law_name(outcome->law));
  else
    json_null(&j, "law");
  json_bool(&j, "forced", outcome->forced);
  json_bool(&j, "refused", outcome->refused);
  json_string(&j, "outcome", outcome->text);
  if (c->chosen >= 0)
    json_string(&j, "test_law", kr_law_name(c->chosen));
  else
    json_null(&j, "test_law");
  json_bool(&j, "tested", c->tested);
  json_number(&j, "D", c->D);
  json_number(&j, "D_crit", c->D_crit);
  json_int(&j, "dof", c->dp);
  json_number(&j, "alpha", KR_SELECT_ALPHA);
  json_string(&j, "test", c->text);
  json_object_end(&j);
  json_object(&j, "data");
  json_numbers(&j, "sw", t->sw, t->n);
  json_numbers(&j, "krw", t->krw, t->n);
  json_numbers(&j, "krw_err", t->krw_err, t->n);
  json_numbers(&j, "kro", t->kro, t->n);
  json_numbers(&j, "kro_err", t->kro_err, t->n);
  json_object_end(&j);
  json_curves(&j, fits);
  if (swof) {
    json_object(&j, "swof");
    json_string(&j, "path", swof_path);
    json_int(&j, "rows", swof->n);
    json_string(&j, "points",
                swof->no_law     ? "measured_no_law"
                : swof->measured ? "measured"
                                 : "law");
    json_int(&j, "clipped_rows", swof->n_clipped);
    json_number(&j, "kr_peak_unclipped", swof->kr_peak);
    json_numbers(&j, "sw", swof->sw, swof->n);
    json_numbers(&j, "krw", swof->krw, swof->n);
    json_numbers(&j, "krow", swof->krow, swof->n);
    json_numbers(&j, "pcow", swof->pcow, swof->n);
    json_object_end(&j);
  }
  json_end(&j);
  return atomic_commit(f, tmp, path);
}

static void print_fit(FILE *out, const kr_fit_result *r, int chosen, int forced,
                      const kr_judgement *g) {
  fprintf(out, "%s%s", kr_law_name(r->kind),
          chosen ? (forced ? " (taken with --force: REFUSED by the check)" : " (chosen)")
          : g->judged && !g->accepted ? " (REFUSED)"
                                      : "");
  if (!r->ok) {
    fprintf(out, ": not fitted: %s\n", r->why);
    return;
  }
  fprintf(out,
          ": chi2 = %.4g, dof = %d, chi2/dof = %.3g, BIC = %.4g, %d points (%d krw, %d kro)%s%s\n",
          r->chi2, r->dof, r->chi2_dof, r->bic, r->n_points, r->n_krw, r->n_kro,
          r->converged ? "" : ", ", r->converged ? "" : r->why);
  for (int ph = 0; ph < 2 && g->judged; ph++) {
    char text[400];
    kr_phase_text(&g->phase[ph], ph, text, sizeof text);
    fprintf(out, "  check %s\n", text);
  }
  if (!g->accepted && !forced) {
    fprintf(out,
            "  (parameters not printed: the law is %s, so they are not a result; the JSON "
            "keeps them, flagged)\n",
            g->judged ? "refused by the check" : "not judged");
    return;
  }
  for (int p = 0; p < kr_law_nparams(r->kind); p++) {
    fprintf(out, "  %-8s %10.5g", kr_law_param_name(r->kind, p), r->law.p[p]);
    if (r->fixed[p])
      fprintf(out, "  (fixed)\n");
    else if (r->at_bound[p])
      fprintf(out, "  (at its bound [%g, %g]: the bound, not the data, sets it)\n", r->lower[p],
              r->upper[p]);
    else if (r->inflation > 1.0)
      fprintf(out, " +- %-9.3g (x%.3g for chi2/dof; stated errors: +- %.3g)\n", r->se_inflated[p],
              r->inflation, r->se[p]);
    else
      fprintf(out, " +- %.3g\n", r->se[p]);
  }
}

void kr_print(FILE *out, const kr_table *t, const kr_fit_opts *o,
              const kr_fit_result fits[KR_LAW_COUNT], const kr_choice *c,
              const kr_outcome *outcome) {
  fprintf(out, "%s: %d rows\n", t->path, t->n);
  const int lw = fits[KR_COREY].ok ? fits[KR_COREY].left_out_krw : fits[KR_LET].left_out_krw;
  const int lo = fits[KR_COREY].ok ? fits[KR_COREY].left_out_kro : fits[KR_LET].left_out_kro;
  if (lw || lo)
    fprintf(out, "left out (no error to weight them): %d krw and %d kro point(s)\n", lw, lo);
  fprintf(out, "end points: %s\n", endpoint_rule(o));
  for (int k = 0; k < KR_LAW_COUNT; k++)
    if (fits[k].ok || fits[k].why[0])
      print_fit(out, &fits[k], outcome->law == k, outcome->forced, &outcome->judge[k]);
  if (c->text[0]) fprintf(out, "choice: %s\n", c->text);
  if (outcome->text[0]) fprintf(out, "result: %s\n", outcome->text);
  if (outcome->law < 0 && !outcome->refused)
    fprintf(out, "result: NO LAW is a result of these data; a SWOF export (--swof) is the measured "
                 "points themselves\n");
}
