/* Shared helpers of the fuzz entries (fuzz_util.h). */
#include "fuzz_util.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int fuzz_last_accepted = 0;
int fuzz_replay_mode = 0;

static char dir[256] = "";
static char captured[8192];
static int saved_stderr = -1;

static void remove_dir(void) {
  if (!dir[0]) return;
  char cmd[300];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) fprintf(stderr, "fuzz: could not remove %s\n", dir);
}

const char *fuzz_dir(void) {
  if (!dir[0]) {
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/mdpore-fuzz-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
      perror("fuzz: mkdtemp");
      abort();
    }
    atexit(remove_dir);
  }
  return dir;
}

void fuzz_path(const char *name, char *out, size_t len) {
  snprintf(out, len, "%s/%s", fuzz_dir(), name);
}

void fuzz_write(const char *path, const void *data, size_t size) {
  FILE *f = fopen(path, "wb");
  if (!f || (size && fwrite(data, 1, size, f) != size) || fclose(f) != 0) {
    perror(path);
    abort();
  }
}

__attribute__((weak)) void fuzz_target_init(void) {}

int fuzz_argv(const uint8_t *data, size_t size, const char *argv0, char **argv, int max) {
  static char *text = NULL;
  free(text);
  text = malloc(size + 1);
  if (!text) abort();
  memcpy(text, data, size);
  text[size] = 0;
  int argc = 0;
  argv[argc++] = (char *)argv0;
  size_t start = 0;
  for (size_t i = 0; i <= size && argc < max - 1; i++)
    if (i == size || text[i] == '\n' || text[i] == 0) {
      text[i] = 0;
      if (i < size || i > start) argv[argc++] = text + start;
      start = i + 1;
    }
  argv[argc] = NULL;
  return argc;
}

int LLVMFuzzerInitialize(int *argc, char ***argv) {
  (void)argc, (void)argv;
  /* Large allocations are refused above this (the readers' memory estimate, docs/fuzzing.md), so a
   * header that claims a huge size gives a clean error instead of tripping libFuzzer's malloc
   * limit. */
  setenv("MDPORE_MEMORY_LIMIT", "33554432", 0);
  fuzz_dir();
  fuzz_target_init();
  return 0;
}

void fuzz_capture_begin(void) {
  char path[300];
  fuzz_path("stderr.txt", path, sizeof path);
  fflush(stderr);
  const int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (fd < 0) abort();
  saved_stderr = dup(2);
  dup2(fd, 2);
  close(fd);
}

const char *fuzz_capture_end(void) {
  char path[300];
  fuzz_path("stderr.txt", path, sizeof path);
  fflush(stderr);
  dup2(saved_stderr, 2);
  close(saved_stderr);
  saved_stderr = -1;
  captured[0] = 0;
  FILE *f = fopen(path, "r");
  if (f) {
    const size_t n = fread(captured, 1, sizeof captured - 1, f);
    captured[n] = 0;
    fclose(f);
  }
  return captured;
}

void fuzz_outcome(int rc, const char *message, const char *path) {
  fuzz_last_accepted = rc == 0;
  if (fuzz_replay_mode && message && *message)
    fprintf(stderr, "  %s%s", message, message[strlen(message) - 1] == '\n' ? "" : "\n");
  if (rc == 0) return;
  if (!message || !*message || !strstr(message, path)) {
    fprintf(stderr, "fuzz: the reader refused %s without a message naming the file (got '%s')\n",
            path, message ? message : "(none)");
    abort();
  }
}
