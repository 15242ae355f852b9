/* Reports of a slip fit (`mdpore slip`): the text table, the trend table as CSV, and JSON (the
 * layout is in docs/permeability.md, "Slip and apparent permeability"). */
#ifndef MDPORE_UPSCALE_SLIP_REPORT_H
#define MDPORE_UPSCALE_SLIP_REPORT_H

#include <stdio.h>

#include "slip_fit.h"

/* b and its errors in metres, when every point that knows rc agrees on it; else NaN. */
double slip_rc_m(const slip_point *p, int n, double rc_m_option);

void slip_print(FILE *out, const slip_point *p, int n, const slip_setup *s, const slip_result *r,
                double rc_m);
/* h, k, k_err, porosity, k_noslip, ratio, ratio_err, model, model_err, residual/sigma, source. */
int slip_write_csv(const char *path, const slip_point *p, int n, const slip_setup *s,
                   const slip_result *r);
/* Everything, plus a curve of the model's ratio over sizes for the plot. */
int slip_write_json(const char *path, const slip_point *p, int n, const slip_setup *s,
                    const slip_result *r, double rc_m);

#endif
