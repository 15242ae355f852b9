/* Replays inputs through one fuzz entry without libFuzzer (every build; the corpus ctests):
 *   fuzz_X_replay FILE_OR_FOLDER...
 * Each file is one input. A file named ok_* must be accepted by the reader and one named bad_* must
 * be refused (with a message naming the file: fuzz_outcome); other names (regressions of crashes)
 * may be either. Exits 1 on a failed expectation or when no input was found; a crash fails too. */
#include "fuzz_util.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int n_inputs, n_accepted, n_failed;

static int by_name(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

static void replay_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    fprintf(stderr, "%s: cannot open\n", path);
    n_failed++;
    return;
  }
  fseek(f, 0, SEEK_END);
  const long size = ftell(f);
  fseek(f, 0, SEEK_SET);
  uint8_t *data = malloc(size > 0 ? (size_t)size : 1);
  if (!data || (size > 0 && fread(data, 1, (size_t)size, f) != (size_t)size)) {
    fprintf(stderr, "%s: cannot read\n", path);
    n_failed++;
    fclose(f);
    free(data);
    return;
  }
  fclose(f);
  fprintf(stderr, "%s (%ld bytes)\n", path, size);
  LLVMFuzzerTestOneInput(data, (size_t)size);
  free(data);
  n_inputs++;
  n_accepted += fuzz_last_accepted;
  const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
  if (!strncmp(base, "ok_", 3) && !fuzz_last_accepted) {
    fprintf(stderr, "FAIL %s: expected the reader to accept it (got a refusal)\n", path);
    n_failed++;
  }
  if (!strncmp(base, "bad_", 4) && fuzz_last_accepted) {
    fprintf(stderr, "FAIL %s: expected the reader to refuse it (got accepted)\n", path);
    n_failed++;
  }
}

static void replay(const char *path) {
  struct stat sb;
  if (stat(path, &sb) != 0) {
    fprintf(stderr, "%s: no such file or folder\n", path);
    n_failed++;
    return;
  }
  if (!S_ISDIR(sb.st_mode)) {
    replay_file(path);
    return;
  }
  DIR *d = opendir(path);
  char **names = NULL;
  int n = 0;
  struct dirent *e;
  while (d && (e = readdir(d))) {
    if (e->d_name[0] == '.') continue;
    names = realloc(names, sizeof *names * (size_t)(n + 1));
    names[n++] = strdup(e->d_name);
  }
  if (d) closedir(d);
  qsort(names, (size_t)n, sizeof *names, by_name);
  for (int i = 0; i < n; i++) {
    char sub[4096];
    snprintf(sub, sizeof sub, "%s/%s", path, names[i]);
    replay(sub);
    free(names[i]);
  }
  free(names);
}

int main(int argc, char **argv) {
  fuzz_replay_mode = 1;
  LLVMFuzzerInitialize(&argc, &argv);
  for (int i = 1; i < argc; i++) replay(argv[i]);
  printf("%d inputs replayed: %d accepted, %d refused with a message naming the file, %d failed "
         "expectations\n",
         n_inputs, n_accepted, n_inputs - n_accepted, n_failed);
  if (n_inputs == 0) {
    fprintf(stderr, "no inputs found (expected a corpus folder)\n");
    return 1;
  }
  return n_failed ? 1 : 0;
}
