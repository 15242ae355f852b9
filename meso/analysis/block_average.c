/* Block averaging of correlated series (see block_average.h). */
#include "analysis/block_average.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Standard error of the mean of nb block means of length len (the first nb * len samples). */
static double block_error(const double *x, long nb, long len, double mean) {
  double ss = 0;
  for (long b = 0; b < nb; b++) {
    double m = 0;
    for (long i = 0; i < len; i++) m += x[b * len + i];
    m /= (double)len;
    ss += (m - mean) * (m - mean);
  }
  return sqrt(ss / (double)(nb - 1) / (double)nb);
}

/* Blocked error with blocks of len samples, centred on the mean of the samples the blocks use. */
static double level_error(const double *x, long n, long len) {
  const long nb = n / len;
  double m = 0;
  for (long i = 0; i < nb * len; i++) m += x[i];
  m /= (double)(nb * len);
  return block_error(x, nb, len, m);
}

static double mean_of(const double *x, long n) {
  double sum = 0;
  for (long i = 0; i < n; i++) sum += x[i];
  return sum / (double)n;
}

block_average_t block_average(const double *x, long n) {
  block_average_t r = {NAN, INFINITY, n, 1, 0};
  if (n < 1) return r;
  r.mean = mean_of(x, n);
  if (n < 2) return r;
  r.err = 0;
  for (long len = 1; len == 1 || n / len >= BLOCK_AVERAGE_MIN_BLOCKS; len *= 2) {
    if (n / len < 2) break;
    const double e = level_error(x, n, len);
    if (e > r.err) {
      r.err = e;
      r.block_len = len;
    }
  }
  return r;
}

int block_levels(const double *x, long n, long min_blocks, block_level_t *lv, int max) {
  if (min_blocks < 2) min_blocks = 2;
  int k = 0;
  for (long len = 1; k < max && n / len >= min_blocks; len *= 2, k++) {
    const long nb = n / len;
    lv[k].block_len = len;
    lv[k].nblocks = nb;
    lv[k].err = level_error(x, n, len);
    lv[k].err_err = lv[k].err / sqrt(2.0 * (double)(nb - 1));
  }
  return k;
}

block_average_t block_average_plateau(const double *x, long n) {
  block_average_t r = {NAN, INFINITY, n, 1, 0};
  if (n < 1) return r;
  r.mean = mean_of(x, n);
  block_level_t lv[64];
  const int nl = block_levels(x, n, BLOCK_PLATEAU_MIN_BLOCKS, lv, 64);
  if (nl < 1) return r;
  /* The blocked error rises with the block length B until blocks are longer than the correlation
   * time, then stays level (Flyvbjerg & Petersen). Its plateau, read automatically: the shortest
   * B with B^3 > 2 n (err_B / err_1)^4 (Lee, Needs & Drummond, Phys. Rev. B 83, 066706 (2011),
   * sec. III; (err_B / err_1)^2 estimates 2 tau_int, so B grows with the correlation time and
   * slowly with n, balancing the bias of too short blocks against the noise of too few). */
  for (int k = 0; k < nl; k++) {
    const double ratio = lv[0].err > 0 ? lv[k].err / lv[0].err : 1.0;
    const double B = (double)lv[k].block_len;
    if (B * B * B > 2.0 * (double)n * ratio * ratio * ratio * ratio) {
      r.err = lv[k].err;
      r.block_len = lv[k].block_len;
      r.plateau = 1;
      return r;
    }
  }
  /* No plateau: the largest error seen, a lower bound of the true one. */
  r.err = 0;
  for (int k = 0; k < nl; k++)
    if (lv[k].err > r.err) {
      r.err = lv[k].err;
      r.block_len = lv[k].block_len;
    }
  return r;
}

int series_push(series_t *s, double v) {
  if (s->n == s->cap) {
    const long cap = s->cap ? 2 * s->cap : 1024;
    double *x = realloc(s->x, (size_t)cap * sizeof *x);
    if (!x) {
      if (!s->full)
        fprintf(stderr,
                "mdpore: warning: out of memory for a time series of %ld samples: later samples "
                "are left out of its statistics\n",
                cap);
      s->full = 1;
      return -1;
    }
    s->x = x, s->cap = cap;
  }
  s->x[s->n++] = v;
  return 0;
}

void series_free(series_t *s) {
  free(s->x);
  s->x = NULL;
  s->n = s->cap = 0;
}
