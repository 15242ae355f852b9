/* Density collapse / cavitation guard (density_guard.h). */
#include "analysis/density_guard.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static long bin_of(const density_guard_t *g, const double x[3]) {
  long b = 0, stride = 1;
  for (int d = 0; d < 3; d++) {
    int i = (int)floor((x[d] - g->lo[d]) / g->h[d]);
    if (i < 0) i = 0;
    if (i >= g->n[d]) i = g->n[d] - 1;
    b += i * stride;
    stride *= g->n[d];
  }
  return b;
}

int density_guard_init(density_guard_t *g, sim_t *sim, const penetration_map_t *map) {
  memset(g, 0, sizeof *g);
  const scene_t *s = sim_scene(sim);
  if (s->guard.density_every <= 0) return 0;
  g->every = s->guard.density_every;
  g->fraction = s->guard.density_fraction;
  g->nbins = 1;
  for (int d = 0; d < 3; d++) {
    const double L = s->box_hi[d] - s->box_lo[d];
    g->n[d] = (int)floor(L / s->guard.density_bin);
    if (g->n[d] < 1) g->n[d] = 1;
    g->lo[d] = s->box_lo[d];
    g->h[d] = L / g->n[d];
    g->nbins *= g->n[d];
  }
  g->pore = calloc((size_t)g->nbins, sizeof *g->pore);
  g->count = calloc((size_t)g->nbins, sizeof *g->count);
  g->ref = calloc((size_t)g->nbins, sizeof *g->ref);
  if (!g->pore || !g->count || !g->ref) {
    fprintf(stderr, "mdpore: out of memory for the density guard (%ld bins)\n", g->nbins);
    density_guard_free(g);
    return -1;
  }
  const double vbin = g->h[0] * g->h[1] * g->h[2];
  if (map && map->on) { /* pore volume: the pore voxels whose centre lies in the bin */
    const double hv = map->h, v3 = hv * hv * hv;
    for (int k = 0; k < map->n[2]; k++)
      for (int j = 0; j < map->n[1]; j++)
        for (int i = 0; i < map->n[0]; i++) {
          const size_t v = (size_t)i + (size_t)map->n[0] * ((size_t)j + (size_t)map->n[1] * k);
          if (map->depth[v] > 0.0f) continue;
          const double x[3] = {g->lo[0] + (i + 0.5) * hv, g->lo[1] + (j + 0.5) * hv,
                               g->lo[2] + (k + 0.5) * hv};
          g->pore[bin_of(g, x)] += v3;
        }
  } else {
    for (long b = 0; b < g->nbins; b++) g->pore[b] = vbin;
  }
  /* mostly solid bins are never watched */
  for (long b = 0; b < g->nbins; b++)
    if (g->pore[b] < 0.5 * vbin) g->pore[b] = 0;
  g->on = 1;
  return 0;
}

int density_guard_due(const density_guard_t *g, long step) {
  return g->on && step % g->every == 0;
}

/* The bin's region [lo, hi) per axis, and its index triple. */
static void region(const density_guard_t *g, long b, int idx[3], double lo[3], double hi[3]) {
  idx[0] = (int)(b % g->n[0]);
  idx[1] = (int)((b / g->n[0]) % g->n[1]);
  idx[2] = (int)(b / ((long)g->n[0] * g->n[1]));
  for (int d = 0; d < 3; d++) {
    lo[d] = g->lo[d] + idx[d] * g->h[d];
    hi[d] = lo[d] + g->h[d];
  }
}

int density_guard_check(density_guard_t *g, sim_t *sim, long step, char *msg, size_t len) {
  if (!density_guard_due(g, step)) return 0;
  const double t0 = MPI_Wtime();
  g->checks++;
  const scene_t *s = sim_scene(sim);
  const particles_t *p = sim_particles(sim);
  memset(g->count, 0, (size_t)g->nbins * sizeof *g->count);
  for (int i = 0; i < p->n_local; i++) {
    if (s->species[p->species[i]].frozen) continue;
    const double x[3] = {p->x[0][i], p->x[1][i], p->x[2][i]};
    g->count[bin_of(g, x)]++;
  }
  MPI_Allreduce(MPI_IN_PLACE, g->count, (int)g->nbins, MPI_LONG, MPI_SUM, sim_comm(sim));
  if (!g->have_ref) { /* the first check: the reference */
    double n = 0, v = 0;
    for (long b = 0; b < g->nbins; b++)
      if (g->pore[b] > 0) {
        n += (double)g->count[b];
        v += g->pore[b];
      }
    g->mean_ref = v > 0 ? n / v : 0;
    g->watched = 0;
    for (long b = 0; b < g->nbins; b++) {
      const double rho = g->pore[b] > 0 ? g->count[b] / g->pore[b] : 0;
      const int watch = g->pore[b] > 0 && rho >= g->fraction * g->mean_ref &&
                        g->mean_ref * g->pore[b] >= DENSITY_GUARD_MIN_COUNT;
      g->ref[b] = watch ? rho : -1.0;
      g->watched += watch;
    }
    g->have_ref = 1;
    g->seconds += MPI_Wtime() - t0;
    return 0;
  }
  long worst = -1;
  double worst_rho = INFINITY;
  for (long b = 0; b < g->nbins; b++) {
    if (g->ref[b] < 0) continue;
    const double rho = g->count[b] / g->pore[b];
    if (rho < worst_rho) {
      worst_rho = rho;
      worst = b;
    }
  }
  g->seconds += MPI_Wtime() - t0;
  if (worst < 0 || worst_rho >= g->fraction * g->mean_ref) return 0;
  int idx[3];
  double lo[3], hi[3];
  region(g, worst, idx, lo, hi);
  snprintf(msg, len,
           "mdpore: step %ld: density collapse (cavitation) in bin (%d, %d, %d) of %d x %d x %d, "
           "region [%g, %g) x [%g, %g) x [%g, %g): fluid density %.3g (%ld particles), below "
           "guard.density_fraction %g of the mean fluid density %.3g (it held %.3g at the first "
           "check). The fluid tore apart: check the pressure (mDPD B and A, the fill density "
           "against the liquid's coexistence density), a smaller body force or run.dt, or a "
           "larger guard.density_bin if the pores are narrow",
           step, idx[0], idx[1], idx[2], g->n[0], g->n[1], g->n[2], lo[0], hi[0], lo[1], hi[1],
           lo[2], hi[2], worst_rho, g->count[worst], g->fraction, g->mean_ref, g->ref[worst]);
  return 1;
}

void density_guard_free(density_guard_t *g) {
  free(g->pore);
  free(g->count);
  free(g->ref);
  memset(g, 0, sizeof *g);
}
