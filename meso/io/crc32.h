/* CRC-32 (IEEE 802.3, the polynomial of zlib and PNG, reflected 0xEDB88320) of byte buffers: the
 * checkpoint's per-dataset checksums (io/checkpoint.c). */
#ifndef MESO_IO_CRC32_H
#define MESO_IO_CRC32_H

#include <stddef.h>
#include <stdint.h>

/* Continue a CRC over `len` more bytes (start with crc = 0). Same value as zlib's crc32(). */
uint32_t crc32_update(uint32_t crc, const void *data, size_t len);

#endif
