/* Fuzz entry: a scene file through scene_load (the YAML walk and every effect's option parser). */
#include "effects/scene_load.h"
#include "fuzz_util.h"

#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300];
  fuzz_path("scene.yaml", path, sizeof path);
  fuzz_write(path, data, size);
  scene_t *s = malloc(sizeof *s); /* large: not on the stack */
  if (!s) abort();
  fuzz_capture_begin();
  const int rc = scene_load(path, s);
  fuzz_outcome(rc, fuzz_capture_end(), path);
  free(s);
  return 0;
}
