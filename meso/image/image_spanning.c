/* Dropping pore clusters that do not span a flow axis: they carry no flow, and a closed pore region
 * has an undetermined pressure for a continuum solver and traps fluid for a particle one. */
#include "image_internal.h"
#include "mdpore_image.h"

#include <stdio.h>
#include <stdlib.h>

int mdp_image_drop_nonspanning(mdp_image_t *img, int axis, long long *dropped, char *err) {
  *dropped = 0;
  if (axis < 0 || axis > 2) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "flow axis %d: expected 0 (x), 1 (y) or 2 (z)", axis);
    return 1;
  }
  size_t n = mdp_image_count(img);
  /* the labels (4 bytes a voxel) beside the image's byte, against the memory limit */
  if (mdp_image_check_memory(5.0 * (double)n, "image", "its cluster labels (4 bytes a voxel)", err))
    return 1;
  int32_t *cl = malloc((n ? n : 1) * sizeof *cl); /* cluster id of each voxel, -1 for solid */
  if (!cl) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "out of memory for cluster labels (%zu voxels)", n);
    return 1;
  }
  int nc = 0;
  if (mdp_image_label_clusters(img, cl, &nc, err)) {
    free(cl);
    return 1;
  }
  unsigned char *faces = calloc((size_t)nc + 1, 1); /* bit 1: touches face 0, bit 2: face n-1 */
  if (!faces) {
    free(cl);
    snprintf(err, MDP_IMAGE_ERR_LEN, "out of memory for %d clusters", nc);
    return 1;
  }
  int solid = -1; /* label given to dropped voxels: that of the last solid voxel met */
  const int dim[3] = {img->nx, img->ny, img->nz};
  for (int k = 0; k < img->nz; k++)
    for (int j = 0; j < img->ny; j++)
      for (int i = 0; i < img->nx; i++) {
        size_t idx = mdp_image_index(img, i, j, k);
        const int ijk[3] = {i, j, k};
        if (cl[idx] < 0) {
          solid = img->label[idx];
          continue;
        }
        if (ijk[axis] == 0) faces[cl[idx]] |= 1;
        if (ijk[axis] == dim[axis] - 1) faces[cl[idx]] |= 2;
      }
  /* Without a solid voxel the pore space is one cluster touching every face: nothing to drop. */
  for (size_t idx = 0; idx < n; idx++)
    if (cl[idx] >= 0 && faces[cl[idx]] != 3) {
      img->label[idx] = (uint8_t)solid;
      (*dropped)++;
    }
  free(cl);
  free(faces);
  return 0;
}
