/* Weighted isotonic regression (pool adjacent violators): the non-decreasing sequence closest to y
 * in the weighted least-squares sense (Barlow, Bartholomew, Bremner & Brunk 1972). Used by the
 * measured-points SWOF rows (kr_swof_rows.c) and by the fit check's question whether any monotone
 * curve follows the rows within their errors (kr_judge.c). */
#ifndef MDPORE_UPSCALE_KR_ISOTONIC_H
#define MDPORE_UPSCALE_KR_ISOTONIC_H

/* y[0..n-1] replaced by its weighted isotonic (non-decreasing) regression, weights w > 0. Returns
 * the number of values it moved, or -1 when out of memory (y untouched). */
int kr_isotonic_increasing(double *y, const double *w, int n);

#endif
