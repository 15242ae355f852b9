/* The flux's steady-state analysis (analysis/steady_state.c, analysis/block_average.c) on synthetic
 * series with known answers:
 *  - white noise: the plateau error equals sigma / sqrt(n) within 10%, the mean within 4 errors,
 *    MSER drops (almost) nothing;
 *  - AR(1) noise x_t = phi x_{t-1} + sigma e_t with phi = 0.9 (integrated autocorrelation time
 *    tau_int = (1 + phi) / (2 (1 - phi)) = 9.5 samples): over 40 seeds the mean ratio of the
 *    plateau error to the exact sigma / ((1 - phi) sqrt(n)) lies within 0.85..1.1, tau_int read
 *    from (err_B / err_1)^2 / 2 within 20%, the true mean inside 2 errors in >= 85% of the seeds
 *    (the naive error of correlated samples, 1/sqrt(2 tau_int) of it, would fail this);
 *  - AR(1) with phi = 0.995 (tau_int ~ 200) over 600 samples: no plateau (too short), not
 *    converged whatever the target;
 *  - a transient: a linear ramp from mu + 20 sigma down to mu over the first 3000 of 12000 samples,
 *    then AR(1) noise: MSER-5 truncates within 2400..3300 and the mean after it matches mu within 3
 *    errors; an exponential relaxation (time constant 500 samples) is cut after 3 time constants
 *    at most and leaves a bias below 2 errors;
 *  - a series that drifts over its whole length: MSER says "not steady";
 *  - steady_state_converged: met for a long steady series at a loose target, not at a target
 *    below its error, not for too few samples;
 *  - the lucky window (a slit campaign stopped 18% low with a 0.9% error bar): tau_int of AR(1)
 *    phi = 0.9 within 25% of 9.5 (mean over 20 seeds); AR(1) phi = 0.98 (tau_int 49.5) over 1500
 *    samples, 15 independent ones (estimated 20-25: Sokal's window reads short series low): not converged at any target, its reported error not below the
 *    exact one by more than 30%; a steady window shorter than 3x the transient before it: not
 *    converged, the same series continued to 4x: converged;
 *  - the correlation-time floor (steady_state_floor_tau, the flux's Darcy relaxation time): AR(1)
 *    phi = 0.99 (tau_int 99.5) over 1500 samples, 40 seeds: the data alone reads tau_int short
 *    and its 2-error bars miss the true mean more often; floored at the exact tau_int, the error
 *    averages 0.8..1.25 of the exact one, the true mean lies inside 2 errors in >= 85% of the
 *    seeds, n_eff <= 7.6 and no seed converges at any target; a floor below the data's tau_int
 *    changes nothing;
 *  - a known slow mode (steady_state_analyse_from, the flux's pressure diffusion): mu (1 + 0.4
 *    e^(-i / 100)) plus AR(1) noise (phi 0.5, sd 0.35: a weak run's noise) over 1500 samples, 40
 *    seeds: the window starts at 300 or later in every seed, the mean over the seeds lies within
 *    0.5% of mu and the true mean inside 2 errors in >= 34; a series of 250 samples ends before
 *    the transient: not steady (before_slow), not converged; 450 samples (a window of 150 < 2 x
 *    100): not converged at any target; 1500: converged at a loose target. */
#include "analysis/steady_state.h"

#include "test_engine_common.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static double gauss(uint64_t *s) {
  const double u = ((test_rng_next(s) >> 11) + 0.5) * 0x1.0p-53,
               v = ((test_rng_next(s) >> 11) + 0.5) * 0x1.0p-53;
  return sqrt(-2.0 * log(u)) * cos(2.0 * M_PI * v);
}

/* x[i] = mu + AR(1) noise, started from its stationary distribution. */
static void ar1(double *x, long n, double mu, double phi, double sigma, uint64_t seed) {
  double e = sigma / sqrt(1.0 - phi * phi) * gauss(&seed);
  for (long i = 0; i < n; i++) {
    x[i] = mu + e;
    e = phi * e + sigma * gauss(&seed);
  }
}

static int white_noise(void) {
  const long n = 20000;
  double *x = malloc(n * sizeof *x);
  ar1(x, n, 5.0, 0.0, 1.0, 11);
  steady_state_t r;
  steady_state_analyse(x, n, &r);
  const double se = 1.0 / sqrt((double)(n - r.start));
  printf("white noise: start %ld, mean %.5f +- %.5f (exact %.5f), block %ld, plateau %d\n", r.start,
         r.avg.mean, r.avg.err, se, r.avg.block_len, r.avg.plateau);
  CHECK(r.steady && r.start <= n / 10, "white noise: truncated %ld of %ld", r.start, n);
  CHECK(r.avg.plateau, "white noise: no plateau");
  CHECK(fabs(r.avg.err / se - 1.0) < 0.1, "white noise: error %g, exact %g", r.avg.err, se);
  CHECK(fabs(r.avg.mean - 5.0) < 4 * r.avg.err, "white noise: mean %g", r.avg.mean);
  free(x);
  return 0;
}

static int correlated_noise(void) {
  const long n = 1L << 15;
  const double phi = 0.9, sigma = 1.0, tau = (1 + phi) / (2 * (1 - phi));
  const double se = sigma / ((1 - phi) * sqrt((double)n)); /* exact for large n */
  double *x = malloc(n * sizeof *x), ratio = 0, tau_est = 0;
  int covered = 0, seeds = 40;
  for (int k = 0; k < seeds; k++) {
    ar1(x, n, 1.0, phi, sigma, 1000 + k);
    const block_average_t b = block_average_plateau(x, n);
    CHECK(b.plateau, "AR(1) seed %d: no plateau", k);
    block_level_t lv[64];
    const int nl = block_levels(x, n, 2, lv, 64);
    CHECK(nl > 10, "AR(1): %d levels", nl);
    ratio += b.err / se;
    tau_est += 0.5 * (b.err / lv[0].err) * (b.err / lv[0].err);
    covered += fabs(b.mean - 1.0) < 2 * b.err;
    if (k == 0) {
      CHECK(lv[0].err < 0.3 * b.err, "AR(1): the naive error %g should be far below %g", lv[0].err,
            b.err);
    }
  }
  ratio /= seeds;
  tau_est /= seeds;
  printf("AR(1) phi %.2f: <err / exact> = %.3f, tau_int %.2f (exact %.2f), mean within 2 err in "
         "%d of %d\n",
         phi, ratio, tau_est, tau, covered, seeds);
  CHECK(ratio > 0.85 && ratio < 1.1, "AR(1): mean ratio err / exact = %g", ratio);
  CHECK(fabs(tau_est / tau - 1) < 0.2, "AR(1): tau_int %g, exact %g", tau_est, tau);
  CHECK(covered >= (int)(0.85 * seeds), "AR(1): mean inside 2 errors in %d of %d", covered, seeds);

  /* Too short for its correlation time: no plateau, never converged. */
  const long m = 600;
  ar1(x, m, 1.0, 0.995, 0.1, 5);
  steady_state_t r;
  steady_state_analyse(x, m, &r);
  printf("AR(1) phi 0.995, %ld samples: plateau %d, rel. error %.3g\n", m, r.avg.plateau,
         r.rel_err);
  CHECK(!r.avg.plateau, "short correlated series: a plateau was claimed (block %ld)",
        r.avg.block_len);
  CHECK(!steady_state_converged(&r, 0.5), "short correlated series: converged");
  free(x);
  return 0;
}

static int transient(void) {
  const long n = 12000, t0 = 3000;
  const double mu = 2.0, sigma = 0.1;
  double *x = malloc(n * sizeof *x);
  /* linear ramp from mu + 20 sigma (in units of the stationary spread) down to mu at t0 */
  ar1(x, n, mu, 0.5, sigma, 77);
  const double amp = 20 * sigma / sqrt(1 - 0.25);
  for (long i = 0; i < t0; i++) x[i] += amp * (1.0 - (double)i / t0);
  steady_state_t r;
  steady_state_analyse(x, n, &r);
  printf("ramp to step %ld: MSER-5 start %ld (steady %d), mean %.5f +- %.5f (mu %.5f)\n", t0,
         r.start, r.steady, r.avg.mean, r.avg.err, mu);
  CHECK(r.steady, "ramp: not steady");
  CHECK(r.start >= t0 - 600 && r.start <= t0 + 300, "ramp: truncation %ld, transient ends at %ld",
        r.start, t0);
  CHECK(fabs(r.avg.mean - mu) < 3 * r.avg.err, "ramp: mean %g +- %g, mu %g", r.avg.mean, r.avg.err,
        mu);
  /* exponential relaxation towards mu */
  const double tc = 500;
  ar1(x, n, mu, 0.5, sigma, 78);
  for (long i = 0; i < n; i++) x[i] += amp * exp(-(double)i / tc);
  steady_state_analyse(x, n, &r);
  printf("relaxation (time constant %.0f): MSER-5 start %ld, mean %.5f +- %.5f\n", tc, r.start,
         r.avg.mean, r.avg.err);
  CHECK(r.steady && r.start >= tc && r.start <= 6 * tc, "relaxation: truncation %ld", r.start);
  CHECK(fabs(r.avg.mean - mu) < 2 * r.avg.err + 1e-12, "relaxation: bias %g, error %g",
        r.avg.mean - mu, r.avg.err);
  /* a drift over the whole series: no steady part */
  ar1(x, n, mu, 0.5, sigma, 79);
  for (long i = 0; i < n; i++) x[i] += amp * (1.0 - (double)i / n);
  int steady;
  const long d = mser_truncation(x, n, STEADY_MSER_BATCH, &steady);
  printf("drift over the whole series: MSER-5 start %ld, steady %d\n", d, steady);
  CHECK(!steady, "drift: MSER claims a steady state from %ld", d);
  free(x);
  return 0;
}

static int convergence(void) {
  const long n = 4000;
  double *x = malloc(n * sizeof *x);
  ar1(x, n, 1.0, 0.5, 0.1, 3); /* SE of the mean ~ 0.2 / sqrt(4000) = 0.003 */
  steady_state_t r;
  steady_state_analyse(x, n, &r);
  printf("convergence: rel. error %.4g\n", r.rel_err);
  CHECK(steady_state_converged(&r, 0.01), "converged at 1%%: rel. error %g", r.rel_err);
  CHECK(!steady_state_converged(&r, 0.5 * r.rel_err), "converged below its own error");
  steady_state_analyse(x, 60, &r);
  CHECK(!steady_state_converged(&r, 0.5), "converged with %ld samples", r.n);
  free(x);
  return 0;
}

static int lucky_window(void) {
  const long n = 16000;
  double *x = malloc(n * sizeof *x), tau_sum = 0;
  for (int seed = 0; seed < 20; seed++) {
    ar1(x, 4000, 0.0, 0.9, 1.0, 100 + seed);
    tau_sum += integrated_autocorrelation_time(x, 4000);
  }
  printf("lucky window: tau_int of AR(1) phi 0.9: %.2f (exact 9.5)\n", tau_sum / 20);
  CHECK(fabs(tau_sum / 20 / 9.5 - 1) < 0.25, "tau_int %g, expected 9.5", tau_sum / 20);
  /* 1500 samples with tau_int 49.5: 15 independent samples */
  ar1(x, 1500, 1.0, 0.98, 0.02, 7);
  steady_state_t r;
  steady_state_analyse(x, 1500, &r);
  const double exact = 0.02 / (1 - 0.98) / sqrt((double)(1500 - r.start));
  printf("lucky window: phi 0.98, 1500 samples: tau_int %.1f, n_eff %.1f, err %.3g (exact %.3g)\n",
         r.tau_int, r.n_eff, r.avg.err, exact);
  CHECK(!steady_state_converged(&r, 1.0), "15 independent samples: converged");
  CHECK(r.avg.err > 0.7 * exact, "error %g below 0.7 x the exact %g", r.avg.err, exact);
  /* a ramp over the first 2000 samples, then white noise: converged only once the steady part
   * is 3x the transient */
  for (long i = 0; i < n; i++) x[i] = 0;
  uint64_t seed = 11;
  for (long i = 0; i < n; i++)
    x[i] = (i < 2000 ? 5.0 * (2000 - i) / 2000.0 : 0.0) + 1.0 + 0.05 * gauss(&seed);
  steady_state_analyse(x, 6000, &r);
  printf("lucky window: ramp 2000 + 4000 steady: start %ld, window %ld\n", r.start, r.n - r.start);
  CHECK(r.start >= 1000 && !steady_state_converged(&r, 0.5),
        "window %ld after a transient of %ld: converged", r.n - r.start, r.start);
  steady_state_analyse(x, n, &r);
  CHECK(steady_state_converged(&r, 0.01),
        "window %ld after a transient of %ld: not converged (rel %g)", r.n - r.start, r.start,
        r.rel_err);
  free(x);
  return 0;
}

static int tau_floor(void) {
  const long n = 1500;
  const double phi = 0.99, sigma = 0.01, tau = (1 + phi) / (2 * (1 - phi));
  double *x = malloc(20000 * sizeof *x), ratio = 0, tau_data = 0;
  int inside_data = 0, inside_floor = 0, converged = 0, governs = 0;
  double max_neff = 0;
  for (int seed = 0; seed < 40; seed++) {
    ar1(x, n, 1.0, phi, sigma, 300 + seed);
    steady_state_t r;
    steady_state_analyse(x, n, &r);
    tau_data += r.tau_int / 40;
    inside_data += fabs(r.avg.mean - 1.0) < 2 * r.avg.err;
    steady_state_floor_tau(&r, x, tau);
    const double exact = sigma / (1 - phi) / sqrt((double)(n - r.start));
    ratio += r.avg.err / exact / 40;
    inside_floor += fabs(r.avg.mean - 1.0) < 2 * r.avg.err;
    converged += steady_state_converged(&r, 1.0);
    governs += r.floor_governs;
    if (r.n_eff > max_neff) max_neff = r.n_eff;
  }
  printf("tau floor: AR(1) phi 0.99 (tau_int %.1f), %ld samples, 40 seeds: data's tau_int %.1f, "
         "inside 2 errors %d/40; floored: error / exact %.3f, inside %d/40, n_eff <= %.1f, floor "
         "governs %d/40, converged %d\n",
         tau, n, tau_data, inside_data, ratio, inside_floor, max_neff, governs, converged);
  CHECK(ratio > 0.8 && ratio < 1.25, "floored error / exact %g", ratio);
  CHECK(inside_floor >= 34, "floored: true mean inside 2 errors in %d of 40", inside_floor);
  CHECK(max_neff <= 7.6 && converged == 0, "floored: n_eff up to %g, %d converged", max_neff,
        converged);
  /* a floor below the data's tau_int: nothing changes */
  ar1(x, 20000, 5.0, 0.9, 1.0, 77);
  steady_state_t a, b;
  steady_state_analyse(x, 20000, &a);
  b = a;
  steady_state_floor_tau(&b, x, 1.0);
  CHECK(!b.floor_governs && b.avg.err == a.avg.err && b.n_eff == a.n_eff && b.tau_floor == 1.0,
        "a floor of 1 sample below tau_int %g changed the analysis", a.tau_int);
  free(x);
  return 0;
}

/* mu (1 + a e^(-i / tau)) plus AR(1) noise. */
static void slow_series(double *x, long n, double a, double tau, uint64_t seed) {
  ar1(x, n, 1.0, 0.5, 0.3, seed);
  for (long i = 0; i < n; i++) x[i] += a * exp(-(double)i / tau);
}

static int slow_mode(void) {
  const long n = 1500;
  const double tau = 100, a = 0.4;
  double *x = malloc(n * sizeof *x);
  double bias_plain = 0, bias_floor = 0;
  int inside_plain = 0, inside_floor = 0, late = 1;
  for (int seed = 0; seed < 40; seed++) {
    slow_series(x, n, a, tau, 900 + (uint64_t)seed);
    steady_state_t p, f;
    steady_state_analyse(x, n, &p);
    steady_state_analyse_from(x, n, tau, &f);
    bias_plain += (p.avg.mean - 1.0) / 40;
    bias_floor += (f.avg.mean - 1.0) / 40;
    inside_plain += fabs(p.avg.mean - 1.0) <= 2 * p.avg.err;
    inside_floor += fabs(f.avg.mean - 1.0) <= 2 * f.avg.err;
    late &= f.start >= 300 && !f.before_slow && f.steady == p.steady;
  }
  printf("slow mode: amplitude %.1f, tau %.0f samples, %ld samples, 40 seeds: MSER alone bias "
         "%+.4f, inside 2 errors %d/40; floored at 3 tau: bias %+.4f, inside %d/40\n",
         a, tau, n, bias_plain, inside_plain, bias_floor, inside_floor);
  CHECK(late, "a floored window started before 3 tau = 300 samples");
  CHECK(fabs(bias_floor) < 0.005, "floored mean off mu by %g on average", bias_floor);
  CHECK(inside_floor >= 34, "floored: true mean inside 2 errors in %d of 40", inside_floor);
  steady_state_t r;
  slow_series(x, 250, a, tau, 7);
  steady_state_analyse_from(x, 250, tau, &r);
  CHECK(r.before_slow && !r.steady && !steady_state_converged(&r, 1.0),
        "250 samples, tau 100: before_slow %d steady %d", r.before_slow, r.steady);
  slow_series(x, 450, a, tau, 8);
  steady_state_analyse_from(x, 450, tau, &r);
  CHECK(!r.before_slow && r.start >= 300 && !steady_state_converged(&r, 1.0),
        "450 samples (window %ld < 2 tau): converged at target 1", r.n - r.start);
  slow_series(x, n, a, tau, 9);
  steady_state_analyse_from(x, n, tau, &r);
  CHECK(steady_state_converged(&r, 1.0),
        "1500 samples: not converged at target 1 (start %ld, "
        "n_eff %g, plateau %d)",
        r.start, r.n_eff, r.avg.plateau);
  free(x);
  return 0;
}

int main(void) {
  int fails = white_noise() + correlated_noise() + transient() + convergence() + lucky_window() +
              tau_floor() + slow_mode();
  printf(fails ? "FAILED\n" : "ok\n");
  return fails ? 1 : 0;
}
