/* Output of `mdpore fit`: JSON (machine contract, read back by `mdpore darcy` and plot_fit.py) and
 * a human-readable table. */
#ifndef MDPORE_UPSCALE_FIT_REPORT_H
#define MDPORE_UPSCALE_FIT_REPORT_H

#include <stdio.h>

#include "fit_select.h"
#include "flowdata/flow_table.h"

#define MD_PER_M2 (1.0 / 9.869233e-16) /* 1 D = 9.869233e-13 m^2 */

/* Unit string of reported parameter i of a law, for the table's unit system. */
void fit_param_unit(const flow_table *t, flow_law_kind kind, int i, char *buf, int len);
/* Permeability in m^2 if the table allows the conversion (SI, or reduced with length_unit_m), else
 * NAN */
double fit_k_in_m2(const flow_table *t, double k);

int fit_write_json(const char *path, const flow_table *t, const fit_result *r, int nr, int chosen,
                   fit_criterion crit);
void fit_print_table(FILE *out, const flow_table *t, const fit_result *r, int nr, int chosen,
                     fit_criterion crit);

#endif
