/* A block's flow law for the loop, from its campaign's `mdpore fit` JSON: the Darcy fit (k and its
 * error), the chosen law, the covariance of the parameters of the law the loop uses (for the
 * Monte-Carlo errors of couple_solve.c) and the range of gradients the table covered. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "common/yaml_tree.h"
#include "couple.h"
#include "darcy/fit_json_law.h"

/* Parameter names of each law in the fit JSON, in covariance order (fit/fit_model.c). */
static const char *const par_names[LAW_COUNT][2] = {
    {"k", NULL}, {"k", "G0"}, {"k", "beta"}, {"K", "n"}};

static double *par_slot(flow_law *law, int p) {
  if (p == 0) return law->kind == LAW_POWER ? &law->K : &law->k;
  return law->kind == LAW_THRESHOLD     ? &law->g0
         : law->kind == LAW_FORCHHEIMER ? &law->beta
                                        : &law->n;
}

/* models[i] of the law named `want`: parameter values, covariance, Darcy k error. */
static int read_model(ytree_t *t, const char *want, couple_law *L) {
  yaml_node_t *models = yt_get(t, yt_root(t), "models");
  if (!models) return yt_error(t, yt_root(t), "models", "expected the list of fitted models");
  for (int i = 0; i < yt_seq_size(models); i++) {
    yaml_node_t *m = yt_seq_item(t, models, i), *n;
    char name[32] = "";
    if (!(n = yt_get(t, m, "law")) || yt_string(t, n, "models[].law", name, sizeof name)) continue;
    if (strcmp(name, want)) continue;
    int kind = flow_law_from_name(want);
    yaml_node_t *pars = yt_get(t, m, "parameters");
    if (!pars) return yt_error(t, m, "models[].parameters", "expected the fitted parameters");
    L->n_par = flow_law_nparams(kind);
    memset(L->cov, 0, sizeof L->cov);
    for (int p = 0; p < L->n_par; p++) {
      yaml_node_t *pn = yt_get(t, pars, par_names[kind][p]), *se;
      double err = 0;
      if (!pn || !(se = yt_get(t, pn, "stderr")) || yt_is_null(se) ||
          yt_double(t, se, "models[].parameters.stderr", &err) || !isfinite(err))
        err = 0;
      L->cov[p][p] = err * err;
    }
    yaml_node_t *cov = yt_get(t, m, "covariance");
    if (cov && yt_seq_size(cov) == L->n_par)
      for (int a = 0; a < L->n_par; a++) {
        yaml_node_t *row = yt_seq_item(t, cov, a);
        if (yt_seq_size(row) != L->n_par) break;
        for (int b = 0; b < L->n_par; b++) {
          double v;
          if (!yt_double(t, yt_seq_item(t, row, b), "models[].covariance", &v) && isfinite(v))
            L->cov[a][b] = v;
        }
      }
    return 0;
  }
  return yt_error(t, models, "models", "expected a fitted '%s' model", want);
}

/* The law of the fit JSON at path into L (the fields of the fit; the rest of L is kept). */
static int read_law(const couple_config *c, const char *path, couple_law *L) {
  int si = 0;
  fluid_props fl;
  flow_law darcy;
  if (fit_json_law(path, "darcy", &darcy, &si, &fl, 0)) return -1;
  if (si) {
    fprintf(stderr, "mdpore couple: %s: expected a fit in reduced units (the campaigns' own)\n",
            path);
    return -1;
  }
  L->mu = fl.mu;
  L->density = fl.rho;
  L->k_darcy = darcy.k;
  if (fit_json_law(path, "chosen", &L->chosen, &si, &fl, 1)) L->chosen = darcy;
  snprintf(L->chosen_name, sizeof L->chosen_name, "%s", flow_law_name(L->chosen.kind));
  L->law = c->law_choice == COUPLE_LAW_CHOSEN ? L->chosen : darcy;
  for (int p = 0; p < flow_law_nparams(L->law.kind); p++) L->par[p] = *par_slot(&L->law, p);

  ytree_t t;
  if (yt_load(&t, path, 0)) return -1;
  int rc = -1;
  couple_law darcy_err = *L;
  if (read_model(&t, "darcy", &darcy_err)) goto out;
  L->k_darcy_err = sqrt(darcy_err.cov[0][0]);
  if (read_model(&t, flow_law_name(L->law.kind), L)) goto out;
  yaml_node_t *data = yt_get(&t, yt_root(&t), "data"), *G = data ? yt_get(&t, data, "G") : NULL;
  if (!G || yt_seq_size(G) < 1) {
    yt_error(&t, data ? data : yt_root(&t), "data.G", "expected the table's gradients");
    goto out;
  }
  L->n_rows = yt_seq_size(G);
  L->g_min = INFINITY;
  L->g_max = 0;
  for (int i = 0; i < L->n_rows; i++) {
    double g;
    if (yt_double(&t, yt_seq_item(&t, G, i), "data.G", &g)) goto out;
    L->g_min = fmin(L->g_min, fabs(g));
    L->g_max = fmax(L->g_max, fabs(g));
  }
  rc = 0;
out:
  yt_free(&t);
  return rc;
}

int couple_read_law(const couple_config *c, couple_block *b) {
  char path[COUPLE_PATH + 32];
  snprintf(path, sizeof path, "%.4000s/fit_%c.json", b->workdir, 'x' + c->axis);
  b->law.percolates = b->percolates;
  return b->percolates ? read_law(c, path, &b->law) : 0;
}

int couple_read_cross_law(const couple_config *c, couple_block *b, int a) {
  char dir[COUPLE_PATH + 8], path[COUPLE_PATH + 48];
  couple_campaign_dir(c, b, a, dir, sizeof dir);
  snprintf(path, sizeof path, "%.4000s/fit_%c.json", dir, 'x' + a);
  memset(&b->cross[a], 0, sizeof b->cross[a]);
  b->cross[a].percolates = 1;
  if (read_law(c, path, &b->cross[a])) return -1;
  b->cross_state[a] = CROSS_MEASURED;
  return 0;
}

void couple_law_sample(const couple_law *L, const double z[3], flow_law *out) {
  *out = L->law;
  /* Cholesky factor of the covariance (n <= 3): par + chol(cov) z is normal with that covariance */
  double l[3][3] = {{0}};
  for (int i = 0; i < L->n_par; i++)
    for (int j = 0; j <= i; j++) {
      double s = L->cov[i][j];
      for (int k = 0; k < j; k++) s -= l[i][k] * l[j][k];
      if (i == j)
        l[i][i] = s > 0 ? sqrt(s) : 0;
      else
        l[i][j] = l[j][j] > 0 ? s / l[j][j] : 0;
    }
  for (int i = 0; i < L->n_par; i++) {
    double v = L->par[i];
    for (int j = 0; j <= i; j++) v += l[i][j] * z[j];
    *par_slot(out, i) = v;
  }
  /* keep the draw a valid law: positive k/K, non-negative G0/beta, positive n */
  char why[128];
  for (int i = 0; i < L->n_par; i++) {
    double *p = par_slot(out, i);
    if (i == 0 && *p <= 0) *p = L->par[0] * 1e-3;
    if (i == 1 && *p < 0) *p = out->kind == LAW_POWER ? L->par[1] : 0;
  }
  if (flow_law_check(out, why, sizeof why)) *out = L->law;
}
