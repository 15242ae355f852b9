/* CHECK(cond) for the scene and I/O tests: counts failures in `failures` and prints where. */
#ifndef MDPORE_TEST_IO_CHECK_H
#define MDPORE_TEST_IO_CHECK_H

#include <stdio.h>

static int failures = 0;
#define CHECK(c)                                                                                   \
  do {                                                                                             \
    if (!(c)) {                                                                                    \
      fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #c);                        \
      failures++;                                                                                  \
    }                                                                                              \
  } while (0)

#endif
