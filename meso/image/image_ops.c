/* Crop, majority downsampling and padding. Each allocates a new image and keeps the label map. */
#include "mdpore_image.h"

#include <limits.h>
#include <stdio.h>
#include <string.h>

int mdp_image_crop(const mdp_image_t *in, const int lo[3], const int size[3], mdp_image_t *out,
                   char *err) {
  const int n[3] = {in->nx, in->ny, in->nz};
  for (int a = 0; a < 3; a++)
    if (lo[a] < 0 || size[a] < 1 || lo[a] + size[a] > n[a]) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "crop along %c: start %d size %d does not fit in the image's %d voxels", 'x' + a,
               lo[a], size[a], n[a]);
      return 1;
    }
  if (mdp_image_alloc_beside(out, size[0], size[1], size[2], (double)mdp_image_count(in), err))
    return 1;
  mdp_image_copy_meta(out, in);
  for (int k = 0; k < size[2]; k++)
    for (int j = 0; j < size[1]; j++)
      memcpy(out->label + mdp_image_index(out, 0, j, k),
             in->label + mdp_image_index(in, lo[0], lo[1] + j, lo[2] + k), (size_t)size[0]);
  return 0;
}

int mdp_image_concat(const mdp_image_t *a, const mdp_image_t *b, int axis, mdp_image_t *out,
                     char *err) {
  const int na[3] = {a->nx, a->ny, a->nz}, nb[3] = {b->nx, b->ny, b->nz};
  for (int d = 0; d < 3; d++)
    if (d != axis && na[d] != nb[d]) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "stack along %c: the images differ along %c (%d and %d voxels); every axis but "
               "the stacking one must match",
               'x' + axis, 'x' + d, na[d], nb[d]);
      return 1;
    }
  if (memcmp(a->phase_of, b->phase_of, sizeof a->phase_of)) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "stack: the images have different label maps (give --labels so that they agree)");
    return 1;
  }
  if (a->voxel_size != b->voxel_size || strcmp(a->unit, b->unit)) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "stack: different voxel sizes (%g %s and %g %s)",
             a->voxel_size, a->unit, b->voxel_size, b->unit);
    return 1;
  }
  int n[3] = {na[0], na[1], na[2]};
  if ((long long)n[axis] + nb[axis] > INT_MAX) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "stack along %c: %d + %d voxels overflow", 'x' + axis,
             na[axis], nb[axis]);
    return 1;
  }
  n[axis] += nb[axis];
  if (mdp_image_alloc_beside(out, n[0], n[1], n[2],
                             (double)mdp_image_count(a) + (double)mdp_image_count(b), err))
    return 1;
  mdp_image_copy_meta(out, a);
  for (int k = 0; k < n[2]; k++)
    for (int j = 0; j < n[1]; j++)
      for (int i = 0; i < n[0]; i++) {
        int c[3] = {i, j, k};
        const mdp_image_t *src = c[axis] < na[axis] ? a : b;
        if (src == b) c[axis] -= na[axis];
        out->label[mdp_image_index(out, i, j, k)] =
            src->label[mdp_image_index(src, c[0], c[1], c[2])];
      }
  return 0;
}

int mdp_image_downsample(const mdp_image_t *in, int f, mdp_image_t *out, char *err) {
  if (f < 1 || in->nx < f || in->ny < f || in->nz < f) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "downsample factor %d: must be >= 1 and <= every dimension (%dx%dx%d)", f, in->nx,
             in->ny, in->nz);
    return 1;
  }
  if (mdp_image_alloc_beside(out, in->nx / f, in->ny / f, in->nz / f, (double)mdp_image_count(in),
                             err))
    return 1;
  mdp_image_copy_meta(out, in);
  out->voxel_size = in->voxel_size * f;
  for (int k = 0; k < out->nz; k++)
    for (int j = 0; j < out->ny; j++)
      for (int i = 0; i < out->nx; i++) {
        int count[256] = {0};
        for (int c = 0; c < f; c++)
          for (int b = 0; b < f; b++)
            for (int a = 0; a < f; a++)
              count[in->label[mdp_image_index(in, f * i + a, f * j + b, f * k + c)]]++;
        int best = 0;
        for (int v = 1; v < 256; v++)
          if (count[v] > count[best]) best = v; /* strict: ties keep the smaller value */
        out->label[mdp_image_index(out, i, j, k)] = (uint8_t)best;
      }
  return 0;
}

int mdp_image_pad(const mdp_image_t *in, const int w[6], uint8_t label, mdp_image_t *out,
                  char *err) {
  for (int s = 0; s < 6; s++)
    if (w[s] < 0) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "pad width %d on side %d: must be >= 0", w[s], s);
      return 1;
    }
  if (in->phase_of[label] == MDP_PHASE_UNSET) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "pad label %d is not in the image's label map", label);
    return 1;
  }
  long long n[3];
  for (int a = 0; a < 3; a++) {
    n[a] = (long long)(a == 0 ? in->nx : a == 1 ? in->ny : in->nz) + w[2 * a] + w[2 * a + 1];
    if (n[a] > INT_MAX) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "pad widths %d and %d along %c: the padded image would have %lld voxels along it "
               "(expected at most %d)",
               w[2 * a], w[2 * a + 1], "xyz"[a], n[a], INT_MAX);
      return 1;
    }
  }
  if (mdp_image_alloc_beside(out, (int)n[0], (int)n[1], (int)n[2], (double)mdp_image_count(in),
                             err))
    return 1;
  mdp_image_copy_meta(out, in);
  memset(out->label, label, mdp_image_count(out));
  for (int k = 0; k < in->nz; k++)
    for (int j = 0; j < in->ny; j++)
      memcpy(out->label + mdp_image_index(out, w[0], j + w[2], k + w[4]),
             in->label + mdp_image_index(in, 0, j, k), (size_t)in->nx);
  return 0;
}
