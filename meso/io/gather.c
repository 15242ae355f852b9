/* Gather owned particles to one rank with MPI_Gatherv, field by field. */
#include "io/gather.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void gatherv(const void *send, int count, MPI_Datatype type, void *recv, const int *counts,
                    const int *displs, int root, MPI_Comm comm) {
  MPI_Gatherv(send, count, type, recv, counts, displs, type, root, comm);
}

int gather_particles(sim_t *sim, int root, int with_f, particle_set_t *out, long *per_rank) {
  MPI_Comm comm = sim_comm(sim);
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  particles_t *p = sim_particles(sim);
  const int n = p->n_local;
  int has_rho = p->rho != NULL;
  MPI_Allreduce(MPI_IN_PLACE, &has_rho, 1, MPI_INT, MPI_MIN, comm);

  int *counts = NULL, *displs = NULL, *counts3 = NULL, *displs3 = NULL;
  long total = 0;
  int bad = 0;
  if (rank == root) {
    counts = malloc((size_t)size * sizeof *counts);
    displs = malloc((size_t)size * sizeof *displs);
    counts3 = malloc((size_t)size * sizeof *counts3);
    displs3 = malloc((size_t)size * sizeof *displs3);
    bad = !counts || !displs || !counts3 || !displs3;
  }
  /* the send buffer of every rank, and the root's tables, before the first collective gather */
  double *buf = malloc((size_t)(3 * (n > 0 ? n : 1)) * sizeof *buf);
  bad |= !buf;
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm);
  if (bad) {
    free(buf), free(counts), free(displs), free(counts3), free(displs3);
    if (rank == root) fprintf(stderr, "mdpore: out of memory gathering the particles\n");
    memset(out, 0, sizeof *out);
    return -1;
  }
  MPI_Gather(&n, 1, MPI_INT, counts, 1, MPI_INT, root, comm);
  if (rank == root) {
    for (int r = 0; r < size; r++) {
      displs[r] = (int)total;
      counts3[r] = 3 * counts[r];
      displs3[r] = 3 * (int)total;
      total += counts[r];
      if (per_rank) per_rank[r] = counts[r];
    }
    bad = particle_set_alloc(out, total, with_f, has_rho);
  } else {
    memset(out, 0, sizeof *out);
  }
  MPI_Bcast(&bad, 1, MPI_INT, root, comm);
  if (bad) {
    free(buf), free(counts), free(displs), free(counts3), free(displs3);
    return -1;
  }

  /* Interleave local vectors for sending. */
  gatherv(p->id, n, MPI_INT64_T, out->id, counts, displs, root, comm);
  gatherv(p->species, n, MPI_INT32_T, out->species, counts, displs, root, comm);
  double *const *src[3] = {p->x, p->v, p->f};
  double *dst[3] = {out->x, out->v, out->f};
  for (int k = 0; k < (with_f ? 3 : 2); k++) {
    for (int i = 0; i < n; i++)
      for (int d = 0; d < 3; d++) buf[3 * i + d] = src[k][d][i];
    gatherv(buf, 3 * n, MPI_DOUBLE, dst[k], counts3, displs3, root, comm);
  }
  if (has_rho) gatherv(p->rho, n, MPI_DOUBLE, out->rho, counts, displs, root, comm);
  if (rank == root) out->has_v = 1;
  free(buf);
  free(counts);
  free(displs);
  free(counts3);
  free(displs3);
  return 0;
}

int particle_set_bcast(particle_set_t *set, int root, MPI_Comm comm) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  long meta[4] = {set->n, set->f != NULL, set->rho != NULL, set->has_v};
  MPI_Bcast(meta, 4, MPI_LONG, root, comm);
  int bad = 0;
  if (rank != root) bad = particle_set_alloc(set, meta[0], (int)meta[1], (int)meta[2]);
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm);
  if (bad) return -1;
  set->has_v = (int)meta[3];
  /* In chunks: counts stay below INT_MAX. */
  const long chunk = 1L << 24;
  for (long o = 0; o < meta[0]; o += chunk) {
    const int m = (int)(meta[0] - o < chunk ? meta[0] - o : chunk);
    MPI_Bcast(set->id + o, m, MPI_INT64_T, root, comm);
    MPI_Bcast(set->species + o, m, MPI_INT32_T, root, comm);
    MPI_Bcast(set->x + 3 * o, 3 * m, MPI_DOUBLE, root, comm);
    MPI_Bcast(set->v + 3 * o, 3 * m, MPI_DOUBLE, root, comm);
    if (set->f) MPI_Bcast(set->f + 3 * o, 3 * m, MPI_DOUBLE, root, comm);
    if (set->rho) MPI_Bcast(set->rho + o, m, MPI_DOUBLE, root, comm);
  }
  return 0;
}
