/* The inputs' hash that names a run folder: FNV-1a 64 over the scene text, the bytes of every file
 * the scene names (image, patch database, initial configuration: a file replaced in place reruns)
 * and the binary version (project version + an FNV-1a 64 of the executable's bytes, so a rebuilt
 * engine reruns). */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "campaign.h"

#ifndef MDPORE_VERSION
#define MDPORE_VERSION "unknown"
#endif

uint64_t camp_fnv1a(uint64_t h, const void *data, size_t n) {
  const unsigned char *p = data;
  for (size_t i = 0; i < n; i++) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}

int camp_binary_version(const char *exe, char *out, int len) {
  FILE *f = fopen(exe, "rb");
  if (!f) {
    fprintf(stderr, "mdpore permeability: %s: cannot read this binary to version the runs\n", exe);
    return -1;
  }
  uint64_t h = 14695981039346656037ULL;
  unsigned char buf[1 << 16];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, f)) > 0) h = camp_fnv1a(h, buf, n);
  fclose(f);
  snprintf(out, len, "mdpore %s exe-fnv1a64 %016llx", MDPORE_VERSION, (unsigned long long)h);
  return 0;
}

/* The bytes of one file folded into h; -1 when it cannot be read. */
static int fold_file(uint64_t *h, const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  unsigned char buf[1 << 16];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, f)) > 0) *h = camp_fnv1a(*h, buf, n);
  const int bad = ferror(f);
  fclose(f);
  return bad ? -1 : 0;
}

int camp_fold_named_files(uint64_t *h, const char *scene_text) {
  static const char *const keys[] = {"image: ", "file: ", "lammps_data: ", "snapshot: ", NULL};
  for (const char *line = scene_text; line && *line;) {
    const char *end = strchr(line, '\n');
    const size_t len = end ? (size_t)(end - line) : strlen(line);
    const char *p = line;
    while (p < line + len && (*p == ' ' || *p == '-')) p++;
    for (int k = 0; keys[k]; k++) {
      const size_t kl = strlen(keys[k]);
      if ((size_t)(line + len - p) > kl && !strncmp(p, keys[k], kl) && p[kl] == '/') {
        char path[4096];
        const size_t pl = (size_t)(line + len - (p + kl));
        if (pl >= sizeof path) return -1;
        memcpy(path, p + kl, pl);
        path[pl] = 0;
        if (fold_file(h, path)) {
          fprintf(stderr, "mdpore permeability: %s: cannot read this input to key the run\n", path);
          return -1;
        }
      }
    }
    line = end ? end + 1 : NULL;
  }
  return 0;
}
