/* Per-step neighbour lists (cpu_passes.h): one scan of the 27 bins around each owned particle,
 * shared by the density and the force pass. Lists are in bin order, so the summation order of each
 * particle is fixed by the configuration, not by the thread count. */
#include "cpu_passes.h"
#include "neighbour_bins.h"

#include <stdio.h>
#include <stdlib.h>

void cpu_neighbours_free(nlist_t *nl) {
  free(nl->count);
  free(nl->count_near);
  free(nl->slot);
  nl->count = NULL;
  nl->count_near = NULL;
  nl->slot = NULL;
  nl->cap = 0;
  nl->cap_n = 0;
}

static int reserve(nlist_t *nl, int n, int stride) {
  if (n > nl->cap_n) {
    int *c = realloc(nl->count, (size_t)n * sizeof(int));
    if (!c) return -1;
    nl->count = c;
    c = realloc(nl->count_near, (size_t)n * sizeof(int));
    if (!c) return -1;
    nl->count_near = c;
    nl->cap_n = n;
  }
  const size_t need = (size_t)n * (size_t)stride;
  if (need > nl->cap) {
    int *s = realloc(nl->slot, need * sizeof(int));
    if (!s) return -1;
    nl->slot = s;
    nl->cap = need;
  }
  nl->stride = stride;
  return 0;
}

/* A static frozen particle under a valid density cache (cpu_passes.h): its non-static partners
 * within near2 (rd), in bin order; rows holding no non-static particle are skipped unscanned. */
static int gather_dynamic_near(const cell_list_t *cl, const density_cache_t *dc, int cell,
                               double xi, double yi, double zi, double near2, int *out) {
  int lo[9], hi[9];
  const int nrows = neighbour_rows(cl, cell, lo, hi);
  const int *pre = dc->dynamic_prefix;
  int m = 0;
  for (int r = 0; r < nrows; r++) {
    if (pre[hi[r]] == pre[lo[r]]) continue; /* only static particles in this row */
    for (int t = lo[r]; t < hi[r]; t++) {
      const double dx = xi - cl->px[t], dy = yi - cl->py[t], dz = zi - cl->pz[t];
      out[m] = t;
      m += ((dx * dx + dy * dy + dz * dz) < near2) & (pre[t + 1] - pre[t]);
    }
  }
  return m;
}

int cpu_neighbours_build(nlist_t *nl, const plan_t *plan, const particles_t *p,
                         const cell_list_t *cl, const density_cache_t *dc) {
  const int cached = dc && dc->valid;
  double cut2[SCENE_MAX_SPECIES] = {0}, near2[SCENE_MAX_SPECIES] = {0};
  for (int a = 0; a < plan->n_species; a++)
    for (int b = 0; b < plan->n_species; b++) {
      if (plan->coef[a][b].cut2 > cut2[a]) cut2[a] = plan->coef[a][b].cut2;
      if (plan->coef[a][b].rd2 > near2[a]) near2[a] = plan->coef[a][b].rd2;
    }
  const int nslots = p->n_local + p->n_ghost, n_local = p->n_local;
  int stride = nl->stride > 0 ? nl->stride : 64;
  const size_t scratch = (size_t)27 * (size_t)cl->max_per_cell + 1;
  for (;;) {
    if (reserve(nl, n_local > 0 ? n_local : 1, stride)) return -1;
    int most = 0, fail = 0;
#pragma omp parallel reduction(max : most) reduction(| : fail)
    {
      int *cand = malloc(2 * scratch * sizeof(int));
      if (!cand) fail = 1;
#pragma omp for schedule(static)
      for (int q = 0; q < nslots; q++) {
        const int i = cl->idx[q];
        if (i >= n_local || !cand) continue;
        const double xi = cl->px[q], yi = cl->py[q], zi = cl->pz[q];
        if (cached && plan->static_frozen[p->species[i]]) {
          const int m =
              gather_dynamic_near(cl, dc, cl->cell_of[i], xi, yi, zi, near2[p->species[i]], cand);
          if (m > most) most = m;
          if (m > stride) continue;
          int *out = nl->slot + (size_t)i * (size_t)stride;
          for (int k = 0; k < m; k++) out[k] = cand[k];
          nl->count[i] = nl->count_near[i] = m;
          continue;
        }
        const int m =
            gather_candidates(cl, cl->cell_of[i], q, xi, yi, zi, cut2[p->species[i]], cand);
        if (m > most) most = m;
        if (m > stride) continue; /* list too short: redone with a larger stride */
        /* Partition (stable): neighbours within rd first, then the rest. */
        int *out = nl->slot + (size_t)i * (size_t)stride;
        const double n2 = near2[p->species[i]];
        int *far = cand + scratch; /* second half of the scratch buffer */
        int nn = 0, nf = 0;
        for (int k = 0; k < m; k++) {
          const int t = cand[k];
          const double dx = xi - cl->px[t], dy = yi - cl->py[t], dz = zi - cl->pz[t];
          const int is_near = dx * dx + dy * dy + dz * dz < n2;
          out[nn] = t; /* branch-free: store in both, advance one */
          far[nf] = t;
          nn += is_near;
          nf += !is_near;
        }
        for (int k = 0; k < nf; k++) out[nn + k] = far[k];
        nl->count[i] = m;
        nl->count_near[i] = nn;
      }
      free(cand);
    }
    if (fail) return -1;
    if (most <= stride) return 0;
    stride = most + most / 4 + 8;
  }
}
