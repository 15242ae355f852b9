/* Ghost exchange in three stages with periodic images (see ghosts.h). One rank along an axis
 * exchanges with itself, so periodic images never need minimum-image arithmetic in the force loops.
 */
#include "ghosts.h"
#include "particle_store.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  int64_t id;
  int32_t species, pad;
  double x[3], v[3];
} ghost_rec_t;

size_t ghosts_record_bytes(void) {
  return sizeof(ghost_rec_t);
}

void ghosts_free(ghost_plan_t *g) {
  for (int d = 0; d < 3; d++)
    for (int k = 0; k < 2; k++) free(g->send_idx[d][k]);
  xbuf_free(&g->sbuf);
  xbuf_free(&g->rbuf);
  memset(g, 0, sizeof *g);
}

static int push_index(ghost_plan_t *g, int d, int k, int i) {
  if (g->n_send[d][k] == g->cap_send[d][k]) {
    int cap = g->cap_send[d][k] ? 2 * g->cap_send[d][k] : 256;
    int *q = realloc(g->send_idx[d][k], (size_t)cap * sizeof(int));
    if (!q) return -1;
    g->send_idx[d][k] = q;
    g->cap_send[d][k] = cap;
  }
  g->send_idx[d][k][g->n_send[d][k]++] = i;
  return 0;
}

/* Send the particles listed for (d, k) to neighbour k, append what comes from the opposite one. */
static int exchange_direction(ghost_plan_t *g, const decomp_t *dc, particles_t *p, int d, int k,
                              int with_v) {
  double **vel = p->vpred[0] ? p->vpred : p->v;
  /* Crossing the periodic boundary: going down from the first subdomain the image sits at x + L,
   * going up from the last one at x - L. */
  double shift = 0.0;
  if (k == 0 && dc->coords[d] == 0) shift = dc->L[d];
  if (k == 1 && dc->coords[d] == dc->dims[d] - 1) shift = -dc->L[d];
  const int n = g->n_send[d][k];
  if (xbuf_reserve(&g->sbuf, (size_t)n * sizeof(ghost_rec_t))) return -1;
  ghost_rec_t *out = (ghost_rec_t *)g->sbuf.data;
  for (int s = 0; s < n; s++) {
    const int i = g->send_idx[d][k][s];
    out[s].id = p->id[i];
    out[s].species = p->species[i];
    out[s].pad = 0;
    for (int c = 0; c < 3; c++) {
      out[s].x[c] = p->x[c][i];
      out[s].v[c] = with_v ? vel[c][i] : 0.0;
    }
    out[s].x[d] += shift;
  }
  const int dest = dc->nbr[d][k], src = dc->nbr[d][1 - k];
  int rc = exchange_bytes(dc->cart, dc->rank, dest, src, out, (size_t)n * sizeof(ghost_rec_t),
                          &g->rbuf, 100 + 4 * d + 2 * k);
  const int m = rc ? 0 : (int)(g->rbuf.size / sizeof(ghost_rec_t));
  const int first = p->n_local + p->n_ghost;
  if (pstore_reserve(p, first + m)) return -1;
  const ghost_rec_t *in = (const ghost_rec_t *)g->rbuf.data;
  for (int s = 0; s < m; s++) {
    const int j = first + s;
    p->id[j] = in[s].id;
    p->species[j] = in[s].species;
    for (int c = 0; c < 3; c++) {
      p->x[c][j] = in[s].x[c];
      if (with_v) vel[c][j] = in[s].v[c];
    }
  }
  g->recv_start[d][k] = first;
  g->n_recv[d][k] = m;
  p->n_ghost += m;
  return rc;
}

int ghosts_build(ghost_plan_t *g, const decomp_t *dc, particles_t *p, double rcut, int with_v) {
  int fail = 0;
  p->n_ghost = 0;
  for (int d = 0; d < 3; d++) {
    /* Select among owned particles and the ghosts of earlier stages (edges and corners). */
    const int n = p->n_local + p->n_ghost;
    g->n_send[d][0] = g->n_send[d][1] = 0;
    const double lo = dc->lo[d] + rcut, hi = dc->hi[d] - rcut;
    const double *x = p->x[d];
    for (int i = 0; i < n; i++) {
      if (dc->nbr[d][0] != MPI_PROC_NULL && x[i] < lo) fail |= push_index(g, d, 0, i);
      if (dc->nbr[d][1] != MPI_PROC_NULL && x[i] >= hi) fail |= push_index(g, d, 1, i);
    }
    if (fail) g->n_send[d][0] = g->n_send[d][1] = 0;
    fail |= exchange_direction(g, dc, p, d, 0, with_v);
    fail |= exchange_direction(g, dc, p, d, 1, with_v);
  }
  int any = fail != 0;
  MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_LOR, dc->cart);
  return any ? -1 : 0;
}

int ghosts_sync_scalar(ghost_plan_t *g, const decomp_t *dc, double *field) {
  int fail = 0;
  for (int d = 0; d < 3; d++)
    for (int k = 0; k < 2; k++) {
      const int n = g->n_send[d][k];
      if (xbuf_reserve(&g->sbuf, (size_t)n * sizeof(double))) return -1;
      double *out = (double *)g->sbuf.data;
      for (int s = 0; s < n; s++) out[s] = field[g->send_idx[d][k][s]];
      fail |= exchange_bytes(dc->cart, dc->rank, dc->nbr[d][k], dc->nbr[d][1 - k], out,
                             (size_t)n * sizeof(double), &g->rbuf, 200 + 4 * d + 2 * k);
      const int m = (int)(g->rbuf.size / sizeof(double));
      if (m != g->n_recv[d][k])
        fail = 1;
      else
        memcpy(field + g->recv_start[d][k], g->rbuf.data, (size_t)m * sizeof(double));
    }
  return fail ? -1 : 0;
}
