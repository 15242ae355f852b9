/* Output of `mdpore fit relperm`: the JSON report (read by plot_relperm.py) and the terminal table.
 */
#ifndef MDPORE_UPSCALE_KR_REPORT_H
#define MDPORE_UPSCALE_KR_REPORT_H

#include <stdio.h>

#include "kr_select.h"
#include "kr_swof.h"

/* Points of the sampled law curves in the JSON report, Sw on [0, 1]. */
#define KR_CURVE_POINTS 101

/* "corey: swc = 0.1 +- 0.01, ..." (inflated errors), for the SWOF header. */
void kr_law_text(const kr_fit_result *r, char *buf, int len);

/* fits[] indexed by kr_law_kind (ok = 0 where not run); swof NULL when not exported. */
int kr_write_json(const char *path, const kr_table *t, const kr_fit_opts *o,
                  const kr_fit_result fits[KR_LAW_COUNT], const kr_choice *c, const kr_swof *swof,
                  const char *swof_path);
void kr_print(FILE *out, const kr_table *t, const kr_fit_opts *o,
              const kr_fit_result fits[KR_LAW_COUNT], const kr_choice *c);

#endif
