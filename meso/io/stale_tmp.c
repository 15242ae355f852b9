/* Clean-up of temporary files left by killed writes (stale_tmp.h). */
#include "io/stale_tmp.h"

#include <dirent.h>
#include <errno.h>
#include <libgen.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

/* The pid of a name ending in ".tmp.<digits>", or -1. */
static long tmp_pid(const char *name) {
  const char *t = strstr(name, ".tmp.");
  if (!t) return -1;
  for (const char *n; (n = strstr(t + 1, ".tmp."));) t = n; /* the last one */
  char *end;
  const long pid = strtol(t + 5, &end, 10);
  return end != t + 5 && *end == 0 && pid > 0 ? pid : -1;
}

int stale_tmp_cleanup(const char *prefix) {
  if (!prefix || !prefix[0]) return 0;
  char dbuf[4096], bbuf[4096];
  snprintf(dbuf, sizeof dbuf, "%s", prefix);
  snprintf(bbuf, sizeof bbuf, "%s", prefix);
  const char *dir = dirname(dbuf), *base = basename(bbuf);
  const size_t bl = strlen(base);
  DIR *dp = opendir(dir);
  if (!dp) return 0;
  int removed = 0;
  struct dirent *e;
  while ((e = readdir(dp))) {
    if (strncmp(e->d_name, base, bl) != 0) continue;
    const long pid = tmp_pid(e->d_name + bl);
    if (pid < 0 || pid == (long)getpid()) continue;
    if (kill((pid_t)pid, 0) == 0 || errno != ESRCH) continue; /* still running (or not ours) */
    char path[8300];
    snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
    if (remove(path) == 0) {
      fprintf(stderr,
              "mdpore: removed %s: the temporary file of a write that process %ld did not finish "
              "(killed; the file it was writing kept its previous complete version)\n",
              path, pid);
      removed++;
    }
  }
  closedir(dp);
  return removed;
}
