/* Migration: owned particles that left this subdomain go to the neighbour that now owns them, in
 * three stages (x, y, z; a particle crossing a corner hops twice or three times). Positions are
 * wrapped across periodic faces on the way. Local order stays deterministic: leavers are removed in
 * place keeping the order of the others, arrivals are appended in the order received (those from
 * the neighbour above, then those from below; along x, then y, then z). */
#ifndef MESO_ENGINE_MIGRATE_H
#define MESO_ENGINE_MIGRATE_H

#include "decomp.h"
#include "exchange.h"
#include "particles.h"

#include <stdint.h>

/* One particle on the wire (migration and redistribution). */
typedef struct {
  int64_t id;
  int32_t species, pad;
  double x[3], v[3], f[3];
} migrant_t;

void migrant_pack(const particles_t *p, int i, migrant_t *m);
void migrant_unpack(particles_t *p, int j, const migrant_t *m);

typedef struct {
  long n_lost;     /* particles that left through a non-periodic face or jumped past a neighbour */
  int64_t lost_id; /* the first of them */
  double lost_x[3];
  int out_of_memory;
} migrate_report_t;

/* Move owned particles to their owners (ghosts are dropped). Collective. Problems are reported in
 * *rep (local; the caller reduces them). */
void migrate_particles(const decomp_t *dc, particles_t *p, xbuf_t *sbuf, xbuf_t *rbuf,
                       migrate_report_t *rep);

/* One axis (d) cut between ranks, the other axes wrapped where the particles live (the CUDA
 * backend's device): the m leavers, already packed as records (in slot order), go to the neighbour
 * below or above along d, wrapped across periodic faces as migrate_particles does. *out receives,
 * in migrate_particles' order, the records that stay here (out only along an uncut axis and
 * wrapped back, or not finite: noted as lost and kept, as there) and then the arrivals (from above,
 * then from below). Returns their count. Collective; problems in *rep as migrate_particles. */
int migrate_records(const decomp_t *dc, int d, const migrant_t *leavers, int m, xbuf_t *sbuf,
                    xbuf_t *rbuf, xbuf_t *out, migrate_report_t *rep);

#endif
