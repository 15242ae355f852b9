/* Reordering the axes of an image (mdpore_image.h: mdp_image_permute_axes). */
#include "mdpore_image.h"

#include <stdio.h>
#include <string.h>

int mdp_image_permute_axes(const mdp_image_t *in, const int axis_map[3], mdp_image_t *out,
                           char *err) {
  const int n_in[3] = {in->nx, in->ny, in->nz};
  int used[3] = {0, 0, 0};
  for (int d = 0; d < 3; d++) {
    if (axis_map[d] < 0 || axis_map[d] > 2 || used[axis_map[d]]++) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "axis map (%d, %d, %d): expected a permutation of the image axes 0, 1, 2",
               axis_map[0], axis_map[1], axis_map[2]);
      return 1;
    }
  }
  if (mdp_image_alloc_beside(out, n_in[axis_map[0]], n_in[axis_map[1]], n_in[axis_map[2]],
                             (double)mdp_image_count(in), err))
    return 1;
  if (mdp_image_copy_meta(out, in)) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "axis map: copying the image metadata failed");
    mdp_image_free(out);
    return 1;
  }
  int src[3];
  for (int k = 0; k < out->nz; k++)
    for (int j = 0; j < out->ny; j++)
      for (int i = 0; i < out->nx; i++) {
        const int dst[3] = {i, j, k};
        for (int d = 0; d < 3; d++) src[axis_map[d]] = dst[d];
        out->label[mdp_image_index(out, i, j, k)] =
            in->label[mdp_image_index(in, src[0], src[1], src[2])];
      }
  return 0;
}
