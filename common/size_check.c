/* Sizes from user input checked against the index range and the memory limit (size_check.h). */
#include "common/size_check.h"

#include <math.h>
#include <stdio.h>

#include "common/memory_limit.h"

int mdp_size_check(double count, double max_count, double bytes_each, const char *what, char *msg,
                   size_t len) {
  if (!isfinite(count) || count < 0) {
    snprintf(msg, len, "%s: the count %g is not a finite number", what, count);
    return -1;
  }
  if (count > max_count) {
    snprintf(msg, len, "%.3g %s exceed the %.3g the code can index", count, what, max_count);
    return -1;
  }
  const double bytes = count * bytes_each, limit = mdp_memory_limit();
  if (bytes > limit) {
    snprintf(msg, len,
             "%.3g %s need %.3g GB; at most %.3g GB fit (physical memory, or MDPORE_MEMORY_LIMIT "
             "in bytes)",
             count, what, bytes / 1e9, limit / 1e9);
    return -1;
  }
  return 0;
}

double mdp_cell_count(const double lo[3], const double hi[3], double rcut) {
  double cells = 1.0;
  for (int d = 0; d < 3; d++) {
    const double extent = hi[d] - lo[d] + 2.0 * rcut;
    const double per_axis = rcut > 0 ? floor(extent / rcut) : 1.0;
    cells *= per_axis < 1.0 ? 1.0 : per_axis;
  }
  return cells;
}
