/* Block averaging of correlated series (see block_average.h). */
#include "analysis/block_average.h"

#include <math.h>
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

block_average_t block_average(const double *x, long n) {
  block_average_t r = {NAN, INFINITY, n, 1};
  if (n < 1) return r;
  double sum = 0;
  for (long i = 0; i < n; i++) sum += x[i];
  r.mean = sum / (double)n;
  if (n < 2) return r;
  r.err = 0;
  for (long len = 1; len == 1 || n / len >= BLOCK_AVERAGE_MIN_BLOCKS; len *= 2) {
    const long nb = n / len;
    if (nb < 2) break;
    /* Means of the blocks use the first nb * len samples; centre on their own mean. */
    double m = 0;
    for (long i = 0; i < nb * len; i++) m += x[i];
    m /= (double)(nb * len);
    const double e = block_error(x, nb, len, m);
    if (e > r.err) {
      r.err = e;
      r.block_len = len;
    }
  }
  return r;
}

void series_push(series_t *s, double v) {
  if (s->n == s->cap) {
    s->cap = s->cap ? 2 * s->cap : 1024;
    s->x = realloc(s->x, (size_t)s->cap * sizeof *s->x);
  }
  s->x[s->n++] = v;
}

void series_free(series_t *s) {
  free(s->x);
  s->x = NULL;
  s->n = s->cap = 0;
}
