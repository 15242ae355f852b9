/* Counting sort of particles into bins (see cell_list.h). The order inside a bin is the particle
 * index order, so the traversal order, and with it every per-particle force sum, is deterministic.
 */
#include "cell_list.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

static int grow_int(int **a, int n) {
  int *q = realloc(*a, (size_t)n * sizeof(int));
  if (!q) return -1;
  *a = q;
  return 0;
}

static int grow_double(double **a, int n) {
  double *q = realloc(*a, (size_t)n * sizeof(double));
  if (!q) return -1;
  *a = q;
  return 0;
}

void cell_list_free(cell_list_t *cl) {
  free(cl->start);
  free(cl->idx);
  free(cl->cell_of);
  free(cl->px);
  free(cl->py);
  free(cl->pz);
  memset(cl, 0, sizeof *cl);
}

static int bin_of(const cell_list_t *cl, int d, double x) {
  const double s = (x - cl->origin[d]) * cl->inv_size[d];
  /* Ghost images can sit a rounding error outside the ghost layer; NaN goes to bin 0 (caught
   * later). */
  if (!(s >= 0.0)) return 0;
  const int b = (int)s;
  return b < cl->nb[d] ? b : cl->nb[d] - 1;
}

int cell_list_build(cell_list_t *cl, const particles_t *p, const double lo[3], const double hi[3],
                    double rcut) {
  const int n = p->n_local + p->n_ghost;
  /* the scene's sizes were checked against memory; a grid the int index cannot count is refused */
  double cells = 1.0;
  for (int d = 0; d < 3; d++) {
    const double extent = hi[d] - lo[d] + 2.0 * rcut;
    const double per_axis = rcut > 0 ? extent / rcut : 1.0;
    cells *= per_axis < 1.0 ? 1.0 : per_axis;
  }
  if (!(cells < (double)INT_MAX - 1.0)) return -1;
  cl->ncell = 1;
  for (int d = 0; d < 3; d++) {
    const double extent = hi[d] - lo[d] + 2.0 * rcut;
    int nb = rcut > 0 ? (int)(extent / rcut) : 1; /* bin width extent / nb >= rcut */
    if (nb < 1) nb = 1;
    cl->nb[d] = nb;
    cl->origin[d] = lo[d] - rcut;
    cl->inv_size[d] = nb / extent;
    cl->ncell *= nb;
  }
  if (cl->ncell + 1 > cl->cap_cells) {
    if (grow_int(&cl->start, cl->ncell + 1)) return -1;
    cl->cap_cells = cl->ncell + 1;
  }
  if (n > cl->cap_part) {
    const int cap = n + n / 4 + 64;
    if (grow_int(&cl->idx, cap) || grow_int(&cl->cell_of, cap) || grow_double(&cl->px, cap) ||
        grow_double(&cl->py, cap) || grow_double(&cl->pz, cap))
      return -1;
    cl->cap_part = cap;
  }
  memset(cl->start, 0, (size_t)(cl->ncell + 1) * sizeof(int));
  for (int i = 0; i < n; i++) {
    const int c = bin_of(cl, 0, p->x[0][i]) +
                  cl->nb[0] * (bin_of(cl, 1, p->x[1][i]) + cl->nb[1] * bin_of(cl, 2, p->x[2][i]));
    cl->cell_of[i] = c;
    cl->start[c + 1]++;
  }
  cl->max_per_cell = 0;
  for (int c = 0; c < cl->ncell; c++) {
    if (cl->start[c + 1] > cl->max_per_cell) cl->max_per_cell = cl->start[c + 1];
    cl->start[c + 1] += cl->start[c];
  }
  /* Fill using start[] as running cursors, then shift back. */
  for (int i = 0; i < n; i++) {
    const int slot = cl->start[cl->cell_of[i]]++;
    cl->idx[slot] = i;
    cl->px[slot] = p->x[0][i];
    cl->py[slot] = p->x[1][i];
    cl->pz[slot] = p->x[2][i];
  }
  for (int c = cl->ncell; c > 0; c--) cl->start[c] = cl->start[c - 1];
  cl->start[0] = 0;
  return 0;
}
