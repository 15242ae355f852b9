/* MSER-5 truncation and the steady-state mean with its block-averaged error (see steady_state.h).
 */
#include "analysis/steady_state.h"

#include <math.h>
#include <stdlib.h>

long mser_truncation(const double *x, long n, int batch, int *steady) {
  *steady = 0;
  if (batch < 1) batch = 1;
  const long k = n / batch;
  if (k < 2) return 0;
  /* Batch means, centred on their overall mean (keeps the running sums well conditioned). Samples
   * past the last full batch are left out of the statistic, as MSER-m does. */
  double *z = malloc((size_t)k * sizeof *z);
  if (!z) return 0;
  double c = 0;
  for (long j = 0; j < k; j++) {
    double m = 0;
    for (long i = 0; i < batch; i++) m += x[j * batch + i];
    z[j] = m / batch;
    c += z[j];
  }
  c /= (double)k;
  /* Suffix sums from the end: s1 = sum z, s2 = sum z^2 over batches d..k-1. */
  double s1 = 0, s2 = 0, best = INFINITY;
  long best_d = 0;
  for (long d = k - 1; d >= 0; d--) {
    const double v = z[d] - c;
    s1 += v;
    s2 += v * v;
    if (d > k / 2) continue; /* MSER looks at truncations in the first half only */
    const double m = (double)(k - d);
    double ss = s2 - s1 * s1 / m;
    if (ss < 0) ss = 0;
    const double stat = ss / (m * m);
    if (stat <= best) { /* ties: the earliest truncation (d runs downwards) */
      best = stat;
      best_d = d;
    }
  }
  free(z);
  /* A minimum at the edge of the allowed range: the statistic was still falling, no steady part
   * shows within the series (White 1997). */
  *steady = best_d < k / 2;
  return best_d * batch;
}

void steady_state_analyse(const double *x, long n, steady_state_t *out) {
  out->n = n;
  out->start = mser_truncation(x, n, STEADY_MSER_BATCH, &out->steady);
  out->avg = block_average_plateau(x + out->start, n - out->start);
  out->rel_err =
      out->avg.mean != 0 && isfinite(out->avg.err) ? out->avg.err / fabs(out->avg.mean) : INFINITY;
}

int steady_state_converged(const steady_state_t *s, double target) {
  return s->steady && s->avg.plateau && s->n - s->start >= STEADY_MIN_SAMPLES &&
         s->rel_err <= target;
}
