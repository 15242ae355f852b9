/* Output of `mdpore fit relperm`: the JSON report (read by plot_relperm.py) and the terminal table.
 */
#ifndef MDPORE_UPSCALE_KR_REPORT_H
#define MDPORE_UPSCALE_KR_REPORT_H

#include <stdio.h>

#include "kr_outcome.h"
#include "kr_select.h"
#include "kr_swof.h"

/* Points of the sampled law curves in the JSON report, Sw on [0, 1]. */
#define KR_CURVE_POINTS 101

/* "corey: swc = 0.1 +- 0.01, ..." (inflated errors), for the SWOF header. */
void kr_law_text(const kr_fit_result *r, char *buf, int len);

/* fits[] indexed by kr_law_kind (ok = 0 where not run); swof NULL when not exported. The JSON's
 * choice.law is the result (outcome->law: null when no law is accepted), choice.test_law the
 * selection test's; every fit carries its check (`check`: accepted, per phase chi2, dof, chi2/dof,
 * its limit, the monotone curve's chi2/dof, the verdict). A refused law's parameters stay in the
 * JSON under its fit, flagged accepted: false: they are not a result. */
int kr_write_json(const char *path, const kr_table *t, const kr_fit_opts *o,
                  const kr_fit_result fits[KR_LAW_COUNT], const kr_choice *c,
                  const kr_outcome *outcome, const kr_swof *swof, const char *swof_path);
/* The terminal report: a refused law's parameters are not printed (its numbers and why are). */
void kr_print(FILE *out, const kr_table *t, const kr_fit_opts *o,
              const kr_fit_result fits[KR_LAW_COUNT], const kr_choice *c,
              const kr_outcome *outcome);

#endif
