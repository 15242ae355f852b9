/* Redistribution of owned particles after the cuts moved (redistribute.h). */
#include "redistribute.h"
#include "migrate.h"
#include "particle_store.h"

#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

/* The rank whose subdomain holds particle i. */
static int owner_of(const decomp_t *dc, const particles_t *p, int i) {
  int coords[3], rank = 0;
  for (int d = 0; d < 3; d++) coords[d] = decomp_coord_of(dc, d, p->x[d][i]);
  MPI_Cart_rank(dc->cart, coords, &rank);
  return rank;
}

int redistribute_particles(const decomp_t *dc, particles_t *p, char *err, size_t errlen) {
  const int nr = dc->nranks, n = p->n_local;
  p->n_ghost = 0;
  int *dest = malloc((size_t)(n > 0 ? n : 1) * sizeof *dest);
  int *scount = calloc((size_t)nr, sizeof *scount), *rcount = calloc((size_t)nr, sizeof *rcount);
  int *sdisp = calloc((size_t)nr, sizeof *sdisp), *rdisp = calloc((size_t)nr, sizeof *rdisp);
  migrant_t *out = malloc((size_t)(n > 0 ? n : 1) * sizeof *out), *in = NULL;
  int bad = !dest || !scount || !rcount || !sdisp || !rdisp || !out;
  if (!bad) {
    for (int i = 0; i < n; i++) scount[dest[i] = owner_of(dc, p, i)]++;
    for (int r = 1; r < nr; r++) sdisp[r] = sdisp[r - 1] + scount[r - 1];
    int *fill = calloc((size_t)nr, sizeof *fill);
    if (!fill)
      bad = 1;
    else {
      for (int i = 0; i < n; i++) migrant_pack(p, i, &out[sdisp[dest[i]] + fill[dest[i]]++]);
      free(fill);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, dc->cart);
  if (bad) {
    snprintf(err, errlen, "out of memory redistributing %d particles after the cuts moved", n);
    goto done;
  }
  MPI_Alltoall(scount, 1, MPI_INT, rcount, 1, MPI_INT, dc->cart);
  int64_t total = 0;
  for (int r = 0; r < nr; r++) {
    rdisp[r] = (int)total;
    total += rcount[r];
  }
  bad = total > INT_MAX / 2 || pstore_reserve(p, (int)total) ||
        !(in = malloc((size_t)(total > 0 ? total : 1) * sizeof *in));
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, dc->cart);
  if (bad) {
    snprintf(err, errlen,
             "cannot take the %lld particles a rank owns after the cuts moved (out of memory or "
             "over %d)",
             (long long)total, INT_MAX / 2);
    goto done;
  }
  MPI_Datatype one;
  MPI_Type_contiguous((int)sizeof(migrant_t), MPI_BYTE, &one);
  MPI_Type_commit(&one);
  MPI_Alltoallv(out, scount, sdisp, one, in, rcount, rdisp, one, dc->cart);
  MPI_Type_free(&one);
  for (int64_t s = 0; s < total; s++) migrant_unpack(p, (int)s, &in[s]);
  p->n_local = (int)total;
done:
  free(dest);
  free(scount);
  free(rcount);
  free(sdisp);
  free(rdisp);
  free(out);
  free(in);
  return bad ? -1 : 0;
}
