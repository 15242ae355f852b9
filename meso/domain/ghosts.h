/* Ghost layer: copies of the particles within the ghost cutoff of this subdomain, with periodic
 * images, built in three stages (x, then y, then z; later stages forward earlier ghosts so that
 * edges and corners are covered). The same stages replayed later send fields (rho) from owners to
 * their ghosts. */
#ifndef MESO_ENGINE_GHOSTS_H
#define MESO_ENGINE_GHOSTS_H

#include "decomp.h"
#include "exchange.h"
#include "particles.h"

typedef struct {
  int *send_idx[3][2]; /* per axis, per direction (0 = down, 1 = up): indices sent */
  int n_send[3][2], cap_send[3][2];
  int recv_start[3][2], n_recv[3][2]; /* where the ghosts received from each direction were put */
  xbuf_t sbuf, rbuf;
} ghost_plan_t;

void ghosts_free(ghost_plan_t *g);
/* Rebuild all ghosts of p (n_ghost is reset) within rcut of the subdomain. with_v: ghosts carry
 * velocity (the predicted one, p->vpred when allocated, else p->v). 0, or -1 when out of memory
 * (collective). */
int ghosts_build(ghost_plan_t *g, const decomp_t *dc, particles_t *p, double rcut, int with_v);
/* Bytes of one ghost sent or received (the exchange record; the memory plan counts them). */
size_t ghosts_record_bytes(void);
/* Forward sync of one per-particle scalar field (e.g. rho) from owners to ghosts. 0 or -1. */
int ghosts_sync_scalar(ghost_plan_t *g, const decomp_t *dc, double *field);

#endif
