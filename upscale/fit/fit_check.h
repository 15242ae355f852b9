/* Checks that a flow table can support the laws to be fitted, before any fit: enough rows, enough
 * distinct gradients, fluxes that vary (docs/flow-table.md, "Degenerate tables"). */
#ifndef MDPORE_UPSCALE_FIT_CHECK_H
#define MDPORE_UPSCALE_FIT_CHECK_H

#include "law/flow_law.h"
#include "flowdata/flow_table.h"

/* Gradients (or fluxes) closer than this, relative to the largest magnitude in the column, count as
 * the same value. */
#define FIT_SAME_VALUE_RTOL 1e-9

/* Number of distinct non-zero gradient magnitudes |G| in the table, values within
 * FIT_SAME_VALUE_RTOL * max|G| of each other counting once. */
int fit_distinct_gradients(const flow_table *t);

/* Refuses (returns -1 with err = "FILE: what is wrong ...: expected ...") a table that cannot
 * determine the laws `kinds` (count nk): fewer rows than the largest law has parameters plus one,
 * fewer distinct non-zero gradients than it has parameters (one gradient, or gradients that differ
 * only by rounding: zero variance), or fluxes that are all equal. */
int fit_check_table(const flow_table *t, const flow_law_kind *kinds, int nk, char *err, int errlen);

#endif
