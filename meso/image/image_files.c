/* Atomic output files and small parsing helpers shared by the readers and writers. */
#include "image_internal.h"
#include "mdpore_image.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void mdp_image_tmp_path(const char *path, char *tmp, size_t len) {
  snprintf(tmp, len, "%s.tmp%ld", path, (long)getpid());
}

int mdp_image_commit(const char *tmp, const char *path, char *err) {
  if (rename(tmp, path) != 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: cannot rename %s into place: %s", path, tmp,
             strerror(errno));
    remove(tmp);
    return 1;
  }
  return 0;
}

int mdp_image_parse_dims(const char *text, int dims[3]) {
  const char *s = text;
  for (int a = 0; a < 3; a++) {
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || v <= 0 || v > 1000000000L) return 1;
    dims[a] = (int)v;
    s = end;
    if (a < 2) {
      while (*s == ' ') s++;
      if (*s == 'x' || *s == 'X' || *s == ',') s++;
    }
  }
  while (*s == ' ' || *s == '\n' || *s == '\r') s++;
  return *s != 0;
}

void mdp_image_err_prefix(char *err, const char *path, const char *key) {
  char msg[MDP_IMAGE_ERR_LEN];
  snprintf(msg, sizeof msg, "%s", err);
  snprintf(err, MDP_IMAGE_ERR_LEN, "%.400s: key '%s': %.500s", path, key, msg);
}
