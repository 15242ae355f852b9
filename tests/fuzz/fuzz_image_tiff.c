/* Fuzz entry: a TIFF stack (one multi-page file) through mdp_image_read. */
#include "fuzz_image_box.h"
#include "fuzz_util.h"
#include "mdpore_image.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300], err[MDP_IMAGE_ERR_LEN] = "";
  fuzz_path("image.tif", path, sizeof path);
  fuzz_write(path, data, size);
  mdp_image_read_opts_t o;
  mdp_image_read_opts_init(&o);
  mdp_image_t img;
  const int rc = mdp_image_read(path, &o, &img, err);
  fuzz_image_box_check(path, &o, rc == 0 ? &img : NULL); /* before the outcome replay judges */
  if (rc == 0) mdp_image_free(&img);
  fuzz_outcome(rc, err, path);
  return 0;
}
