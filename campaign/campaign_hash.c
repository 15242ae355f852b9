/* The inputs' hash that names a run folder: FNV-1a 64 over the scene text, the bytes of every file
 * the scene names (image with its raw sidecar or a folder of slices, patch database, initial
 * configuration: a file replaced in place reruns; the path plain or quoted)
 * and the binary version (project version + an FNV-1a 64 of the executable's bytes, so a rebuilt
 * engine reruns). */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

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

static int by_name(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

/* A folder (a stack of TIFF slices): the name and bytes of each regular file in it, in name order.
 */
static int fold_folder(uint64_t *h, const char *dir) {
  DIR *d = opendir(dir);
  if (!d) return -1;
  char **names = NULL;
  size_t n = 0, cap = 0;
  int rc = 0;
  struct dirent *e;
  while (!rc && (e = readdir(d))) {
    if (e->d_name[0] == '.') continue;
    if (n == cap) {
      char **more = realloc(names, (cap = cap ? 2 * cap : 64) * sizeof *names);
      if (!more)
        rc = -1;
      else
        names = more;
    }
    if (!rc && !(names[n++] = strdup(e->d_name))) rc = -1, n--;
  }
  closedir(d);
  if (!rc) qsort(names, n, sizeof *names, by_name);
  for (size_t i = 0; i < n; i++) {
    char path[4096 + 256];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", dir, names[i]);
    if (!rc && !stat(path, &st) && S_ISREG(st.st_mode)) {
      *h = camp_fnv1a(*h, names[i], strlen(names[i]) + 1);
      rc = fold_file(h, path);
    }
    free(names[i]);
  }
  free(names);
  return rc;
}

/* A named input: a file's bytes, plus those of its raw sidecar PATH.hdr when there is one (the
 * voxel layout of a raw image lives there), or a folder's files. */
static int fold_input(uint64_t *h, const char *path) {
  struct stat st;
  if (stat(path, &st)) return -1;
  if (S_ISDIR(st.st_mode)) return fold_folder(h, path);
  if (fold_file(h, path)) return -1;
  char side[4096 + 8];
  snprintf(side, sizeof side, "%s.hdr", path);
  if (!stat(side, &st) && S_ISREG(st.st_mode)) {
    *h = camp_fnv1a(*h, ".hdr", 4);
    return fold_file(h, side);
  }
  return 0;
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
      if ((size_t)(line + len - p) <= kl || strncmp(p, keys[k], kl)) continue;
      /* the value, plain or quoted (the emitter quotes a path that YAML would misread) */
      const char *v = p + kl, *v_end = line + len;
      while (v_end > v && (v_end[-1] == ' ' || v_end[-1] == '\r')) v_end--;
      if (v_end - v >= 2 && (*v == '"' || *v == '\'') && v_end[-1] == *v) v++, v_end--;
      if (v >= v_end || *v != '/') continue; /* absolute paths only: outputs are relative */
      char path[4096];
      const size_t pl = (size_t)(v_end - v);
      if (pl >= sizeof path) return -1;
      memcpy(path, v, pl);
      path[pl] = 0;
      if (memchr(path, '\\', pl)) { /* an escaped path: its bytes are not the text's */
        fprintf(stderr,
                "mdpore permeability: %s: expected a path without backslashes to key the run\n",
                path);
        return -1;
      }
      if (fold_input(h, path)) {
        fprintf(stderr, "mdpore permeability: %s: cannot read this input to key the run\n", path);
        return -1;
      }
    }
    line = end ? end + 1 : NULL;
  }
  return 0;
}
