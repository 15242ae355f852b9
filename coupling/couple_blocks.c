/* The blocks of a coupling run: the sample image cut into blocks[0] x blocks[1] x blocks[2] equal
 * boxes (or one image per block), each written as HDF5 under WORKDIR/blocks/bI_J_K/ with a file name
 * that carries a hash of its voxels (the campaigns' cache keys hold the image's bytes as well). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "campaign.h"
#include "common/atomic_file.h"
#include "couple.h"
#include "mdpore_image.h"

static int read_image(const couple_config *c, const char *path, mdp_image_t *img) {
  mdp_image_read_opts_t ro;
  mdp_image_read_opts_init(&ro);
  char err[1024] = "";
  if (c->image_labels[0]) snprintf(ro.labels, sizeof ro.labels, "%s", c->image_labels);
  if (c->image_voxel_size[0] &&
      mdp_image_parse_voxel_size(c->image_voxel_size, &ro.voxel_size, ro.unit, err)) {
    fprintf(stderr, "mdpore couple: %s: key 'image_voxel_size': %s\n", c->path, err);
    return -1;
  }
  if (mdp_image_read(path, &ro, img, err)) {
    fprintf(stderr, "mdpore couple: %s: %s\n", path, err);
    return -1;
  }
  return 0;
}

/* Writes the block image (unless the same file exists) and measures it. */
static int store_block(const couple_config *c, mdp_image_t *img, couple_block *b) {
  uint64_t h = camp_fnv1a(14695981039346656037ULL, img->label, mdp_image_count(img));
  h = camp_fnv1a(h, img->phase_of, sizeof img->phase_of);
  int dims[3] = {img->nx, img->ny, img->nz};
  h = camp_fnv1a(h, dims, sizeof dims);
  char dir[COUPLE_PATH + 64], err[1024] = "";
  snprintf(dir, sizeof dir, "%.4000s/blocks/b%d_%d_%d", c->workdir, b->index[0], b->index[1],
           b->index[2]);
  if (make_dirs(dir)) return -1;
  snprintf(b->image, sizeof b->image, "%.4000s/image-%016llx.h5", dir, (unsigned long long)h);
  snprintf(b->workdir, sizeof b->workdir, "%.4000s/campaign", dir);
  if (access(b->image, R_OK) && mdp_image_write_hdf5(img, b->image, err)) {
    fprintf(stderr, "mdpore couple: %s: %s\n", b->image, err);
    return -1;
  }
  mdp_image_stats_t st;
  if (mdp_image_stats(img, &st, err)) {
    fprintf(stderr, "mdpore couple: %s: %s\n", b->image, err);
    return -1;
  }
  b->porosity = st.porosity;
  b->percolates = st.spans[c->axis];
  for (int a = 0; a < 3; a++) b->spans[a] = st.spans[a];
  /* campaign.axes: all measures every cross axis with faces between blocks from the start */
  for (int a = 0; a < 3; a++)
    if (c->axes == COUPLE_AXES_ALL && a != c->axis && c->blocks[a] > 1)
      b->cross_state[a] = b->spans[a] ? CROSS_WANTED : CROSS_NO_SPAN;
  return 0;
}

int couple_make_blocks(const couple_config *c, couple_block *blocks, double block_size[3]) {
  int nb = c->blocks[0] * c->blocks[1] * c->blocks[2];
  int rc = -1;
  mdp_image_t whole = {0};
  int first_dims[3] = {0, 0, 0};
  double first_voxel_m = 0.0;
  if (c->image[0] && read_image(c, c->image, &whole)) return -1;
  int dims[3] = {whole.nx, whole.ny, whole.nz};
  int size[3];
  if (c->image[0])
    for (int a = 0; a < 3; a++) {
      if (dims[a] % c->blocks[a]) {
        fprintf(stderr,
                "mdpore couple: %s: key 'blocks': expected block counts that divide the image "
                "(%d x %d x %d voxels) evenly (got %d blocks along %c: %d voxels do not split)\n",
                c->path, dims[0], dims[1], dims[2], c->blocks[a], 'x' + a, dims[a]);
        goto out;
      }
      size[a] = dims[a] / c->blocks[a];
    }
  for (int b = 0; b < nb; b++) {
    couple_block *B = &blocks[b];
    memset(B, 0, sizeof *B);
    B->n_extra_run = -1;
    B->index[0] = b % c->blocks[0];
    B->index[1] = (b / c->blocks[0]) % c->blocks[1];
    B->index[2] = b / (c->blocks[0] * c->blocks[1]);
    mdp_image_t part = {0};
    char err[1024] = "";
    if (c->image[0]) {
      int lo[3] = {B->index[0] * size[0], B->index[1] * size[1], B->index[2] * size[2]};
      if (mdp_image_crop(&whole, lo, size, &part, err)) {
        fprintf(stderr, "mdpore couple: %s: %s\n", c->image, err);
        goto out;
      }
    } else if (read_image(c, c->block_image[b], &part)) {
      goto out;
    }
    int pd[3] = {part.nx, part.ny, part.nz};
    if (b == 0) memcpy(first_dims, pd, sizeof pd);
    if (memcmp(first_dims, pd, sizeof pd)) {
      fprintf(stderr,
              "mdpore couple: %s: key 'block_images[%d]': expected %d x %d x %d voxels like the "
              "first block (got %d x %d x %d): blocks are equal boxes of the continuum grid\n",
              c->path, b, first_dims[0], first_dims[1], first_dims[2], pd[0], pd[1], pd[2]);
      mdp_image_free(&part);
      goto out;
    }
    /* block images at different voxel sizes are different physical boxes: refused unless the
     * config's image_voxel_size gives them one size */
    const double voxel_m = mdp_image_voxel_size_m(&part);
    if (b == 0) {
      first_voxel_m = voxel_m;
    } else if (!c->image[0] && ((voxel_m == 0.0) != (first_voxel_m == 0.0) ||
                                fabs(voxel_m - first_voxel_m) > 1e-9 * first_voxel_m)) {
      fprintf(stderr,
              "mdpore couple: %s: key 'block_images[%d]': expected the voxel size of the first "
              "block (%g m; got %g m in %s; 0 = no physical size): blocks of different voxel "
              "sizes are not equal boxes; set image_voxel_size to read every block at one size\n",
              c->path, b, first_voxel_m, voxel_m, c->block_image[b]);
      mdp_image_free(&part);
      goto out;
    }
    int bad = store_block(c, &part, B);
    mdp_image_free(&part);
    if (bad) goto out;
  }
  for (int a = 0; a < 3; a++) block_size[a] = first_dims[a] * c->rc_per_voxel;
  rc = 0;
out:
  if (c->image[0]) mdp_image_free(&whole);
  return rc;
}
