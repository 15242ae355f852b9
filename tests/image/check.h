/* Minimal assertion helpers for the image tests. */
#ifndef MDPORE_TEST_CHECK_H
#define MDPORE_TEST_CHECK_H
#include <math.h>
#include <stdio.h>
#include <string.h>

static int check_failures = 0;
#define CHECK(cond, ...)                                                                           \
  do {                                                                                             \
    if (!(cond)) {                                                                                 \
      check_failures++;                                                                            \
      fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);                              \
      fprintf(stderr, __VA_ARGS__);                                                                \
      fprintf(stderr, "\n");                                                                       \
    }                                                                                              \
  } while (0)
#define CHECK_CLOSE(a, b, tol)                                                                     \
  CHECK(fabs((double)(a) - (double)(b)) <= (tol), "%.10g vs %.10g (tol %g)", (double)(a),          \
        (double)(b), (double)(tol))
#define CHECK_ERR_HAS(rc, err, text)                                                               \
  CHECK((rc) != 0 && strstr(err, text), "expected an error containing '%s', got rc %d '%s'", text, \
        rc, err)
#endif
