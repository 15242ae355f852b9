/* Sizes from user input checked before anything is allocated: a count of items (cells, particles,
 * voxels, bins) computed in double from the input's numbers, compared with the largest count the
 * code can index and, at a number of bytes per item, with the memory one process may use
 * (memory_limit.h). The caller names the file and key; the message says what was asked and what
 * fits. */
#ifndef COMMON_SIZE_CHECK_H
#define COMMON_SIZE_CHECK_H

#include <stddef.h>

/* 0 when `count` items fit: finite, at most `max_count` and count * bytes_each bytes within
 * mdp_memory_limit(). Else -1 and `msg` (len bytes) holds "2.2e+09 cells of the cell grid need
 * 35.2 GB; at most 16 GB fit (...)" or the index limit exceeded. `what` names the items. */
int mdp_size_check(double count, double max_count, double bytes_each, const char *what, char *msg,
                   size_t len);

/* The number of cells of width >= rcut along an extent grown by rcut at each side (a cell list's
 * bins, ghost layer included), as a double: never overflows. */
double mdp_cell_count(const double lo[3], const double hi[3], double rcut);

#endif
