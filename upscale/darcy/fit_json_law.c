/* Fitted law from `mdpore fit` JSON (see fit_json_law.h and fit/fit_report.c for the layout). */
#include "fit_json_law.h"

#include <stdio.h>
#include <string.h>

#include "common/yaml_tree.h"

static const char *const format_words[] = {"mdpore-fit", NULL};
static const char *const unit_words[] = {"reduced", "SI", NULL}; /* index = si */

/* The parameters of models[i] named by the law kind, into law. */
static int read_parameters(ytree_t *t, yaml_node_t *m, const char *mpath, int kind, flow_law *law) {
  static const char *pn[LAW_COUNT][2] = {{"k", NULL}, {"k", "G0"}, {"k", "beta"}, {"K", "n"}};
  char path[256];
  snprintf(path, sizeof path, "%s.parameters", mpath);
  yaml_node_t *pars = yt_need(t, m, "parameters", path, "a mapping of fitted parameters");
  if (!pars || yt_expect_map(t, pars, path)) return -1;
  memset(law, 0, sizeof *law);
  law->kind = kind;
  for (int p = 0; p < 2 && pn[kind][p]; p++) {
    char ppath[320], vpath[340];
    snprintf(ppath, sizeof ppath, "%s.%s", path, pn[kind][p]);
    snprintf(vpath, sizeof vpath, "%s.value", ppath);
    yaml_node_t *pnode = yt_need(t, pars, pn[kind][p], ppath, "the fitted parameter");
    yaml_node_t *vnode = pnode ? yt_need(t, pnode, "value", vpath, "a number") : NULL;
    double v;
    if (!vnode || yt_double(t, vnode, vpath, &v)) return -1;
    if (p == 0 && kind == LAW_POWER)
      law->K = v;
    else if (p == 0)
      law->k = v;
    else if (kind == LAW_THRESHOLD)
      law->g0 = v;
    else if (kind == LAW_FORCHHEIMER)
      law->beta = v;
    else
      law->n = v;
  }
  return 0;
}

static int read_fit(ytree_t *t, const char *model, flow_law *law, int *si, fluid_props *fit_fluid) {
  yaml_node_t *root = yt_root(t), *n;
  if (yt_expect_map(t, root, "")) return -1;
  if (!(n = yt_need(t, root, "format", "format", "mdpore-fit")) ||
      yt_enum(t, n, "format", format_words) < 0)
    return -1;
  if (!(n = yt_need(t, root, "unit_system", "unit_system", "SI or reduced")) ||
      (*si = yt_enum(t, n, "unit_system", unit_words)) < 0)
    return -1;
  if (!(n = yt_need(t, root, "viscosity", "viscosity", "a number")) ||
      yt_double(t, n, "viscosity", &fit_fluid->mu))
    return -1;
  if (!(n = yt_need(t, root, "density", "density", "a number")) ||
      yt_double(t, n, "density", &fit_fluid->rho))
    return -1;
  int kind;
  if (!strcmp(model, "chosen")) {
    if (!(n = yt_need(t, root, "chosen", "chosen", "the name of the chosen law"))) return -1;
    if (yt_is_null(n))
      return yt_error(t, n, "chosen",
                      "expected the name of the chosen law (got null: no fit converged)");
    if ((kind = yt_enum(t, n, "chosen", flow_law_names)) < 0) return -1;
  } else if ((kind = flow_law_from_name(model)) < 0) {
    return yt_error(t, root, "",
                    "model '%s' is not a law (expected chosen, darcy, threshold, "
                    "forchheimer or power)",
                    model);
  }
  const char *want = flow_law_names[kind];
  yaml_node_t *models = yt_need(t, root, "models", "models", "a list of fitted models");
  if (!models || yt_expect_seq(t, models, "models")) return -1;
  for (int i = 0; i < yt_seq_size(models); i++) {
    yaml_node_t *m = yt_seq_item(t, models, i);
    char mpath[64], sub[96], name[32];
    snprintf(mpath, sizeof mpath, "models[%d]", i);
    if (yt_expect_map(t, m, mpath)) return -1;
    snprintf(sub, sizeof sub, "%s.law", mpath);
    if (!(n = yt_need(t, m, "law", sub, "a law name")) || yt_string(t, n, sub, name, sizeof name))
      return -1;
    if (strcmp(name, want)) continue;
    int converged;
    snprintf(sub, sizeof sub, "%s.converged", mpath);
    if (!(n = yt_need(t, m, "converged", sub, "true or false")) || yt_bool(t, n, sub, &converged))
      return -1;
    if (!converged)
      return yt_error(t, n, sub, "expected a converged %s fit (got false: it cannot be used)",
                      want);
    return read_parameters(t, m, mpath, kind, law);
  }
  return yt_error(t, models, "models", "expected a model with law '%s' (got none)", want);
}

int fit_json_law(const char *path, const char *model, flow_law *law, int *si,
                 fluid_props *fit_fluid, int quiet) {
  ytree_t t;
  if (yt_load(&t, path, quiet)) return -1;
  const int rc = read_fit(&t, model, law, si, fit_fluid);
  yt_free(&t);
  return rc;
}
