/* Partial reads (mdpore_image.h): the format of the file as mdp_image_read chooses it, the box
 * checked against the image's size, then the format's own box reader, and the labels of the box
 * checked against the map with the voxel named in the whole image's coordinates. A rank of the wall
 * builder reads only the voxels it needs this way (meso/populate/image_window.c). */
#include "mdpore_image.h"

#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

static int ends_with(const char *s, const char *ext) {
  size_t n = strlen(s), m = strlen(ext);
  return n >= m && !strcasecmp(s + n - m, ext);
}

int mdp_image_read_box(const char *path, const mdp_image_read_opts_t *opts, const int lo[3],
                       const int size[3], mdp_image_t *img, int dims[3], char *err) {
  memset(img, 0, sizeof *img);
  const char *fmt = opts->format;
  struct stat sb;
  if (stat(path, &sb) != 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: no such file or folder", path);
    return 1;
  }
  if (!fmt[0]) {
    if (ends_with(path, ".h5") || ends_with(path, ".hdf5") || ends_with(path, ".hdf"))
      fmt = "hdf5";
    else if (ends_with(path, ".tif") || ends_with(path, ".tiff") || S_ISDIR(sb.st_mode))
      fmt = "tiff";
    else
      fmt = "raw";
  }
  int (*reader)(const char *, const mdp_image_read_opts_t *, const mdp_image_box_t *, mdp_image_t *,
                int[3], char *) = !strcmp(fmt, "hdf5")   ? mdp_image_read_hdf5_box
                                  : !strcmp(fmt, "tiff") ? mdp_image_read_tiff_box
                                  : !strcmp(fmt, "raw")  ? mdp_image_read_raw_box
                                                         : NULL;
  if (!reader) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: unknown format '%s' (expected raw, hdf5 or tiff)", path,
             fmt);
    return 1;
  }
  /* the size first (cheap for every format), so that the box is checked before anything is read */
  int n[3];
  mdp_image_box_t box = {{0, 0, 0}, {0, 0, 0}};
  if (reader(path, opts, &box, img, n, err)) return 1;
  if (dims) memcpy(dims, n, sizeof n);
  if (!size) return 0;
  for (int d = 0; d < 3; d++) {
    if (lo[d] < 0 || size[d] < 1 || lo[d] > n[d] - size[d]) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "%s: box %c %d..%d: expected voxels inside the image's %d x %d x %d (got %d..%d)",
               path, "xyz"[d], lo[d], lo[d] + size[d] - 1, n[0], n[1], n[2], lo[d],
               lo[d] + size[d] - 1);
      return 1;
    }
    box.lo[d] = lo[d], box.size[d] = size[d];
  }
  if (reader(path, opts, &box, img, NULL, err)) return 1;
  const size_t count = mdp_image_count(img);
  for (size_t idx = 0; idx < count; idx++) {
    if (img->phase_of[img->label[idx]] != MDP_PHASE_UNSET) continue;
    const int i = (int)(idx % (size_t)img->nx), j = (int)(idx / (size_t)img->nx % (size_t)img->ny);
    const int k = (int)(idx / ((size_t)img->nx * (size_t)img->ny));
    char map[512];
    mdp_image_format_labels(img->phase_of, map, sizeof map);
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: voxel (%d,%d,%d) has label %d, which the label map '%s' does not name (give it "
             "with --labels, e.g. --labels pore=0,inorganic=1,%d)",
             path, lo[0] + i, lo[1] + j, lo[2] + k, img->label[idx], map, img->label[idx]);
    mdp_image_free(img);
    return 1;
  }
  return 0;
}
