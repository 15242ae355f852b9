/* The allocation limit for user inputs and the memory available to a run (memory_limit.h). */
#include "common/memory_limit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

double mdp_parse_bytes(const char *text) {
  if (!text || !*text) return -1;
  char *end;
  double v = strtod(text, &end);
  if (end == text || !isfinite(v) || v <= 0) return -1;
  static const char units[] = "KMGT";
  const char *u = *end ? strchr(units, *end) : NULL;
  if (u) {
    v *= pow(1024.0, (double)(u - units + 1));
    end++;
  }
  return *end ? -1 : v;
}

double mdp_memory_limit(void) {
  const double env = mdp_parse_bytes(getenv("MDPORE_MEMORY_LIMIT"));
  if (env > 0) return env;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? (double)pages * (double)page : 1e18;
}

/* The first number of a one-line file (-1 when absent or "max"). */
static double read_number(const char *path) {
  FILE *f = fopen(path, "r");
  if (!f) return -1;
  double v = -1;
  if (fscanf(f, "%lf", &v) != 1) v = -1;
  fclose(f);
  return v;
}

/* The value of line "KEY VALUE" of a file of such lines (/proc/meminfo: "MemAvailable: N kB";
 * memory.stat: "inactive_file N"). -1 when absent. */
static double read_key(const char *path, const char *key) {
  FILE *f = fopen(path, "r");
  if (!f) return -1;
  char line[256];
  double v = -1;
  const size_t n = strlen(key);
  while (fgets(line, sizeof line, f))
    if (!strncmp(line, key, n) && (line[n] == ' ' || line[n] == ':' || line[n] == '\t')) {
      v = strtod(line + n + 1, NULL);
      break;
    }
  fclose(f);
  return v;
}

/* The cgroup's room: limit - (usage - inactive file cache); -1 without a limit. v2 at the
 * namespace root (/sys/fs/cgroup/memory.max), else v1 (/sys/fs/cgroup/memory/). */
static double cgroup_room(const char **name) {
  static const struct {
    const char *limit, *usage, *stat, *inactive, *name;
  } kinds[2] = {{"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory.current",
                 "/sys/fs/cgroup/memory.stat", "inactive_file", "cgroup memory.max"},
                {"/sys/fs/cgroup/memory/memory.limit_in_bytes",
                 "/sys/fs/cgroup/memory/memory.usage_in_bytes", "/sys/fs/cgroup/memory/memory.stat",
                 "total_inactive_file", "cgroup memory.limit_in_bytes"}};
  for (int k = 0; k < 2; k++) {
    const double limit = read_number(kinds[k].limit);
    if (!(limit > 0) || limit >= 1e18) continue; /* "max", absent or unlimited (2^63 - page) */
    double used = read_number(kinds[k].usage);
    const double inactive = read_key(kinds[k].stat, kinds[k].inactive);
    if (used < 0) used = 0;
    if (inactive > 0 && inactive < used) used -= inactive;
    *name = kinds[k].name;
    return limit > used ? limit - used : 0;
  }
  return -1;
}

double mdp_memory_available(char *from, size_t len) {
  double best = 1e18;
  const char *name = "unknown";
  const double avail_kb = read_key("/proc/meminfo", "MemAvailable");
  if (avail_kb >= 0) {
    best = avail_kb * 1024.0;
    name = "MemAvailable";
  }
  const char *cg_name = NULL;
  const double cg = cgroup_room(&cg_name);
  if (cg >= 0 && cg < best) {
    best = cg;
    name = cg_name;
  }
  const double env = mdp_parse_bytes(getenv("MDPORE_MEMORY_LIMIT"));
  if (env > 0 && env < best) {
    best = env;
    name = "MDPORE_MEMORY_LIMIT";
  }
  if (from && len) snprintf(from, len, "%s", name);
  return best;
}
