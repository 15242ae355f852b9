/* Small text helpers (text.h). */
#include "text.h"

#include "common/memory_limit.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

char *text_trim(char *s) {
  while (isspace((unsigned char)*s)) s++;
  char *e = s + strlen(s);
  while (e > s && isspace((unsigned char)e[-1])) *--e = 0;
  return s;
}

char *text_read_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  /* its size against the memory limit before anything is allocated (the text and its growth:
   * twice the size at most) */
  struct stat sb;
  if (fstat(fileno(f), &sb) == 0 && 2.0 * (double)sb.st_size + 1 > mdp_memory_limit()) {
    fclose(f);
    errno = EFBIG;
    return NULL;
  }
  size_t cap = 4096, n = 0, r;
  char *s = malloc(cap);
  while (s && (r = fread(s + n, 1, cap - n - 1, f)) > 0) {
    n += r;
    if (n + 1 >= cap) {
      char *t = realloc(s, cap *= 2);
      if (!t) free(s);
      s = t;
    }
  }
  fclose(f);
  if (s) s[n] = 0;
  return s;
}
