/* Neighbour exchange: sizes first, then the payload (MPI_Sendrecv, or a copy when sending to self).
 */
#include "exchange.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int xbuf_reserve(xbuf_t *b, size_t n) {
  if (n <= b->cap) return 0;
  size_t cap = b->cap ? b->cap : 4096;
  while (cap < n) cap *= 2;
  char *q = realloc(b->data, cap);
  if (!q) return -1;
  b->data = q;
  b->cap = cap;
  return 0;
}

void xbuf_free(xbuf_t *b) {
  free(b->data);
  memset(b, 0, sizeof *b);
}

int exchange_bytes(MPI_Comm comm, int me, int dest, int src, const void *sbuf, size_t sbytes,
                   xbuf_t *rbuf, int tag) {
  if (dest == me && src == me) {
    if (xbuf_reserve(rbuf, sbytes)) return -1;
    if (sbytes) memcpy(rbuf->data, sbuf, sbytes);
    rbuf->size = sbytes;
    return 0;
  }
  uint64_t ns = sbytes, nr = 0;
  MPI_Sendrecv(&ns, 1, MPI_UINT64_T, dest, tag, &nr, 1, MPI_UINT64_T, src, tag, comm,
               MPI_STATUS_IGNORE);
  if (src == MPI_PROC_NULL) nr = 0;
  int fail = xbuf_reserve(rbuf, (size_t)nr) != 0;
  if (nr > INT32_MAX || ns > INT32_MAX) fail = 1; /* one message per neighbour stays below 2 GiB */
  /* Payload (zero bytes when out of memory, so the partner is not left waiting). */
  MPI_Sendrecv(sbuf, fail ? 0 : (int)ns, MPI_BYTE, dest, tag + 1, rbuf->data, fail ? 0 : (int)nr,
               MPI_BYTE, src, tag + 1, comm, MPI_STATUS_IGNORE);
  rbuf->size = fail ? 0 : (size_t)nr;
  return fail ? -1 : 0;
}
