/* Steady state of a time series (the flux q of a flow run) and its error bar:
 *  1. the end of the transient by MSER-5 (White, Simulation 69, 323 (1997); White, Cobb & Spratt,
 *     Proc. Winter Simulation Conf. 2000; Franklin & White, WSC 2008): batch means of 5 samples
 *     Z_1..Z_k; the truncation d (in batches) minimises
 *         MSER(d) = sum_{j > d} (Z_j - mean_{j > d} Z)^2 / (k - d)^2,
 *     the squared standard error of the mean left after dropping the first d batches, over
 *     d <= k / 2. A minimum found in the second half of the range is MSER's sign that the series
 *     has not reached a steady state within its length (steady = 0);
 *  2. the mean after the truncation and its standard error by block averaging, the block length
 *     chosen from the data (the plateau of the blocked error, analysis/block_average.h);
 *  3. the integrated autocorrelation time tau_int of that window (Sokal's automatic window,
 *     M >= 6 tau_int; Madras & Sokal, J. Stat. Phys. 50, 109 (1988)), its error
 *     s sqrt(2 tau_int / m) and the effective sample count m / (2 tau_int). The reported error is
 *     the larger of the two estimates.
 * A converged verdict (the early stop of run.target_error) also asks for a window at least
 * STEADY_WINDOW_OVER_TRANSIENT times the transient it follows and STEADY_MIN_EFFECTIVE effective
 * samples: a slowly fluctuating flux (a channel's momentum relaxes over h^2 / (pi^2 nu)) can show a
 * short, quiet stretch whose block error is far too small; seen in a slit campaign that stopped
 * 18% low with a 0.9% error bar (docs/permeability.md).
 *
 * A transient that the data of one run cannot show is floored from physics
 * (steady_state_analyse_from): a slow mode known to decay as exp(-t / tau_slow) is left out for
 * STEADY_SLOW_TRANSIENT_TIMES tau_slow, and a converged verdict asks for at least
 * STEADY_SLOW_WINDOW_TIMES tau_slow of data after it. For a flow run through a compressible liquid
 * the mode is the pressure diffusion that builds the pressure field of the flow (run/run_flux.c):
 * its relative amplitude does not depend on the forcing, so MSER finds it in the strongest run of a
 * campaign and misses it in the weakest, whose noise hides a bias of 10-15% (Berea crops at 1 rc
 * per voxel, docs/permeability.md). */
#ifndef MESO_ANALYSIS_STEADY_STATE_H
#define MESO_ANALYSIS_STEADY_STATE_H

#include "analysis/block_average.h"

#define STEADY_MSER_BATCH 5
/* A converged verdict needs at least this many samples after the truncation, ... */
#define STEADY_MIN_SAMPLES 100
/* ... a window at least this many times the truncated transient, ... */
#define STEADY_WINDOW_OVER_TRANSIENT 3
/* ... and at least this many effective (independent) samples. */
#define STEADY_MIN_EFFECTIVE 30
/* A known slow mode: its first STEADY_SLOW_TRANSIENT_TIMES relaxation times are left out (what is
 * left of an amplitude a is a e^-3, 1.5% of q for a = 0.3), and a converged verdict needs
 * STEADY_SLOW_WINDOW_TIMES of them after that. */
#define STEADY_SLOW_TRANSIENT_TIMES 3.0
#define STEADY_SLOW_WINDOW_TIMES 2.0

typedef struct {
  long n;              /* samples analysed */
  long start;          /* first sample of the steady part (the MSER-5 truncation) */
  int steady;          /* 1: MSER's minimum lies in the first half of the series */
  block_average_t avg; /* mean and error of x[start..n) (block_average_plateau) */
  double tau_int;      /* integrated autocorrelation time of x[start..n), in samples */
  double n_eff;        /* effective samples: (n - start) / (2 tau_int) */
  double rel_err;      /* avg.err / |avg.mean| (inf when the mean is 0); avg.err is the larger of
                          the block error and the autocorrelation error */
  double tau_floor;    /* a physical lower bound on tau_int in samples (steady_state_floor_tau; 0:
                          none applied) */
  int floor_governs;   /* 1: the floor was above the data's tau_int and set the error and n_eff */
  long mser_start;     /* MSER-5's truncation (start is the larger of it and the slow floor) */
  double tau_slow;     /* relaxation time of a known slow mode, in samples (0: none) */
  int slow_governs;    /* 1: the slow mode's floor, not MSER, set start */
  int before_slow;     /* 1: the series ends before the slow mode's transient does (steady = 0) */
} steady_state_t;

/* MSER truncation with batches of `batch` samples: the number of samples to drop (a multiple of
 * batch); *steady as above. Fewer than 2 batches: 0 dropped, *steady = 0. */
long mser_truncation(const double *x, long n, int batch, int *steady);

/* MSER-5, then the block average of what follows. */
void steady_state_analyse(const double *x, long n, steady_state_t *out);

/* The same with a slow mode of relaxation time tau_slow samples (<= 0 or not finite: none): the
 * window starts no earlier than STEADY_SLOW_TRANSIENT_TIMES tau_slow. A series that ends before
 * that, or leaves fewer than 2 samples after it, is analysed from MSER's start but is not steady
 * (before_slow = 1). */
void steady_state_analyse_from(const double *x, long n, double tau_slow, steady_state_t *out);

/* Integrated autocorrelation time (samples) of x[0..n) by Sokal's automatic window; a series
 * longer than 4096 samples is first reduced to 4096 batch means (then tau_batch x batch, an upper
 * bound in samples). */
double integrated_autocorrelation_time(const double *x, long n);

/* A lower bound on the correlation time that the series may be too short to show: a window of a
 * few times a slow mode's relaxation time makes its own autocorrelation read short (the mean is
 * taken over the same window), and the error with it. With tau_floor > tau_int (samples) the
 * analysis of x[0..s->n) is redone with tau_floor: error sqrt(var 2 tau_floor / m), n_eff =
 * m / (2 tau_floor) for the m samples of the window, var their variance (the larger error and the
 * smaller n_eff are kept). For a flow run the bound is the Darcy relaxation time of the mean flow,
 * by Green-Kubo the integrated autocorrelation time of q's thermal fluctuations (run/run_flux.c).
 * tau_floor <= 0 or not finite: nothing changes. */
void steady_state_floor_tau(steady_state_t *s, const double *x, double tau_floor);

/* Another series sampled with the one `ref` analysed (a part of it: one liquid's flux): its mean
 * and error over ref's window [ref->start, n), with ref's correlation-time floor (the verdict
 * fields are ref's). */
void steady_state_window(const double *x, long n, const steady_state_t *ref, steady_state_t *out);

/* Whether the analysed series meets a relative error target: steady, a plateau of the blocked
 * error, at least STEADY_MIN_SAMPLES samples used, a window >= STEADY_WINDOW_OVER_TRANSIENT x
 * MSER's transient and >= STEADY_SLOW_WINDOW_TIMES x tau_slow, >= STEADY_MIN_EFFECTIVE effective
 * samples and rel_err <= target. */
int steady_state_converged(const steady_state_t *s, double target);

#endif
