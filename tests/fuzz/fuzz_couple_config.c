/* Fuzz entry: a `mdpore couple` configuration (docs/coupling.md) through couple_config_read. */
#include "couple.h"
#include "fuzz_util.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300];
  fuzz_path("couple.yaml", path, sizeof path);
  fuzz_write(path, data, size);
  couple_config c;
  fuzz_capture_begin();
  const int rc = couple_config_read(path, &c);
  const char *msg = fuzz_capture_end();
  couple_config_free(&c);
  fuzz_outcome(rc, msg, path);
  return 0;
}
