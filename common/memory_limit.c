/* The allocation limit for user inputs (memory_limit.h). */
#include "common/memory_limit.h"

#include <stdlib.h>
#include <unistd.h>

double mdp_memory_limit(void) {
  const char *env = getenv("MDPORE_MEMORY_LIMIT");
  char *end;
  if (env && *env) {
    const double v = strtod(env, &end);
    if (end != env && v > 0) return v;
  }
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? (double)pages * (double)page : 1e18;
}
