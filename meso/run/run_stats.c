/* Sampling-window statistics of a run (see run_stats.h). */
#include "run/run_stats.h"

#include <stdlib.h>
#include <string.h>

const char *const run_stat_names[STAT_COUNT] = {"T",   "KE",  "Pxx", "Pyy", "Pzz",
                                                "Pxy", "Pxz", "Pyz", "p",   "surface_tension"};

void run_stats_init(run_stats_t *st, const scene_t *s, long first, long last, int nranks) {
  memset(st, 0, sizeof *st);
  st->first_step = first;
  st->last_step = last;
  st->nranks = nranks;
  if (s->profile.nbins > 0) {
    st->window_start = st->sample_from = s->profile.start;
    st->sample_every = s->profile.every;
    st->gamma_axis = s->profile.axis;
    st->gamma_len = s->box_hi[s->profile.axis] - s->box_lo[s->profile.axis];
  } else {
    st->window_start = first + (last - first) / 2; /* as planned */
    /* a run that may stop early on its flux error samples from the start, and run_stats_finish
     * keeps the second half of what it ran; the others sample the planned second half only */
    st->sample_from = s->target_error > 0 ? first : st->window_start;
    st->sample_every = s->thermo.every > 0 ? s->thermo.every : 10;
    st->gamma_axis = -1;
  }
}

int run_stats_wants(const run_stats_t *st, long step) {
  return step > st->first_step && step >= st->sample_from && step % st->sample_every == 0;
}

/* Multiples of `every` in (first, b). */
static long multiples_between(long first, long b, long every) {
  return b > first + 1 ? (b - 1) / every - first / every : 0;
}

void run_stats_finish(run_stats_t *st, long last) {
  if (st->gamma_axis >= 0 || st->sample_from != st->first_step ||
      st->window_start == st->first_step)
    return; /* a profile's window, or the planned second half sampled */
  st->window_start = st->first_step + (last - st->first_step) / 2;
  const long drop = multiples_between(st->first_step, st->window_start, st->sample_every);
  for (int k = 0; k < STAT_COUNT; k++) {
    series_t *x = &st->s[k];
    const long d = drop < x->n ? drop : x->n;
    if (d > 0) memmove(x->x, x->x + d, (size_t)(x->n - d) * sizeof *x->x);
    x->n -= d;
  }
}

void run_stats_add(run_stats_t *st, const thermo_t *t) {
  const double *P = t->pressure;
  series_push(&st->s[STAT_T], t->temperature);
  series_push(&st->s[STAT_KE], t->ke);
  for (int k = 0; k < 6; k++) series_push(&st->s[STAT_PXX + k], P[k]);
  series_push(&st->s[STAT_P], (P[0] + P[1] + P[2]) / 3);
  if (st->gamma_axis >= 0) {
    /* gamma = (L_n / 2) (P_nn - (P_t1 + P_t2) / 2): two interfaces of a slab in a periodic box
     * (physics.md section 2). */
    const int n = st->gamma_axis;
    const double pt = 0.5 * (P[0] + P[1] + P[2] - P[n]);
    series_push(&st->s[STAT_GAMMA], 0.5 * st->gamma_len * (P[n] - pt));
  }
}

void run_stats_free(run_stats_t *st) {
  for (int k = 0; k < STAT_COUNT; k++) series_free(&st->s[k]);
  series_free(&st->core_density);
  free(st->busy_rank_since_move);
  free(st->busy_rank_run);
  st->busy_rank_since_move = st->busy_rank_run = NULL;
}
