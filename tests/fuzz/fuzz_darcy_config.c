/* Fuzz entry: a `mdpore darcy` configuration (docs/darcy-config.md) through darcy_config_read, or
 * through darcy_config_read_upscale (`mdpore darcy --upscale`) when the last byte is odd. */
#include "darcy/darcy_config.h"
#include "fuzz_util.h"

#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300];
  fuzz_path("darcy.yaml", path, sizeof path);
  fuzz_write(path, data, size);
  const int upscale = size > 0 && (data[size - 1] & 1);
  darcy_config c;
  fuzz_capture_begin();
  const int rc = upscale ? darcy_config_read_upscale(path, &c, 0) : darcy_config_read(path, &c, 0);
  const char *msg = fuzz_capture_end();
  if (rc == 0) {
    darcy_problem_free(&c.problem);
    twophase_config_free(&c.twophase); /* output_times, a relperm table */
  }
  fuzz_outcome(rc, msg, path);
  return 0;
}
