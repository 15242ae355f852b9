/* Fuzz entry: a raw image with its sidecar header (docs/images.md) through mdp_image_read. The
 * input is the sidecar text, a line "%%", then the voxel bytes; without that line the whole input is
 * the sidecar and the data file is empty. */
#include "fuzz_image_box.h"
#include "fuzz_util.h"
#include "mdpore_image.h"

#include <stdio.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300], side[320], err[MDP_IMAGE_ERR_LEN] = "";
  fuzz_path("image.raw", path, sizeof path);
  snprintf(side, sizeof side, "%s.hdr", path);
  size_t split = size, skip = 0;
  for (size_t i = 0; i + 3 <= size; i++)
    if (!memcmp(data + i, "%%\n", 3) && (i == 0 || data[i - 1] == '\n')) {
      split = i, skip = 3;
      break;
    }
  fuzz_write(side, data, split);
  fuzz_write(path, data + split + skip, size - split - skip);
  mdp_image_read_opts_t o;
  mdp_image_read_opts_init(&o);
  mdp_image_t img;
  const int rc = mdp_image_read(path, &o, &img, err);
  fuzz_image_box_check(path, &o, rc == 0 ? &img : NULL); /* before the outcome replay judges */
  if (rc == 0) mdp_image_free(&img);
  fuzz_outcome(rc, err, path);
  return 0;
}
