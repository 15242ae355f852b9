/* CRC-32, table-driven (see crc32.h). */
#include "io/crc32.h"

#include <pthread.h>

static uint32_t table[256];
static pthread_once_t table_once = PTHREAD_ONCE_INIT; /* threads (replicas) may ask at once */

static void make_table(void) {
  for (uint32_t n = 0; n < 256; n++) {
    uint32_t c = n;
    for (int k = 0; k < 8; k++) c = c & 1u ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
}

uint32_t crc32_update(uint32_t crc, const void *data, size_t len) {
  pthread_once(&table_once, make_table);
  const unsigned char *b = data;
  crc = ~crc;
  for (size_t i = 0; i < len; i++) crc = table[(crc ^ b[i]) & 0xffu] ^ (crc >> 8);
  return ~crc;
}
