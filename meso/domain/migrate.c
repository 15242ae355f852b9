/* Migration of owned particles between subdomains (see migrate.h). */
#include "migrate.h"
#include "particle_store.h"

#include <math.h>
#include <string.h>

static void note_lost(migrate_report_t *rep, int64_t id, const double x[3]) {
  if (rep->n_lost++ == 0) {
    rep->lost_id = id;
    memcpy(rep->lost_x, x, sizeof rep->lost_x);
  }
}

/* Put x back into [box_lo, box_hi) after a periodic shift, against rounding (x - L + L may land on
 * hi). */
static double clamp_into_box(const decomp_t *dc, int d, double x) {
  if (x >= dc->box_hi[d]) return nextafter(dc->box_hi[d], dc->box_lo[d]);
  if (x < dc->box_lo[d]) return dc->box_lo[d];
  return x;
}

/* Along an axis with a single subdomain: *x wrapped back into the box (periodic), or 1 for a loss
 * (a non-periodic axis, not finite, or farther than two box lengths), *x left as it is. */
static int wrap_uncut(const decomp_t *dc, int d, double *x) {
  if (*x >= dc->box_lo[d] && *x < dc->box_hi[d]) return 0;
  if (!dc->periodic[d] || !isfinite(*x) || fabs(*x - dc->box_lo[d]) > 2.0 * dc->L[d]) return 1;
  *x = clamp_into_box(dc, d, *x < dc->box_lo[d] ? *x + dc->L[d] : *x - dc->L[d]);
  return 0;
}

/* A leaver along the cut axis d going down (dir 0) or up (1): across the periodic face it takes
 * the image on the other side. */
static void wrap_crossing(const decomp_t *dc, int d, int dir, double x[3]) {
  if (dir == 0 && dc->coords[d] == 0) x[d] = clamp_into_box(dc, d, x[d] + dc->L[d]);
  if (dir == 1 && dc->coords[d] == dc->dims[d] - 1) x[d] = clamp_into_box(dc, d, x[d] - dc->L[d]);
}

static void wrap_axis_in_place(const decomp_t *dc, particles_t *p, int d, migrate_report_t *rep) {
  for (int i = 0; i < p->n_local; i++)
    if (wrap_uncut(dc, d, &p->x[d][i])) {
      double pos[3] = {p->x[0][i], p->x[1][i], p->x[2][i]};
      note_lost(rep, p->id[i], pos);
    }
}

void migrant_pack(const particles_t *p, int i, migrant_t *m) {
  m->id = p->id[i];
  m->species = p->species[i];
  m->pad = 0;
  for (int c = 0; c < 3; c++) {
    m->x[c] = p->x[c][i];
    m->v[c] = p->v[c][i];
    m->f[c] = p->f[c][i];
  }
}

void migrant_unpack(particles_t *p, int j, const migrant_t *m) {
  p->id[j] = m->id;
  p->species[j] = m->species;
  for (int c = 0; c < 3; c++) {
    p->x[c][j] = m->x[c];
    p->v[c][j] = m->v[c];
    p->f[c][j] = m->f[c];
  }
}

void migrate_particles(const decomp_t *dc, particles_t *p, xbuf_t *sbuf, xbuf_t *rbuf,
                       migrate_report_t *rep) {
  p->n_ghost = 0;
  for (int d = 0; d < 3; d++) {
    if (dc->dims[d] == 1) {
      wrap_axis_in_place(dc, p, d, rep);
      continue;
    }
    /* Pack leavers: down first, then up, in local order; compact the stayers in place. */
    int n_out[2] = {0, 0}, keep = 0;
    const double lo = dc->lo[d], hi = dc->hi[d];
    for (int i = 0; i < p->n_local; i++) {
      const double xi = p->x[d][i];
      const int dir = xi < lo ? 0 : (xi >= hi ? 1 : -1);
      if (!isfinite(xi)) { /* fails both cut tests: it would stay here, in no cell (as the
                              single-subdomain path, a loss; the drift check names it first) */
        double pos[3] = {p->x[0][i], p->x[1][i], p->x[2][i]};
        note_lost(rep, p->id[i], pos);
        if (keep != i) pstore_copy(p, keep, i);
        keep++;
        continue;
      }
      if (dir >= 0 && dc->nbr[d][dir] == MPI_PROC_NULL) {
        double pos[3] = {p->x[0][i], p->x[1][i], p->x[2][i]};
        note_lost(rep, p->id[i],
                  pos); /* through a non-periodic face: box_walls should prevent it */
        continue;
      }
      if (dir < 0) {
        if (keep != i) pstore_copy(p, keep, i);
        keep++;
        continue;
      }
      /* Two lists in one buffer: leavers down grow from the front of a scratch area of size
       * n_local. */
      if (xbuf_reserve(sbuf, (size_t)2 * (size_t)p->n_local * sizeof(migrant_t))) {
        rep->out_of_memory = 1;
        keep++;
        continue;
      }
      migrant_t *m =
          (migrant_t *)sbuf->data + (size_t)dir * (size_t)p->n_local + (size_t)n_out[dir]++;
      migrant_pack(p, i, m);
      wrap_crossing(dc, d, dir, m->x); /* across a periodic face: the image on the other side */
    }
    const int n_before = p->n_local;
    p->n_local = keep;
    for (int k = 0; k < 2; k++) {
      const migrant_t *out =
          n_out[k] ? (const migrant_t *)sbuf->data + (size_t)k * (size_t)n_before : NULL;
      if (exchange_bytes(dc->cart, dc->rank, dc->nbr[d][k], dc->nbr[d][1 - k], out,
                         (size_t)n_out[k] * sizeof(migrant_t), rbuf, 300 + 4 * d + 2 * k)) {
        rep->out_of_memory = 1;
        continue;
      }
      const int m = (int)(rbuf->size / sizeof(migrant_t));
      if (pstore_reserve(p, p->n_local + m)) {
        rep->out_of_memory = 1;
        continue;
      }
      const migrant_t *in = (const migrant_t *)rbuf->data;
      for (int s = 0; s < m; s++) {
        /* A particle that moved farther than one subdomain cannot be placed correctly. */
        if (!(in[s].x[d] >= lo && in[s].x[d] < hi)) note_lost(rep, in[s].id, in[s].x);
        migrant_unpack(p, p->n_local++, &in[s]);
      }
    }
  }
}

/* The leavers' records: along the uncut axes wrapped in place (wrap_axis_in_place's test), then
 * sorted into the stay, down and up lists of sbuf / out as migrate_particles' cut-axis stage. */
static void sort_records(const decomp_t *dc, int d, const migrant_t *leavers, int m,
                         migrant_t *down, migrant_t *up, migrant_t *stay, int n_out[2], int *n_stay,
                         migrate_report_t *rep) {
  for (int i = 0; i < m; i++) {
    migrant_t r = leavers[i];
    int through = 0; /* left through a non-periodic face (or too far): lost */
    for (int e = 0; e < 3; e++)
      if (e != d) through |= wrap_uncut(dc, e, &r.x[e]);
    const double xi = r.x[d];
    if (through || !isfinite(xi)) { /* kept, as migrate_particles keeps it (the check stops) */
      note_lost(rep, r.id, r.x);
      stay[(*n_stay)++] = r;
      continue;
    }
    const int dir = xi < dc->lo[d] ? 0 : (xi >= dc->hi[d] ? 1 : -1);
    if (dir < 0) {
      stay[(*n_stay)++] = r;
      continue;
    }
    if (dc->nbr[d][dir] == MPI_PROC_NULL) { /* through a non-periodic face: dropped */
      note_lost(rep, r.id, r.x);
      continue;
    }
    wrap_crossing(dc, d, dir, r.x);
    (dir ? up : down)[n_out[dir]++] = r;
  }
}

int migrate_records(const decomp_t *dc, int d, const migrant_t *leavers, int m, xbuf_t *sbuf,
                    xbuf_t *rbuf, xbuf_t *out, migrate_report_t *rep) {
  const size_t rec = sizeof(migrant_t);
  int n_out[2] = {0, 0}, n = 0;
  if (m < 0 || xbuf_reserve(sbuf, 2 * (size_t)m * rec + 1) ||
      xbuf_reserve(out, (size_t)m * rec + 1)) {
    rep->out_of_memory = 1;
    m = 0; /* still enter the exchanges below (collective) */
  }
  migrant_t *down = (migrant_t *)sbuf->data, *up = down + m;
  sort_records(dc, d, leavers, m, down, up, (migrant_t *)out->data, n_out, &n, rep);
  for (int k = 0; k < 2; k++) {
    if (exchange_bytes(dc->cart, dc->rank, dc->nbr[d][k], dc->nbr[d][1 - k],
                       n_out[k] ? (k ? (const void *)up : (const void *)down) : NULL,
                       (size_t)n_out[k] * rec, rbuf, 300 + 4 * d + 2 * k)) {
      rep->out_of_memory = 1;
      continue;
    }
    const int a = (int)(rbuf->size / rec);
    if (xbuf_reserve(out, (size_t)(n + a) * rec + 1)) {
      rep->out_of_memory = 1;
      continue;
    }
    const migrant_t *in = (const migrant_t *)rbuf->data;
    migrant_t *dst = (migrant_t *)out->data;
    for (int s = 0; s < a; s++) {
      /* A particle that moved farther than one subdomain cannot be placed correctly. */
      if (!(in[s].x[d] >= dc->lo[d] && in[s].x[d] < dc->hi[d])) note_lost(rep, in[s].id, in[s].x);
      dst[n++] = in[s];
    }
  }
  return n;
}
