/* Temp-file + rename output (see atomic_file.h). */
#include "atomic_file.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

void atomic_temp_name(atomic_file *a, const char *path) {
  a->f = NULL;
  snprintf(a->final_path, sizeof a->final_path, "%s", path);
  snprintf(a->temp_path, sizeof a->temp_path, "%s.tmp.%ld", path, (long)getpid());
}

int atomic_open(atomic_file *a, const char *path) {
  atomic_temp_name(a, path);
  a->f = fopen(a->temp_path, "w");
  if (!a->f) {
    fprintf(stderr, "mdpore: cannot write '%s': %s\n", a->temp_path, strerror(errno));
    return -1;
  }
  return 0;
}

int atomic_rename(atomic_file *a) {
  if (rename(a->temp_path, a->final_path) != 0) {
    fprintf(stderr, "mdpore: cannot rename '%s' to '%s': %s\n", a->temp_path, a->final_path,
            strerror(errno));
    remove(a->temp_path);
    return -1;
  }
  return 0;
}

int atomic_commit(atomic_file *a) {
  int bad = ferror(a->f);
  if (fclose(a->f) != 0) bad = 1;
  a->f = NULL;
  if (bad) {
    fprintf(stderr, "mdpore: write error on '%s'\n", a->temp_path);
    remove(a->temp_path);
    return -1;
  }
  return atomic_rename(a);
}
