/* Mean and standard error of correlated time series by block averaging (Flyvbjerg & Petersen, J.
 * Chem. Phys. 91, 461 (1989)): the series is cut into blocks of 1, 2, 4, ... samples; once blocks
 * are longer than the correlation time the naive error of the block means levels off.
 *  - block_average: the largest estimate over block sizes that leave at least
 *    BLOCK_AVERAGE_MIN_BLOCKS blocks (a conservative read of the plateau; the same rule as
 *    validation/engine/mdval.py). Used by the run summary's thermo averages.
 *  - block_average_plateau: the block length chosen from the data, where the blocked error stops
 *    growing (used by the flux's steady-state analysis, analysis/steady_state.c). */
#ifndef MESO_ANALYSIS_BLOCK_AVERAGE_H
#define MESO_ANALYSIS_BLOCK_AVERAGE_H

#define BLOCK_AVERAGE_MIN_BLOCKS 16
/* Levels that block_average_plateau looks at keep at least this many blocks. */
#define BLOCK_PLATEAU_MIN_BLOCKS 8

typedef struct {
  double mean;
  double err;     /* standard error of the mean (inf for fewer than 2 samples) */
  long n;         /* samples */
  long block_len; /* block length at which the reported error was found */
  int plateau;    /* block_average_plateau: 1 when the blocked error levelled off */
} block_average_t;

block_average_t block_average(const double *x, long n);

/* One blocking level: blocks of block_len samples, nblocks of them (the first nblocks * block_len
 * samples), the standard error of the mean from the block means, and the uncertainty of that
 * estimate, err / sqrt(2 (nblocks - 1)) (Flyvbjerg & Petersen eq. 28). */
typedef struct {
  long block_len, nblocks;
  double err, err_err;
} block_level_t;

/* Levels with block lengths 1, 2, 4, ... while at least `min_blocks` (>= 2) blocks remain, at most
 * `max` of them. Returns how many were written. */
int block_levels(const double *x, long n, long min_blocks, block_level_t *lv, int max);

/* The plateau rule: the shortest block length B = 2^k (with at least BLOCK_PLATEAU_MIN_BLOCKS
 * blocks) where B^3 > 2 n (err_B / err_1)^4 (Lee, Needs & Drummond, Phys. Rev. B 83, 066706
 * (2011): the automated read of the Flyvbjerg-Petersen plateau; pyblock's rule), plateau = 1.
 * Without one (the series is too short for its correlation time: B would leave fewer blocks) the
 * largest error over the levels, a lower bound, and plateau = 0. */
block_average_t block_average_plateau(const double *x, long n);

/* A growing series of doubles (rank-0 time series of the run summary). */
typedef struct {
  double *x;
  long n, cap;
  int full; /* the array could not grow: later values were left out (said once on stderr) */
} series_t;

/* Append v. 0, or -1 when the array cannot grow: v is left out, the series keeps its values and a
 * warning is printed once. */
int series_push(series_t *s, double v);
void series_free(series_t *s);

#endif
