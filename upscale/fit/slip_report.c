/* Text, CSV and JSON reports of a slip fit (see slip_report.h). */
#include "slip_report.h"

#include <math.h>
#include <string.h>

#include "common/atomic_file.h"
#include "common/json_out.h"

double slip_rc_m(const slip_point *p, int n, double rc_m_option) {
  if (isfinite(rc_m_option)) return rc_m_option;
  double rc = NAN;
  for (int i = 0; i < n; i++) {
    if (!isfinite(p[i].rc_m)) continue;
    if (isfinite(rc) && fabs(p[i].rc_m - rc) > 1e-9 * rc) return NAN; /* inputs disagree */
    rc = p[i].rc_m;
  }
  return rc;
}

typedef struct {
  double k0, ratio, ratio_err, model, model_err, resid;
} trend_row;

static trend_row trend(const slip_point *q, const slip_setup *s, const slip_result *r) {
  trend_row t;
  t.k0 = slip_k_noslip(s->shape, q->h, q->porosity);
  t.ratio = q->k / t.k0;
  t.ratio_err = q->k_err / t.k0;
  t.model = slip_model_ratio(s, r, q->h, &t.model_err);
  t.resid = (t.ratio - t.model) / t.ratio_err;
  return t;
}

static const char *form_text(const slip_setup *s) {
  if (s->model == SLIP_NAVIER)
    return s->shape == SLIP_SLIT ? "k = a phi h^2/12 (1 + 6 b/h)" : "k = a phi R^2/8 (1 + 4 b/R)";
  return s->shape == SLIP_SLIT ? "k = a phi h^2/12 (1 + 2 b/h)^3" : "k = a phi R^2/8 (1 + b/R)^4";
}

void slip_print(FILE *out, const slip_point *p, int n, const slip_setup *s, const slip_result *r,
                double rc_m) {
  fprintf(out, "mdpore slip: %s, %s model: %s%s\n", slip_shape_names[s->shape],
          slip_model_names[s->model], form_text(s), s->free_scale ? " (a fitted)" : ", a = 1");
  fprintf(out, "  %-10s %-12s %-12s %-8s %-12s %-16s %-16s %s\n", s->shape == SLIP_TUBE ? "R" : "h",
          "k", "k_err", "phi", "k_noslip", "k/k_noslip", "model", "(k-model)/err");
  for (int i = 0; i < n; i++) {
    const trend_row t = trend(&p[i], s, r);
    fprintf(out,
            "  %-10.4g %-12.5g %-12.3g %-8.4g %-12.5g %-7.4f +- %-6.4f %-7.4f +- %-6.4f %+.2f\n",
            p[i].h, p[i].k, p[i].k_err, p[i].porosity, t.k0, t.ratio, t.ratio_err, t.model,
            t.model_err, t.resid);
  }
  fprintf(out, "  b = %.4f +- %.4f rc", r->b, r->b_err);
  if (r->b_err_scaled > r->b_err)
    fprintf(out, " (+- %.4f scaled by sqrt(chi2/dof))", r->b_err_scaled);
  if (isfinite(rc_m)) fprintf(out, "  = %.4g +- %.3g m", r->b * rc_m, r->b_err * rc_m);
  fprintf(out, "\n");
  if (s->free_scale)
    fprintf(out, "  a = %.4f +- %.4f (correlation with b %.2f)\n", r->a, r->a_err,
            r->cov_ab / (r->a_err * r->b_err));
  if (r->dof > 0)
    fprintf(out, "  chi2 = %.4g, dof = %d, chi2/dof = %.4g\n", r->chi2, r->dof, r->chi2_dof);
  else
    fprintf(out,
            "  chi2/dof undefined: %d point(s) for %d parameter(s), b is solved, not fitted; its "
            "error is the input error propagated\n",
            r->n, r->npar);
}

int slip_write_csv(const char *path, const slip_point *p, int n, const slip_setup *s,
                   const slip_result *r) {
  char tmp[4200];
  FILE *fp = atomic_open(path, tmp, sizeof tmp);
  if (!fp) return -1;
  fprintf(fp, "# mdpore slip: %s, %s model: %s; b = %.17g +- %.17g, a = %.17g +- %.17g\n",
          slip_shape_names[s->shape], slip_model_names[s->model], form_text(s), r->b, r->b_err,
          r->a, r->a_err);
  fprintf(fp, "shape,h,k,k_err,porosity,k_noslip,k_over_k_noslip,k_over_k_noslip_err,model,"
              "model_err,normalised_residual,source\n");
  for (int i = 0; i < n; i++) {
    const trend_row t = trend(&p[i], s, r);
    fprintf(fp, "%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,\"%s\"\n",
            slip_shape_names[s->shape], p[i].h, p[i].k, p[i].k_err, p[i].porosity, t.k0, t.ratio,
            t.ratio_err, t.model, t.model_err, t.resid, p[i].source);
  }
  return atomic_commit(fp, tmp, path);
}

int slip_write_json(const char *path, const slip_point *p, int n, const slip_setup *s,
                    const slip_result *r, double rc_m) {
  char tmp[4200];
  FILE *fp = atomic_open(path, tmp, sizeof tmp);
  if (!fp) return -1;
  json_out j;
  json_begin(&j, fp);
  json_string(&j, "format", "mdpore-slip");
  json_int(&j, "version", 1);
  json_string(&j, "shape", slip_shape_names[s->shape]);
  json_string(&j, "size", slip_size_meaning(s->shape));
  json_string(&j, "model", slip_model_names[s->model]);
  json_string(&j, "form", form_text(s));
  json_bool(&j, "free_scale", s->free_scale);
  json_object(&j, "fit");
  json_int(&j, "points", r->n);
  json_int(&j, "parameters", r->npar);
  json_int(&j, "dof", r->dof);
  json_number(&j, "b", r->b);
  json_number(&j, "b_err", r->b_err);
  json_number(&j, "b_err_scaled", r->b_err_scaled);
  json_number(&j, "a", r->a);
  json_number(&j, "a_err", r->a_err);
  json_number(&j, "cov_ab", r->cov_ab);
  json_number(&j, "chi2", r->chi2); /* null when dof = 0 */
  json_number(&j, "chi2_dof", r->chi2_dof);
  json_string(&j, "chi2_note",
              r->dof > 0 ? "chi2 of k against the model, weights 1 / k_err^2"
                         : "undefined: as many points as parameters (b solved from the point)");
  json_number(&j, "rc_m", rc_m);
  json_number(&j, "b_m", r->b * rc_m);
  json_number(&j, "b_err_m", r->b_err * rc_m);
  json_object_end(&j);
  json_array(&j, "points");
  double hmin = INFINITY, hmax = 0;
  for (int i = 0; i < n; i++) {
    const trend_row t = trend(&p[i], s, r);
    json_object(&j, NULL);
    json_number(&j, "h", p[i].h);
    json_number(&j, "k", p[i].k);
    json_number(&j, "k_err", p[i].k_err);
    json_number(&j, "porosity", p[i].porosity);
    json_number(&j, "k_noslip", t.k0);
    json_number(&j, "ratio", t.ratio);
    json_number(&j, "ratio_err", t.ratio_err);
    json_number(&j, "model", t.model);
    json_number(&j, "model_err", t.model_err);
    json_number(&j, "normalised_residual", t.resid);
    json_string(&j, "source", p[i].source);
    json_object_end(&j);
    hmin = fmin(hmin, p[i].h);
    hmax = fmax(hmax, p[i].h);
  }
  json_array_end(&j);
  /* The model's ratio from below the smallest size to twice the largest, for the plot. */
  enum { NC = 60 };
  double ch[NC], cr[NC], ce[NC];
  /* (b < 0: above the size where the flowing width closes, b / b_min(1) = -b m) */
  const double lo = fmax(0.5 * hmin, 1.05 * fmax(0.0, r->b / slip_b_min(s->shape, s->model, 1.0)));
  const double hi = 2.0 * hmax;
  for (int i = 0; i < NC; i++) {
    ch[i] = lo * pow(hi / lo, i / (double)(NC - 1));
    cr[i] = slip_model_ratio(s, r, ch[i], &ce[i]);
  }
  json_object(&j, "curve");
  json_numbers(&j, "h", ch, NC);
  json_numbers(&j, "model", cr, NC);
  json_numbers(&j, "model_err", ce, NC);
  json_object_end(&j);
  json_end(&j);
  return atomic_commit(fp, tmp, path);
}
