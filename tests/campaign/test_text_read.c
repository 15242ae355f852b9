/* Whole-file reads (common/text.c: text_read_file, the campaigns' comparison of a run folder's
 * scene.yaml with the text they would write) check the file's size against the memory limit before
 * allocating: a 64 MiB sparse file under MDPORE_MEMORY_LIMIT=1M is refused with errno EFBIG (the
 * peak resident memory stays below the file's size), a small one is read back whole. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "common/text.h"

static int failures;

static void check(int ok, const char *what) {
  printf("%s %s\n", ok ? "ok  " : "FAIL", what);
  if (!ok) failures++;
}

int main(void) {
  const char *big = "test_text_read_big.txt", *small = "test_text_read_small.txt";
  FILE *f = fopen(big, "wb");
  if (!f || ftruncate(fileno(f), 64L << 20) != 0) {
    perror(big);
    return 1;
  }
  fclose(f);
  const char *text = "name: x\nbox: {lo: [0, 0, 0], hi: [1, 1, 1]}\n";
  f = fopen(small, "wb");
  if (!f || fputs(text, f) < 0) {
    perror(small);
    return 1;
  }
  fclose(f);

  setenv("MDPORE_MEMORY_LIMIT", "1M", 1);
  errno = 0;
  char *s = text_read_file(big);
  check(!s && errno == EFBIG, "a 64 MiB file under MDPORE_MEMORY_LIMIT=1M: NULL, errno EFBIG");
  free(s);
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  printf("  peak RSS %ld kB\n", ru.ru_maxrss);
  check(ru.ru_maxrss < 32 * 1024, "the peak resident memory stays below half the file's size");
  s = text_read_file(small);
  check(s && !strcmp(s, text), "a 53-byte file under the same limit: read back whole");
  free(s);
  unsetenv("MDPORE_MEMORY_LIMIT");
  s = text_read_file(big);
  check(s && s[0] == 0 && s[(64L << 20) - 1] == 0,
        "the 64 MiB file without the limit: read (64 MiB of zero bytes)");
  free(s);
  remove(big), remove(small);
  printf("%s\n", failures ? "FAILED" : "all passed");
  return failures ? 1 : 0;
}
