/* Cartesian decomposition of the box over the ranks of a communicator. */
#include "decomp.h"
#include "physics/verlet.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char axis_name[3] = {'x', 'y', 'z'};

int decomp_dims(const scene_t *s, int nranks, int dims[3], char *err, size_t errlen) {
  int fixed = 1;
  for (int d = 0; d < 3; d++) {
    dims[d] = s->procs[d] > 0 ? s->procs[d] : 0;
    if (dims[d] > 0) fixed *= dims[d];
  }
  if (nranks % fixed != 0 || (dims[0] && dims[1] && dims[2] && fixed != nranks)) {
    snprintf(err, errlen, "%s: procs = [%d, %d, %d] does not fit %d MPI ranks", s->file,
             s->procs[0], s->procs[1], s->procs[2], nranks);
    return -1;
  }
  if (MPI_Dims_create(nranks, 3, dims) != MPI_SUCCESS) {
    snprintf(err, errlen, "%s: cannot arrange %d MPI ranks as procs = [%d, %d, %d]", s->file,
             nranks, s->procs[0], s->procs[1], s->procs[2]);
    return -1;
  }
  return 0;
}

double decomp_bound(const decomp_t *dc, int d, int c) {
  return c >= dc->dims[d] ? dc->box_hi[d] : dc->cut[d][c];
}

/* The uniform cut c of dims along axis d: the same expression on every rank. */
static double uniform_cut(const decomp_t *dc, int d, int c) {
  return c >= dc->dims[d] ? dc->box_hi[d] : dc->box_lo[d] + c * (dc->L[d] / dc->dims[d]);
}

int decomp_set_cuts(decomp_t *dc, int d, const double *cuts, char *err, size_t errlen) {
  const int m = dc->dims[d];
  if (cuts[0] != dc->box_lo[d] || cuts[m] != dc->box_hi[d]) {
    snprintf(err, errlen,
             "cuts along %c: expected the box bounds [%g, %g] at the ends (got %g, %g)",
             axis_name[d], dc->box_lo[d], dc->box_hi[d], cuts[0], cuts[m]);
    return -1;
  }
  for (int c = 0; c < m; c++)
    if (!(cuts[c + 1] - cuts[c] >= dc->rcut)) {
      snprintf(err, errlen,
               "cuts along %c: slab %d is [%g, %g), thinner than the ghost cutoff %g (expected "
               "increasing cuts at least rcut apart)",
               axis_name[d], c, cuts[c], cuts[c + 1], dc->rcut);
      return -1;
    }
  memcpy(dc->cut[d], cuts, (size_t)(m + 1) * sizeof *cuts);
  dc->lo[d] = decomp_bound(dc, d, dc->coords[d]);
  dc->hi[d] = decomp_bound(dc, d, dc->coords[d] + 1);
  return 0;
}

int decomp_coord_of(const decomp_t *dc, int d, double x) {
  int a = 0, b = dc->dims[d] - 1; /* the last c with cut[c] <= x, by bisection */
  while (a < b) {
    const int mid = (a + b + 1) / 2;
    if (dc->cut[d][mid] <= x)
      a = mid;
    else
      b = mid - 1;
  }
  return a;
}

int decomp_create(decomp_t *dc, const scene_t *s, MPI_Comm comm, double rcut, char *err,
                  size_t errlen) {
  memset(dc, 0, sizeof *dc);
  dc->cart = MPI_COMM_NULL;
  int nranks;
  MPI_Comm_size(comm, &nranks);
  if (decomp_dims(s, nranks, dc->dims, err, errlen)) return -1;
  dc->rcut = rcut;
  for (int d = 0; d < 3; d++) {
    dc->periodic[d] = s->periodic[d] != 0;
    dc->box_lo[d] = s->box_lo[d];
    dc->box_hi[d] = s->box_hi[d];
    dc->L[d] = s->box_hi[d] - s->box_lo[d];
    const double width = dc->L[d] / dc->dims[d];
    if (width < rcut) {
      snprintf(
          err, errlen,
          "%s: subdomain along %c is %g wide (box %g / %d ranks), thinner than the ghost cutoff "
          "%g: use fewer ranks along %c (scene procs) or a larger box",
          s->file, axis_name[d], width, dc->L[d], dc->dims[d], rcut, axis_name[d]);
      return -1;
    }
  }
  /* No reordering: rank numbers stay those of comm, so outputs and tests can rely on them. */
  MPI_Cart_create(comm, 3, dc->dims, dc->periodic, 0, &dc->cart);
  MPI_Comm_rank(dc->cart, &dc->rank);
  dc->nranks = nranks;
  MPI_Cart_coords(dc->cart, dc->rank, 3, dc->coords);
  for (int d = 0; d < 3; d++) {
    dc->cut[d] = malloc((size_t)(dc->dims[d] + 1) * sizeof(double));
    if (!dc->cut[d]) {
      snprintf(err, errlen, "out of memory for the cuts of %d subdomains along %c", dc->dims[d],
               axis_name[d]);
      return -1;
    }
    for (int c = 0; c <= dc->dims[d]; c++) dc->cut[d][c] = uniform_cut(dc, d, c);
    MPI_Cart_shift(dc->cart, d, 1, &dc->nbr[d][0], &dc->nbr[d][1]);
    dc->lo[d] = decomp_bound(dc, d, dc->coords[d]);
    dc->hi[d] = decomp_bound(dc, d, dc->coords[d] + 1);
  }
  return 0;
}

void decomp_free(decomp_t *dc) {
  if (dc->cart != MPI_COMM_NULL) MPI_Comm_free(&dc->cart);
  dc->cart = MPI_COMM_NULL;
  for (int d = 0; d < 3; d++) {
    free(dc->cut[d]);
    dc->cut[d] = NULL;
  }
}

void decomp_wrap(const decomp_t *dc, double x[3]) {
  for (int d = 0; d < 3; d++)
    if (dc->periodic[d]) x[d] = box_wrap(x[d], dc->box_lo[d], dc->box_hi[d], dc->L[d]);
}

int decomp_owns(const decomp_t *dc, const double x[3]) {
  for (int d = 0; d < 3; d++)
    if (!(x[d] >= dc->lo[d] && x[d] < dc->hi[d])) return 0;
  return 1;
}
