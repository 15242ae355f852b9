/* Steady state of a time series (the flux q of a flow run) and its error bar:
 *  1. the end of the transient by MSER-5 (White, Simulation 69, 323 (1997); White, Cobb & Spratt,
 *     Proc. Winter Simulation Conf. 2000; Franklin & White, WSC 2008): batch means of 5 samples
 *     Z_1..Z_k; the truncation d (in batches) minimises
 *         MSER(d) = sum_{j > d} (Z_j - mean_{j > d} Z)^2 / (k - d)^2,
 *     the squared standard error of the mean left after dropping the first d batches, over
 *     d <= k / 2. A minimum found in the second half of the range is MSER's sign that the series
 *     has not reached a steady state within its length (steady = 0);
 *  2. the mean after the truncation and its standard error by block averaging, the block length
 *     chosen from the data (the plateau of the blocked error, analysis/block_average.h). */
#ifndef MESO_ANALYSIS_STEADY_STATE_H
#define MESO_ANALYSIS_STEADY_STATE_H

#include "analysis/block_average.h"

#define STEADY_MSER_BATCH 5
/* A converged verdict needs at least this many samples after the truncation. */
#define STEADY_MIN_SAMPLES 100

typedef struct {
  long n;              /* samples analysed */
  long start;          /* first sample of the steady part (the MSER-5 truncation) */
  int steady;          /* 1: MSER's minimum lies in the first half of the series */
  block_average_t avg; /* mean and error of x[start..n) (block_average_plateau) */
  double rel_err;      /* avg.err / |avg.mean| (inf when the mean is 0) */
} steady_state_t;

/* MSER truncation with batches of `batch` samples: the number of samples to drop (a multiple of
 * batch); *steady as above. Fewer than 2 batches: 0 dropped, *steady = 0. */
long mser_truncation(const double *x, long n, int batch, int *steady);

/* MSER-5, then the block average of what follows. */
void steady_state_analyse(const double *x, long n, steady_state_t *out);

/* Whether the analysed series meets a relative error target: steady, a plateau of the blocked
 * error, at least STEADY_MIN_SAMPLES samples used and rel_err <= target. */
int steady_state_converged(const steady_state_t *s, double target);

#endif
