/* MSER-5 truncation and the steady-state mean with its block-averaged error (see steady_state.h).
 */
#include "analysis/steady_state.h"

#include <math.h>
#include <stdlib.h>

/* The means of k batches of b samples of x (malloc'd; NULL without memory) and their mean. */
static double *batch_means(const double *x, long k, long b, double *mean) {
  double *z = malloc((size_t)k * sizeof *z);
  if (!z) return NULL;
  double sum = 0;
  for (long j = 0; j < k; j++) {
    double m = 0;
    for (long i = 0; i < b; i++) m += x[j * b + i];
    z[j] = m / b;
    sum += z[j];
  }
  *mean = sum / (double)k;
  return z;
}

long mser_truncation(const double *x, long n, int batch, int *steady) {
  *steady = 0;
  if (batch < 1) batch = 1;
  const long k = n / batch;
  if (k < 2) return 0;
  /* Batch means, centred on their overall mean (keeps the running sums well conditioned). Samples
   * past the last full batch are left out of the statistic, as MSER-m does. */
  double c;
  double *z = batch_means(x, k, batch, &c);
  if (!z) return 0;
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

/* Sokal's automatic window on the batch means z[0..k) of x[0..n) (batches of b samples, k <= 4096):
 * tau_int of z in batches (tau_b), and the variance of z. */
static double batch_tau(const double *x, long n, long *batch, long *k_out, double *var_z) {
  const long b = n > 4096 ? (n + 4095) / 4096 : 1, k = n / b;
  *batch = b;
  *k_out = k;
  *var_z = 0;
  if (k < 4) return 0.5;
  double mean;
  double *z = batch_means(x, k, b, &mean);
  if (!z) return INFINITY;
  double c0 = 0;
  for (long j = 0; j < k; j++) c0 += (z[j] - mean) * (z[j] - mean);
  double tau = 0.5; /* tau_int = 1/2 + sum_{t=1..M} rho(t), window M >= 6 tau (Sokal) */
  if (c0 > 0) {
    for (long t = 1; t < k / 2; t++) {
      double c = 0;
      for (long j = 0; j + t < k; j++) c += (z[j] - mean) * (z[j + t] - mean);
      tau += c / c0;
      if ((double)t >= 6.0 * tau) break;
    }
  }
  free(z);
  *var_z = c0 / (double)(k - 1);
  return tau < 0.5 ? 0.5 : tau;
}

static void window_stats(const double *x, long n, steady_state_t *out);

double integrated_autocorrelation_time(const double *x, long n) {
  long b, k;
  double var_z;
  const double tau_b = batch_tau(x, n, &b, &k, &var_z);
  return b == 1 ? tau_b : tau_b * b; /* batched: an upper bound in samples */
}

void steady_state_analyse(const double *x, long n, steady_state_t *out) {
  steady_state_analyse_from(x, n, 0, out);
}

void steady_state_analyse_from(const double *x, long n, double tau_slow, steady_state_t *out) {
  out->n = n;
  out->tau_floor = 0;
  out->floor_governs = 0;
  out->mser_start = out->start = mser_truncation(x, n, STEADY_MSER_BATCH, &out->steady);
  out->tau_slow = tau_slow > 0 && isfinite(tau_slow) ? tau_slow : 0;
  out->slow_governs = out->before_slow = 0;
  if (out->tau_slow > 0) {
    const double slow_start = ceil(STEADY_SLOW_TRANSIENT_TIMES * out->tau_slow);
    if (slow_start > (double)(n - 2)) {
      out->before_slow = 1; /* the transient is not over: analysed from MSER's start, not steady */
      out->steady = 0;
    } else if ((long)slow_start > out->start) {
      out->start = (long)slow_start;
      out->slow_governs = 1;
    }
  }
  window_stats(x, n, out);
}

/* The mean and error of x[out->start..n): the block error, or the autocorrelation error where it
 * is larger; n_eff, tau_int and rel_err with them. */
static void window_stats(const double *x, long n, steady_state_t *out) {
  const long m = n - out->start;
  out->avg = block_average_plateau(x + out->start, m);
  /* The autocorrelation estimate on (batch means of) the window: error sqrt(var_z 2 tau_b / k),
   * n_eff = k / (2 tau_b); the reported error is the larger of it and the block error. */
  long b = 1, k = 0;
  double var_z = 0;
  const double tau_b = m > 0 ? batch_tau(x + out->start, m, &b, &k, &var_z) : 0.5;
  out->n_eff = k > 0 ? (double)k / (2.0 * tau_b) : 0;
  out->tau_int = out->n_eff > 0 ? (double)m / (2.0 * out->n_eff) : INFINITY;
  if (k >= 4 && isfinite(out->avg.err)) {
    const double acf_err = sqrt(var_z * 2.0 * tau_b / (double)k);
    if (acf_err > out->avg.err) out->avg.err = acf_err;
  }
  out->rel_err =
      out->avg.mean != 0 && isfinite(out->avg.err) ? out->avg.err / fabs(out->avg.mean) : INFINITY;
}

void steady_state_floor_tau(steady_state_t *s, const double *x, double tau_floor) {
  if (!(tau_floor > 0) || !isfinite(tau_floor)) return;
  s->tau_floor = tau_floor;
  const long m = s->n - s->start;
  if (m < 2 || !(tau_floor > s->tau_int)) return;
  const double *w = x + s->start;
  double mean = 0, var = 0;
  for (long i = 0; i < m; i++) mean += w[i];
  mean /= (double)m;
  for (long i = 0; i < m; i++) var += (w[i] - mean) * (w[i] - mean);
  var /= (double)(m - 1);
  s->floor_governs = 1;
  s->tau_int = tau_floor;
  s->n_eff = (double)m / (2.0 * tau_floor);
  const double err = sqrt(var * 2.0 * tau_floor / (double)m);
  if (!(s->avg.err >= err)) s->avg.err = err; /* (a NaN error too) */
  s->rel_err = s->avg.mean != 0 && isfinite(s->avg.err) ? s->avg.err / fabs(s->avg.mean) : INFINITY;
}

int steady_state_converged(const steady_state_t *s, double target) {
  const long window = s->n - s->start;
  return s->steady && s->avg.plateau && window >= STEADY_MIN_SAMPLES &&
         window >= STEADY_WINDOW_OVER_TRANSIENT * s->mser_start &&
         (double)window >= STEADY_SLOW_WINDOW_TIMES * s->tau_slow &&
         s->n_eff >= STEADY_MIN_EFFECTIVE && s->rel_err <= target;
}

void steady_state_window(const double *x, long n, const steady_state_t *ref, steady_state_t *out) {
  *out = *ref;
  out->n = n;
  out->tau_floor = 0;
  out->floor_governs = 0;
  window_stats(x, n, out);
  steady_state_floor_tau(out, x, ref->tau_floor);
}
