/* Mean and standard error of correlated time series by block averaging (Flyvbjerg & Petersen, J.
 * Chem. Phys. 91, 461 (1989)): the series is cut into blocks of 1, 2, 4, ... samples; once blocks
 * are longer than the correlation time the naive error of the block means levels off. The error
 * reported is the largest estimate over block sizes that leave at least BLOCK_AVERAGE_MIN_BLOCKS
 * blocks (a conservative read of the plateau; the same rule as validation/engine/mdval.py). */
#ifndef MESO_ANALYSIS_BLOCK_AVERAGE_H
#define MESO_ANALYSIS_BLOCK_AVERAGE_H

#define BLOCK_AVERAGE_MIN_BLOCKS 16

typedef struct {
  double mean;
  double err;     /* standard error of the mean (inf for fewer than 2 samples) */
  long n;         /* samples */
  long block_len; /* block length at which the reported error was found */
} block_average_t;

block_average_t block_average(const double *x, long n);

/* A growing series of doubles (rank-0 time series of the run summary). */
typedef struct {
  double *x;
  long n, cap;
} series_t;

void series_push(series_t *s, double v);
void series_free(series_t *s);

#endif
