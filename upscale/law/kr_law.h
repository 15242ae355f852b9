/* Relative-permeability laws fitted by `mdpore fit relperm` (docs/relperm.md section 5). With the
 * normalised water saturation Se = (Sw - swc) / (1 - swc - sor), clamped to [0, 1]:
 *
 *   Corey:  krw = krw_max Se^nw,                         kro = kro_max (1 - Se)^no
 *   LET (Lomeland, Ebeltoft & Thomas 2005):
 *           krw = krw_max Se^Lw / (Se^Lw + Ew (1 - Se)^Tw),
 *           kro = kro_max (1 - Se)^Lo / ((1 - Se)^Lo + Eo Se^To)
 *
 * Parameters, in this order (the fit's parameter vector and the report's):
 *   Corey: swc sor krw_max nw kro_max no                      (6)
 *   LET:   swc sor krw_max Lw Ew Tw kro_max Lo Eo To          (10)
 */
#ifndef MDPORE_UPSCALE_KR_LAW_H
#define MDPORE_UPSCALE_KR_LAW_H

typedef enum { KR_COREY = 0, KR_LET = 1, KR_LAW_COUNT } kr_law_kind;

#define KR_MAX_PARAMS 10

typedef struct {
  kr_law_kind kind;
  double p[KR_MAX_PARAMS]; /* in the order above */
} kr_law;

int kr_law_nparams(kr_law_kind kind);
const char *kr_law_name(kr_law_kind kind); /* "corey", "let" */
int kr_law_from_name(const char *name);    /* -1 if unknown */
const char *kr_law_param_name(kr_law_kind kind, int i);
/* Index of the parameter of this name in the law, or -1. */
int kr_law_param_index(kr_law_kind kind, const char *name);

double kr_law_se(const kr_law *law, double sw);
/* krw and kro at water saturation sw. */
void kr_law_eval(const kr_law *law, double sw, double *krw, double *kro);
/* The same and their derivatives with respect to every parameter p[j] of the law (dkrw[j],
 * dkro[j]; 0 where Se is clamped for swc and sor, and for the shape parameters at Se = 0 or 1). */
void kr_law_eval_grad(const kr_law *law, double sw, double *krw, double *kro, double *dkrw,
                      double *dkro);

#endif
