/* The two liquids of `mdpore relperm` (docs/relperm.md section 3; docs/twophase.md sections 1, 4):
 * water and oil of one mDPD liquid (A = -40, B = 25, rd = 0.75 for every pair), immiscible through
 * the cross attraction A_wo = -20; the wetting liquid's wall attraction -40 (the campaign water's),
 * the other's -20; the oil's viscosity through its thermostat (gamma, and the exponent s of the
 * weight w_R = (1 - r/rc)^s), the cross pair's the means of the two like pairs', each liquid-wall
 * pair its liquid's like pair's. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "common/yaml_tree.h"
#include "relperm.h"

int rp_liquids_of(int ratio, rp_liquids *l) {
  /* M measured by reverse Poiseuille (docs/twophase.md section 4, the table of gamma and s) */
  switch (ratio) {
  case 1:
    *l = (rp_liquids){.M = 1.0, .M_err = 0.0, .gamma_oo = 4.5, .s_oo = 1.0};
    break;
  case 2:
    *l = (rp_liquids){.M = 2.231, .M_err = 0.023, .gamma_oo = 4.5, .s_oo = 0.25};
    break;
  case 5:
    *l = (rp_liquids){.M = 5.398, .M_err = 0.065, .gamma_oo = 13.5, .s_oo = 0.25};
    break;
  default:
    return -1;
  }
  l->gamma_wo = 0.5 * (4.5 + l->gamma_oo);
  l->s_wo = 0.5 * (1.0 + l->s_oo);
  return 0;
}

/* One pair's thermostat part: nothing at the default (gamma 4.5, s 1), so an M = 1 scene reads as
 * the one-liquid template's pairs. */
static void thermostat(double gamma, double s, char *out, int len) {
  out[0] = 0;
  if (gamma != 4.5) snprintf(out, len, ", gamma: %.6g", gamma);
  if (s != 1.0) {
    const size_t u = strlen(out);
    snprintf(out + u, len - u, ", s: %.6g", s);
  }
}

void rp_pairs_text(const rp_liquids *l, int wetting, double a_wo, const char *const *walls,
                   int n_walls, char *out, int len) {
  char oo[64], wo[64];
  thermostat(l->gamma_oo, l->s_oo, oo, sizeof oo);
  thermostat(l->gamma_wo, l->s_wo, wo, sizeof wo);
  const double a_water = wetting == RP_WET_WATER ? RP_A_WETTING : RP_A_NONWETTING;
  const double a_oil = wetting == RP_WET_WATER ? RP_A_NONWETTING : RP_A_WETTING;
  int n =
      snprintf(out, len,
               "{default: {A: %.6g, B: 25.0, gamma: 4.5, rc: 1.0, rd: 0.75}, oil-oil: {A: %.6g%s}, "
               "water-oil: {A: %.6g%s}",
               RP_A_LIKE, RP_A_LIKE, oo, a_wo, wo);
  for (int k = 0; k < n_walls && n < len; k++)
    n += snprintf(out + n, len - n, ", water-%s: {A: %.6g}, oil-%s: {A: %.6g%s}", walls[k], a_water,
                  walls[k], a_oil, oo);
  if (n < len) snprintf(out + n, len - n, "}");
}

/* --template SCENE: its pairs block, which must name both liquids. */
int rp_template_pairs(const char *path, char *out, int len) {
  ytree_t t;
  if (yt_load(&t, path, 0)) return -1;
  int rc = -1;
  yaml_node_t *root = yt_root(&t), *species, *pairs;
  if (!root || yt_expect_map(&t, root, "")) goto done;
  int have_water = 0, have_oil = 0;
  if (!(species = yt_need(&t, root, "species", "species", "the species water and oil")) ||
      yt_expect_seq(&t, species, "species"))
    goto done;
  for (int i = 0; i < yt_seq_size(species); i++) {
    yaml_node_t *e = yt_seq_item(&t, species, i), *nm;
    char name[128];
    if (e && e->type == YAML_MAPPING_NODE && (nm = yt_get(&t, e, "name")) &&
        !yt_string(&t, nm, "species.name", name, sizeof name)) {
      have_water |= !strcmp(name, "water");
      have_oil |= !strcmp(name, "oil");
    }
  }
  if (!have_water || !have_oil) {
    yt_error(&t, species, "species",
             "expected the two liquids water and oil of a relative-permeability campaign (got %s)",
             have_water ? "water only"
             : have_oil ? "oil only"
                        : "neither");
    goto done;
  }
  if (!(pairs = yt_need(&t, root, "pairs", "pairs", "the pair parameters of water and oil")) ||
      yt_expect_map(&t, pairs, "pairs"))
    goto done;
  /* the block as flow YAML: key: {param: value, ...} */
  int n = snprintf(out, len, "{");
  int first = 1;
  for (yaml_node_pair_t *p = pairs->data.mapping.pairs.start; p < pairs->data.mapping.pairs.top;
       p++) {
    yaml_node_t *k = yaml_document_get_node(&t.doc, p->key);
    yaml_node_t *v = yaml_document_get_node(&t.doc, p->value);
    if (!k || k->type != YAML_SCALAR_NODE || !v || v->type != YAML_MAPPING_NODE) {
      yt_error(&t, v ? v : pairs, "pairs", "expected name: {A: ..., ...} entries");
      goto done;
    }
    n += snprintf(out + n, n < len ? len - n : 0, "%s%s: {", first ? "" : ", ",
                  (const char *)k->data.scalar.value);
    first = 0;
    int f2 = 1;
    for (yaml_node_pair_t *q = v->data.mapping.pairs.start; q < v->data.mapping.pairs.top; q++) {
      yaml_node_t *kk = yaml_document_get_node(&t.doc, q->key);
      yaml_node_t *vv = yaml_document_get_node(&t.doc, q->value);
      if (!kk || kk->type != YAML_SCALAR_NODE || !vv || vv->type != YAML_SCALAR_NODE) continue;
      n += snprintf(out + n, n < len ? len - n : 0, "%s%s: %s", f2 ? "" : ", ",
                    (const char *)kk->data.scalar.value, (const char *)vv->data.scalar.value);
      f2 = 0;
    }
    n += snprintf(out + n, n < len ? len - n : 0, "}");
  }
  n += snprintf(out + n, n < len ? len - n : 0, "}");
  if (n >= len) {
    fprintf(stderr, "mdpore relperm: %s: key 'pairs': too long (%d characters)\n", path, n);
    goto done;
  }
  rc = 0;
done:
  yt_free(&t);
  return rc;
}
