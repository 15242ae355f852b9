/* Atomic whole-file writes (temp file in the same directory + rename) and mkdir -p. */
#include "common/atomic_file.h"

#include <errno.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void atomic_tmp_name(const char *path, char *tmp, size_t len) {
  snprintf(tmp, len, "%s.tmp.%ld", path, (long)getpid());
}

FILE *atomic_open(const char *path, char *tmp, size_t len) {
  atomic_tmp_name(path, tmp, len);
  FILE *fp = fopen(tmp, "w");
  if (!fp) fprintf(stderr, "%s: cannot write: %s\n", tmp, strerror(errno));
  return fp;
}

int atomic_rename(const char *tmp, const char *path) {
  if (rename(tmp, path) != 0) {
    fprintf(stderr, "%s: cannot rename %s over it: %s\n", path, tmp, strerror(errno));
    remove(tmp);
    return -1;
  }
  return 0;
}

int atomic_commit(FILE *fp, const char *tmp, const char *path) {
  int bad = ferror(fp);
  bad |= fflush(fp) != 0;
  bad |= fsync(fileno(fp)) != 0 && errno != EINVAL;
  bad |= fclose(fp) != 0;
  if (bad) {
    fprintf(stderr, "%s: write failed: %s\n", tmp, strerror(errno));
    remove(tmp);
    return -1;
  }
  return atomic_rename(tmp, path);
}

int atomic_write_text(const char *path, const char *text) {
  char tmp[4096 + 64];
  FILE *f = atomic_open(path, tmp, sizeof tmp);
  if (!f) return -1;
  fputs(text, f);
  return atomic_commit(f, tmp, path);
}

int make_dirs(const char *dir) {
  char buf[4096];
  if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf) return -1;
  for (char *p = buf + 1;; p++) {
    const char c = *p;
    if (c == '/' || c == 0) {
      *p = 0;
      if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "%s: cannot create directory: %s\n", buf, strerror(errno));
        return -1;
      }
      *p = c;
      if (!c) break;
    }
  }
  return 0;
}
