/* The partial read (mdp_image_read_box, used by the rank-local geometry build) on the same input as
 * the whole read of an image fuzz entry: the dims-only query and the central box (a quarter in from
 * each face, half of each axis, at least one voxel) must be refused with a message naming the file
 * or accepted; accepted after an accepted whole read, the box must hold the whole image's labels
 * (else abort: a finding). Header-only, so the image entries need no other source file. */
#ifndef MDPORE_TESTS_FUZZ_IMAGE_BOX_H
#define MDPORE_TESTS_FUZZ_IMAGE_BOX_H

#include "fuzz_util.h"
#include "mdpore_image.h"

#include <stdio.h>
#include <stdlib.h>

static void fuzz_image_box_check(const char *path, const mdp_image_read_opts_t *o,
                                 const mdp_image_t *whole) {
  char err[MDP_IMAGE_ERR_LEN] = "";
  int dims[3], lo[3], size[3];
  mdp_image_t box;
  int rc = mdp_image_read_box(path, o, NULL, NULL, &box, dims, err);
  fuzz_outcome(rc, err, path);
  if (rc) return;
  for (int d = 0; d < 3; d++) {
    lo[d] = dims[d] / 4;
    size[d] = dims[d] / 2 > 0 ? dims[d] / 2 : 1;
  }
  err[0] = 0;
  rc = mdp_image_read_box(path, o, lo, size, &box, dims, err);
  fuzz_outcome(rc, err, path);
  if (rc) return;
  if (whole)
    for (int k = 0; k < size[2]; k++)
      for (int j = 0; j < size[1]; j++)
        for (int i = 0; i < size[0]; i++)
          if (box.label[mdp_image_index(&box, i, j, k)] !=
              whole->label[mdp_image_index(whole, lo[0] + i, lo[1] + j, lo[2] + k)]) {
            fprintf(stderr,
                    "fuzz: %s: the box read differs from the whole read at voxel (%d,%d,%d)\n",
                    path, lo[0] + i, lo[1] + j, lo[2] + k);
            abort();
          }
  mdp_image_free(&box);
}

#endif
