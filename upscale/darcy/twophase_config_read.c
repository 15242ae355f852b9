/* The `twophase:` block of a `mdpore darcy` config (see twophase_config_read.h,
 * docs/twophase-darcy.md). */
#include "twophase_config_read.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "darcy_config_keys.h"

#define TRY(x)                                                                                     \
  do {                                                                                             \
    if ((x) != 0) return -1;                                                                       \
  } while (0)

enum { PATH_LEN = 256 };

static const char *const face_words[] = {"x-", "x+", "y-", "y+", "z-", "z+", NULL};

/* A plain number map.key in [lo, hi] at path.key; required, or *v keeps its default when absent. */
static int number_in(ytree_t *t, yaml_node_t *map, const char *path, const char *key, double lo,
                     double hi, int required, double *v) {
  char sub[PATH_LEN];
  snprintf(sub, sizeof sub, "%s.%s", path, key);
  yaml_node_t *n = required ? yt_need(t, map, key, sub, "a number") : yt_get(t, map, key);
  if (!n) return required ? -1 : 0;
  TRY(yt_double(t, n, sub, v));
  if (!(*v >= lo && *v <= hi))
    return yt_error(t, n, sub, "expected a number in [%g, %g] (got %g)", lo, hi, *v);
  return 0;
}

/* A positive quantity map.key (with an optional unit). */
static int positive_quantity(ytree_t *t, yaml_node_t *map, const char *path, const char *key,
                             darcy_quantity q, int si, double *v) {
  char sub[PATH_LEN];
  snprintf(sub, sizeof sub, "%s.%s", path, key);
  yaml_node_t *n = yt_need(t, map, key, sub, "a number (with an optional unit)");
  if (!n) return -1;
  TRY(darcy_key_quantity(t, n, sub, q, si, v));
  if (!(*v > 0 && isfinite(*v)))
    return yt_error(t, n, sub, "expected a %s > 0 (got %g)", darcy_quantity_name(q), *v);
  return 0;
}

/* relperm: {corey: {nw, no, swc, sor, krw_max, kro_max}} or {table: FILE} */
static int read_relperm(ytree_t *t, yaml_node_t *n, relperm *kr) {
  static const char *const keys[] = {"corey", "table", NULL};
  static const char *const corey_keys[] = {"nw", "no", "swc", "sor", "krw_max", "kro_max", NULL};
  char b[64], why[512];
  if (!n || n->type != YAML_MAPPING_NODE || yt_map_size(n) != 1)
    return yt_error(t, n, "twophase.relperm",
                    "expected exactly one of {corey: {nw, no, swc, sor, krw_max, kro_max}} or "
                    "{table: FILE} (got %s)",
                    yt_describe(n, b, sizeof b));
  TRY(yt_check_keys(t, n, "twophase.relperm", keys));
  yaml_node_t *c = yt_get(t, n, "corey");
  if (c) {
    TRY(yt_check_keys(t, c, "twophase.relperm.corey", corey_keys));
    kr->kind = RELPERM_COREY;
    kr->nw = kr->no = 2.0;
    kr->swc = kr->sor = 0.0;
    kr->krw_max = kr->kro_max = 1.0;
    double *v[] = {&kr->nw, &kr->no, &kr->swc, &kr->sor, &kr->krw_max, &kr->kro_max};
    for (int i = 0; i < 6; i++)
      TRY(number_in(t, c, "twophase.relperm.corey", corey_keys[i], -INFINITY, INFINITY, 0, v[i]));
    if (relperm_check_corey(kr, why, sizeof why)) {
      const char *key = strtok(why, ":"), *rest = why + strlen(key) + 2;
      char sub[PATH_LEN];
      snprintf(sub, sizeof sub, "twophase.relperm.corey.%s", key);
      yaml_node_t *at = yt_get(t, c, key);
      return yt_error(t, at ? at : c, sub, "%s%s", rest, at ? "" : " (the default)");
    }
    return 0;
  }
  yaml_node_t *tn = yt_get(t, n, "table");
  char path[4096];
  int had_pc;
  TRY(darcy_key_file_name(t, tn, "twophase.relperm.table", path, sizeof path));
  if (relperm_read_table(path, kr, &had_pc, why, sizeof why))
    return yt_error(t, tn, "twophase.relperm.table",
                    "expected a table of rows Sw krw kro [Pc] (got %s)", why);
  if (had_pc)
    yt_warn(t, tn, "twophase.relperm.table",
            "the capillary pressure column of '%s' is read and not used (no capillary pressure "
            "in this solve)",
            path);
  return 0;
}

/* injection: {face: x-, saturation: S, rate: Q} */
static int read_injection(ytree_t *t, yaml_node_t *n, darcy_config *c) {
  static const char *const keys[] = {"face", "saturation", "rate", NULL};
  twophase_config *tp = &c->twophase;
  darcy_problem *p = &c->problem;
  char b[64];
  if (!n || n->type != YAML_MAPPING_NODE)
    return yt_error(t, n, "twophase.injection",
                    "expected a mapping {face: x-, saturation: S, rate: Q} (got %s)",
                    yt_describe(n, b, sizeof b));
  TRY(yt_check_keys(t, n, "twophase.injection", keys));
  yaml_node_t *fn = yt_need(t, n, "face", "twophase.injection.face", "a face x-, x+, y-, ...");
  if (!fn || (tp->inlet_face = yt_enum(t, fn, "twophase.injection.face", face_words)) < 0)
    return -1;
  if (tp->inlet_face >= 2 * p->dim || !p->fixed[tp->inlet_face])
    return yt_error(t, fn, "twophase.injection.face",
                    "expected a face with a fixed pressure under `boundary` (got %s, which is %s)",
                    face_words[tp->inlet_face],
                    tp->inlet_face >= 2 * p->dim ? "not a face of this 2D grid" : "no-flow");
  double s_min, s_max;
  relperm_range(&tp->kr, &s_min, &s_max);
  tp->s_inj = s_max;
  TRY(number_in(t, n, "twophase.injection", "saturation", 0.0, 1.0, 0, &tp->s_inj));
  yaml_node_t *rn = yt_get(t, n, "rate");
  if (!rn) return 0;
  TRY(positive_quantity(t, n, "twophase.injection", "rate", p->dim == 3 ? QTY_RATE : QTY_RATE_2D,
                        c->si, &tp->rate));
  /* a set rate scales the pressure solution: every other fixed face must hold one pressure */
  double p_out = NAN;
  for (int f = 0; f < 2 * p->dim; f++)
    if (p->fixed[f] && f != tp->inlet_face) {
      if (isnan(p_out)) p_out = p->bc_p[f][0];
      if (p->bc_p[f][0] != p_out)
        return yt_error(t, rn, "twophase.injection.rate",
                        "expected the faces other than the inlet to hold one pressure when a rate "
                        "is set (got %g and %g)",
                        p_out, p->bc_p[f][0]);
    }
  if (isnan(p_out))
    return yt_error(t, rn, "twophase.injection.rate",
                    "expected a fixed-pressure outlet face besides the inlet %s (got none: the "
                    "injected fluid could not leave)",
                    face_words[tp->inlet_face]);
  if (p->source)
    return yt_error(t, rn, "twophase.injection.rate",
                    "expected no `sources` when an injection rate is set (got a sources list)");
  return 0;
}

/* output_times: [t1, t2, ...] increasing, each in (0, end_time] */
static int read_times(ytree_t *t, yaml_node_t *n, twophase_config *tp) {
  char b[64];
  if (!n) return 0;
  if (n->type != YAML_SEQUENCE_NODE)
    return yt_error(t, n, "twophase.output_times", "expected a list of times (got %s)",
                    yt_describe(n, b, sizeof b));
  tp->n_out = yt_seq_size(n);
  tp->t_out = calloc(tp->n_out ? tp->n_out : 1, sizeof(double));
  for (int i = 0; i < tp->n_out; i++) {
    char sub[64];
    snprintf(sub, sizeof sub, "twophase.output_times[%d]", i);
    yaml_node_t *it = yt_seq_item(t, n, i);
    TRY(yt_double(t, it, sub, &tp->t_out[i]));
    double prev = i ? tp->t_out[i - 1] : 0.0;
    if (!(tp->t_out[i] > prev && tp->t_out[i] <= tp->t_end))
      return yt_error(t, it, sub, "expected a time in (%g, end_time = %g] (got %g)", prev,
                      tp->t_end, tp->t_out[i]);
  }
  return 0;
}

static int read_output(ytree_t *t, yaml_node_t *n, twophase_config *tp) {
  static const char *const keys[] = {"profiles", "history", NULL};
  yaml_node_t *m;
  if (!n) return -1;
  TRY(yt_check_keys(t, n, "twophase.output", keys));
  if ((m = yt_get(t, n, "profiles")))
    TRY(darcy_key_file_name(t, m, "twophase.output.profiles", tp->profiles_csv,
                            sizeof tp->profiles_csv));
  if ((m = yt_get(t, n, "history")))
    TRY(darcy_key_file_name(t, m, "twophase.output.history", tp->history_csv,
                            sizeof tp->history_csv));
  if (!tp->profiles_csv[0] && !tp->history_csv[0])
    return yt_error(t, n, "twophase.output",
                    "expected a 'profiles' and/or a 'history' file name (got neither)");
  return 0;
}

int twophase_config_read(ytree_t *t, yaml_node_t *n, darcy_config *c) {
  static const char *const keys[] = {
      "mu_w",         "mu_o", "porosity", "relperm", "initial_saturation", "injection", "end_time",
      "output_times", "cfl",  "output",   NULL};
  twophase_config *tp = &c->twophase;
  darcy_problem *p = &c->problem;
  char b[64];
  if (n->type != YAML_MAPPING_NODE)
    return yt_error(t, n, "twophase", "expected a mapping (got %s)", yt_describe(n, b, sizeof b));
  TRY(yt_check_keys(t, n, "twophase", keys));
  tp->enabled = 1;
  snprintf(tp->config_path, sizeof tp->config_path, "%s", t->file ? t->file : "config");
  for (long i = 0; i < darcy_nblocks(p); i++)
    if (p->laws[i].kind != LAW_DARCY)
      return yt_error(t, n, "twophase",
                      "expected Darcy laws in every block for a two-phase solve (got a %s law in "
                      "block %ld)",
                      flow_law_name(p->laws[i].kind), i);
  if (darcy_is_diagonal(p))
    return yt_error(t, n, "twophase",
                    "expected one scalar law per block for a two-phase solve (got diagonal laws "
                    "{x: ..., y: ...}: the two-phase solve scales one permeability per block)");
  TRY(positive_quantity(t, n, "twophase", "mu_w", QTY_VISCOSITY, c->si, &tp->kr.mu_w));
  TRY(positive_quantity(t, n, "twophase", "mu_o", QTY_VISCOSITY, c->si, &tp->kr.mu_o));
  TRY(number_in(t, n, "twophase", "porosity", 1e-6, 1.0, 1, &tp->porosity));
  TRY(read_relperm(t, yt_need(t, n, "relperm", "twophase.relperm", "{corey: ...} or {table: FILE}"),
                   &tp->kr));
  double s_max;
  relperm_range(&tp->kr, &tp->s_init, &s_max);
  TRY(number_in(t, n, "twophase", "initial_saturation", 0.0, 1.0, 0, &tp->s_init));
  TRY(read_injection(t, yt_need(t, n, "injection", "twophase.injection", "{face: x-, ...}"), c));
  yaml_node_t *en = yt_need(t, n, "end_time", "twophase.end_time", "a time");
  if (!en) return -1;
  TRY(yt_double(t, en, "twophase.end_time", &tp->t_end));
  if (!(tp->t_end > 0 && isfinite(tp->t_end)))
    return yt_error(t, en, "twophase.end_time", "expected a time > 0 (got %g)", tp->t_end);
  TRY(read_times(t, yt_get(t, n, "output_times"), tp));
  tp->cfl = 0.5;
  TRY(number_in(t, n, "twophase", "cfl", 1e-3, 1.0, 0, &tp->cfl));
  return read_output(t,
                     yt_need(t, n, "output", "twophase.output",
                             "a mapping {profiles: FILE.csv, history: FILE.csv}"),
                     tp);
}

void twophase_config_free(twophase_config *tp) {
  relperm_free(&tp->kr);
  free(tp->t_out);
  tp->t_out = NULL;
  tp->n_out = 0;
}
