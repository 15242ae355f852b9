/* Corey and LET relative-permeability laws (see kr_law.h). */
#include "kr_law.h"

#include <math.h>
#include <string.h>

static const char *const corey_names[] = {"swc", "sor", "krw_max", "nw", "kro_max", "no"};
static const char *const let_names[] = {"swc", "sor",     "krw_max", "Lw", "Ew",
                                        "Tw",  "kro_max", "Lo",      "Eo", "To"};

int kr_law_nparams(kr_law_kind kind) {
  return kind == KR_COREY ? 6 : kind == KR_LET ? 10 : 0;
}

const char *kr_law_name(kr_law_kind kind) {
  return kind == KR_COREY ? "corey" : kind == KR_LET ? "let" : "?";
}

int kr_law_from_name(const char *name) {
  if (!strcmp(name, "corey")) return KR_COREY;
  if (!strcmp(name, "let")) return KR_LET;
  return -1;
}

const char *kr_law_param_name(kr_law_kind kind, int i) {
  if (i < 0 || i >= kr_law_nparams(kind)) return "?";
  return kind == KR_COREY ? corey_names[i] : let_names[i];
}

int kr_law_param_index(kr_law_kind kind, const char *name) {
  for (int i = 0; i < kr_law_nparams(kind); i++)
    if (!strcmp(kr_law_param_name(kind, i), name)) return i;
  return -1;
}

double kr_law_se(const kr_law *law, double sw) {
  const double swc = law->p[0], sor = law->p[1], span = 1.0 - swc - sor;
  const double se = span > 0 ? (sw - swc) / span : 0.0;
  return se < 0.0 ? 0.0 : se > 1.0 ? 1.0 : se;
}

/* LET: kr_max s^L / (s^L + E (1 - s)^T), s the phase's own normalised saturation; 0 at s = 0 and
 * kr_max at s = 1 for any L, E, T > 0. */
static double let_branch(double s, double kr_max, double L, double E, double T) {
  if (s <= 0.0) return 0.0;
  if (s >= 1.0) return kr_max;
  const double a = pow(s, L);
  return kr_max * a / (a + E * pow(1.0 - s, T));
}

void kr_law_eval(const kr_law *law, double sw, double *krw, double *kro) {
  const double se = kr_law_se(law, sw);
  const double *p = law->p;
  if (law->kind == KR_COREY) {
    *krw = p[2] * pow(se, p[3]);
    *kro = p[4] * pow(1.0 - se, p[5]);
  } else {
    *krw = let_branch(se, p[2], p[3], p[4], p[5]);
    *kro = let_branch(1.0 - se, p[6], p[7], p[8], p[9]);
  }
}

/* Corey branch K s^n and its derivatives d/dK, d/dn, d/ds. */
static double corey_branch_grad(double s, double K, double n, double *dK, double *dn, double *ds) {
  if (s <= 0.0) return *dK = *dn = *ds = 0.0, 0.0;
  const double a = pow(s, n);
  *dK = a;
  *dn = K * a * log(s);
  *ds = K * n * a / s;
  return K * a;
}

/* LET branch f = K a / (a + E c), a = s^L, c = (1 - s)^T, and d/dK, d/dL, d/dE, d/dT, d/ds. */
static double let_branch_grad(double s, double K, double L, double E, double T, double *g,
                              double *ds) {
  g[0] = g[1] = g[2] = g[3] = *ds = 0.0;
  if (s <= 0.0) return 0.0;
  if (s >= 1.0) return g[0] = 1.0, K;
  const double a = pow(s, L), c = pow(1.0 - s, T), den = a + E * c, den2 = den * den;
  const double df_da = K * E * c / den2, df_dc = -K * a * E / den2;
  g[0] = a / den;
  g[1] = df_da * a * log(s);
  g[2] = -K * a * c / den2;
  g[3] = df_dc * c * log(1.0 - s);
  *ds = df_da * L * a / s - df_dc * T * c / (1.0 - s);
  return K * a / den;
}

void kr_law_eval_grad(const kr_law *law, double sw, double *krw, double *kro, double *dkrw,
                      double *dkro) {
  const double *p = law->p;
  const double swc = p[0], sor = p[1], span = 1.0 - swc - sor;
  const double raw = span > 0 ? (sw - swc) / span : 0.0;
  const int inside = raw > 0.0 && raw < 1.0;
  const double se = raw < 0.0 ? 0.0 : raw > 1.0 ? 1.0 : raw;
  /* dSe/dswc = (Se - 1) / span, dSe/dsor = Se / span (0 where Se is clamped) */
  const double dse_dswc = inside ? (se - 1.0) / span : 0.0, dse_dsor = inside ? se / span : 0.0;
  const int np = kr_law_nparams(law->kind);
  for (int j = 0; j < np; j++) dkrw[j] = dkro[j] = 0.0;
  double dw_dse, do_dse;
  if (law->kind == KR_COREY) {
    double ds;
    *krw = corey_branch_grad(se, p[2], p[3], &dkrw[2], &dkrw[3], &ds);
    dw_dse = ds;
    *kro = corey_branch_grad(1.0 - se, p[4], p[5], &dkro[4], &dkro[5], &ds);
    do_dse = -ds;
  } else {
    double ds;
    *krw = let_branch_grad(se, p[2], p[3], p[4], p[5], &dkrw[2], &ds);
    dw_dse = ds;
    *kro = let_branch_grad(1.0 - se, p[6], p[7], p[8], p[9], &dkro[6], &ds);
    do_dse = -ds;
  }
  if (!inside) dw_dse = do_dse = 0.0;
  dkrw[0] = dw_dse * dse_dswc, dkrw[1] = dw_dse * dse_dsor;
  dkro[0] = do_dse * dse_dswc, dkro[1] = do_dse * dse_dsor;
}
