/* Two paths naming one file (same_file.h). */
#include "common/same_file.h"

#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* The canonical form of a path whose last component may not exist yet: realpath of its folder plus
 * the name. 0 on success. */
static int canonical(const char *path, char out[PATH_MAX]) {
  if (realpath(path, out)) return 0;
  char dir_copy[PATH_MAX], base_copy[PATH_MAX], dir_real[PATH_MAX];
  if (strlen(path) >= PATH_MAX) return -1;
  strcpy(dir_copy, path);
  strcpy(base_copy, path);
  if (!realpath(dirname(dir_copy), dir_real)) return -1;
  const char *base = basename(base_copy);
  if ((size_t)snprintf(out, PATH_MAX, "%s/%s", dir_real, base) >= PATH_MAX) return -1;
  return 0;
}

int mdp_same_file(const char *a, const char *b) {
  if (!a || !b || !*a || !*b) return 0;
  struct stat sa, sb;
  if (!stat(a, &sa) && !stat(b, &sb)) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  char ca[PATH_MAX], cb[PATH_MAX];
  if (canonical(a, ca) || canonical(b, cb)) return !strcmp(a, b);
  return !strcmp(ca, cb);
}

int mdp_check_outputs(const char *const *outputs, const char *const *output_roles, int n,
                      const char *const *inputs, const char *const *input_roles, int n_in,
                      char *msg, size_t len) {
  for (int i = 0; i < n; i++) {
    if (!outputs[i] || !*outputs[i]) continue;
    for (int j = 0; j < n_in; j++)
      if (mdp_same_file(outputs[i], inputs[j])) {
        snprintf(msg, len,
                 "%s '%s' would overwrite %s '%s': expected an output path apart from the inputs",
                 output_roles[i], outputs[i], input_roles[j], inputs[j]);
        return -1;
      }
    for (int j = 0; j < i; j++)
      if (mdp_same_file(outputs[i], outputs[j])) {
        snprintf(msg, len, "%s '%s' and %s '%s' name one file: expected a path for each output",
                 output_roles[j], outputs[j], output_roles[i], outputs[i]);
        return -1;
      }
  }
  return 0;
}
