/* Fitted law from `mdpore fit` JSON (see fit_json_law.h). */
#include "fit_json_law.h"

#include <string.h>

#include "common/yaml_doc.h"

int fit_json_law(const char *path, const char *model, flow_law *law, int *si,
                 fluid_props *fit_fluid, char *err, int errlen) {
  ydoc y;
  yaml_node_t *root = ydoc_load(&y, path, err, errlen);
  if (!root) return -1;
  int rc = -1;
  const char *fmt = ydoc_string(&y, root, "format");
  const char *units = fmt ? ydoc_string(&y, root, "unit_system") : NULL;
  yaml_node_t *models = ydoc_get(&y, root, "models");
  if (fmt && strcmp(fmt, "mdpore-fit"))
    ydoc_fail(&y, root, "'format' is '%s', not 'mdpore-fit'", fmt);
  if (y.failed) goto done;
  *si = !strcmp(units, "SI");
  if (ydoc_number(&y, root, "viscosity", &fit_fluid->mu) ||
      ydoc_number(&y, root, "density", &fit_fluid->rho))
    goto done;
  const char *want = model;
  if (!strcmp(model, "chosen")) {
    yaml_node_t *c = ydoc_get(&y, root, "chosen");
    want = (c && c->type == YAML_SCALAR_NODE) ? (const char *)c->data.scalar.value : NULL;
    if (!want || !strcmp(want, "null")) {
      ydoc_fail(&y, c ? c : root, "no chosen model (no fit converged)");
      goto done;
    }
  }
  int kind = flow_law_from_name(want);
  if (kind < 0) {
    ydoc_fail(&y, root,
              "model '%s' is not a law (expected chosen, darcy, threshold, forchheimer or power)",
              want);
    goto done;
  }
  if (!ydoc_is_seq(models)) {
    ydoc_fail(&y, root, "missing list 'models'");
    goto done;
  }
  for (int i = 0; i < ydoc_seq_len(models); i++) {
    yaml_node_t *m = ydoc_seq_item(&y, models, i);
    const char *name = ydoc_string(&y, m, "law");
    if (!name) goto done;
    if (strcmp(name, want)) continue;
    yaml_node_t *conv = ydoc_get(&y, m, "converged");
    if (!conv || conv->type != YAML_SCALAR_NODE ||
        strcmp((char *)conv->data.scalar.value, "true")) {
      ydoc_fail(&y, m, "the %s fit did not converge; it cannot be used", want);
      goto done;
    }
    yaml_node_t *pars = ydoc_get(&y, m, "parameters");
    memset(law, 0, sizeof *law);
    law->kind = kind;
    static const char *pn[LAW_COUNT][2] = {{"k", NULL}, {"k", "G0"}, {"k", "beta"}, {"K", "n"}};
    for (int p = 0; p < 2 && pn[kind][p]; p++) {
      double v;
      yaml_node_t *pnode = ydoc_get(&y, pars, pn[kind][p]);
      if (!pnode) {
        ydoc_fail(&y, m, "model '%s' has no parameter '%s'", want, pn[kind][p]);
        goto done;
      }
      if (ydoc_number(&y, pnode, "value", &v)) goto done;
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
    rc = 0;
    goto done;
  }
  ydoc_fail(&y, models, "no model '%s' in the list", want);
done:
  ydoc_free(&y);
  return rc;
}
