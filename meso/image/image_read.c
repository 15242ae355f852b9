/* Format dispatch: choose the reader from --format or the file name. */
#include "mdpore_image.h"

#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

static int ends_with(const char *s, const char *ext) {
  size_t n = strlen(s), m = strlen(ext);
  return n >= m && !strcasecmp(s + n - m, ext);
}

int mdp_image_read(const char *path, const mdp_image_read_opts_t *opts, mdp_image_t *img,
                   char *err) {
  const char *fmt = opts->format;
  struct stat sb;
  if (!fmt[0]) {
    if (ends_with(path, ".h5") || ends_with(path, ".hdf5") || ends_with(path, ".hdf"))
      fmt = "hdf5";
    else if (ends_with(path, ".tif") || ends_with(path, ".tiff") ||
             (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)))
      fmt = "tiff";
    else
      fmt = "raw";
  }
  if (stat(path, &sb) != 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: no such file or folder", path);
    return 1;
  }
  if (!strcmp(fmt, "hdf5")) return mdp_image_read_hdf5(path, opts, img, err);
  if (!strcmp(fmt, "tiff")) return mdp_image_read_tiff(path, opts, img, err);
  if (!strcmp(fmt, "raw")) return mdp_image_read_raw(path, opts, img, err);
  snprintf(err, MDP_IMAGE_ERR_LEN, "%s: unknown format '%s' (expected raw, hdf5 or tiff)", path,
           fmt);
  return 1;
}
