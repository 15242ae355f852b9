/* The inputs' hash that names a run folder: FNV-1a 64 over the scene text and the binary version
 * (project version + an FNV-1a 64 of the executable's bytes, so a rebuilt engine reruns). */
#include <stdint.h>
#include <stdio.h>

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
