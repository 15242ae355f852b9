/* Point-to-point byte exchange with one neighbour pair (send to dest, receive from src), the
 * building block of migration and ghost exchange. A rank that is its own neighbour copies locally.
 */
#ifndef MESO_ENGINE_EXCHANGE_H
#define MESO_ENGINE_EXCHANGE_H

#include <mpi.h>
#include <stddef.h>

typedef struct {
  char *data;
  size_t size, cap;
} xbuf_t;

/* Make room for n bytes (contents kept). 0 or -1. */
int xbuf_reserve(xbuf_t *b, size_t n);
void xbuf_free(xbuf_t *b);

/* Send sbuf (sbytes) to dest and receive into rbuf from src; either may be MPI_PROC_NULL.
 * rbuf->size is set to the received byte count. 0 or -1 (out of memory). Collective over the pair.
 */
int exchange_bytes(MPI_Comm comm, int me, int dest, int src, const void *sbuf, size_t sbytes,
                   xbuf_t *rbuf, int tag);

#endif
