/* How periodic an image is along each axis (mdpore_image.h, docs/images.md): the pore overlap of
 * the two end slices, and percolation along the axis without and with the periodic wrap. With the
 * wrap, the clusters of the image (6-connected, no wrap) are joined across the seam by a weighted
 * union-find that keeps, per cluster, its winding offset (in periods along the axis) from its
 * root; a seam join between two clusters whose offsets already differ by other than one closes a
 * loop that winds around the axis, and every cluster of that component percolates (the lifting
 * argument of percolation on a torus, e.g. Machta, Phys. Rev. B 33 (1986) 4842; the same test as
 * Newman & Ziff's wrapping check, Phys. Rev. E 64 (2001) 016706). */
#include "image_internal.h"
#include "mdpore_image.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  int32_t *parent;
  int32_t *offset; /* winding of a cluster relative to its parent (periods along the axis) */
  uint8_t *winds;  /* per root: its component holds a loop around the axis */
} winding_forest_t;

/* Root of c; *shift = winding of c relative to the root (path compression keeps the offsets). */
static int32_t root_of(winding_forest_t *w, int32_t c, int32_t *shift) {
  int32_t s = 0, r = c;
  while (w->parent[r] != r) s += w->offset[r], r = w->parent[r];
  /* compress: point every cluster on the path at the root with its whole offset */
  int32_t rest = s;
  while (w->parent[c] != c) {
    const int32_t next = w->parent[c], own = w->offset[c];
    w->parent[c] = r;
    w->offset[c] = rest;
    rest -= own;
    c = next;
  }
  *shift = s;
  return r;
}

/* The seam joins cluster `last` (on slice n-1) to cluster `first` (on slice 0) of the next period:
 * winding(first) = winding(last) + 1 along that path. */
static void join_across_seam(winding_forest_t *w, int32_t last, int32_t first) {
  int32_t s_last, s_first;
  const int32_t r_last = root_of(w, last, &s_last), r_first = root_of(w, first, &s_first);
  if (r_last == r_first) {
    if (s_first != s_last + 1) w->winds[r_last] = 1;
    return;
  }
  w->parent[r_last] = r_first;
  w->offset[r_last] = s_first - 1 - s_last;
  w->winds[r_first] |= w->winds[r_last];
}

static void axis_periodicity(const mdp_image_t *img, const int32_t *cluster, int nc,
                             const long long *size, const uint8_t *faces, int a,
                             winding_forest_t *w, mdp_image_axis_periodicity_t *p) {
  const int dim[3] = {img->nx, img->ny, img->nz};
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const size_t stride[3] = {1, (size_t)dim[0], (size_t)dim[0] * (size_t)dim[1]};
  memset(p, 0, sizeof *p);
  for (int i = 0; i < nc; i++) w->parent[i] = i, w->offset[i] = 0, w->winds[i] = 0;
  p->face_voxels = (long long)dim[b] * dim[c];
  for (int kc = 0; kc < dim[c]; kc++)
    for (int kb = 0; kb < dim[b]; kb++) {
      const size_t base = (size_t)kb * stride[b] + (size_t)kc * stride[c];
      const int32_t first = cluster[base], last = cluster[base + (size_t)(dim[a] - 1) * stride[a]];
      p->pore_first += first >= 0;
      p->pore_last += last >= 0;
      p->pore_both += first >= 0 && last >= 0;
      p->pore_either += first >= 0 || last >= 0;
      if (first >= 0 && last >= 0) join_across_seam(w, last, first);
    }
  p->overlap = p->pore_either ? (double)p->pore_both / (double)p->pore_either : 0.0;
  p->overlap_face = (double)p->pore_both / (double)p->face_voxels;
  const unsigned both_faces = 3u << (2 * a);
  for (int i = 0; i < nc; i++) {
    int32_t shift;
    const int wraps = w->winds[root_of(w, i, &shift)];
    const int open = (faces[i] & both_faces) == both_faces;
    if (open) p->percolates_open = 1, p->connected_open += size[i];
    if (wraps) p->percolates_wrap = 1, p->connected_wrap += size[i];
    if (wraps && !open) p->wrap_only_clusters++, p->wrap_only_voxels += size[i];
    if (open && !wraps) p->seam_blocked_clusters++, p->seam_blocked_voxels += size[i];
  }
}

int mdp_image_periodicity(const mdp_image_t *img, mdp_image_axis_periodicity_t per[3], char *err) {
  const size_t n = mdp_image_count(img);
  /* the labels (4 bytes a voxel) beside the image's byte, against the memory limit */
  if (mdp_image_check_memory(5.0 * (double)n, "image", "its cluster labels (4 bytes a voxel)", err))
    return 1;
  int32_t *cluster = malloc(n * sizeof *cluster);
  int nc = 0, rc = 1;
  long long *size = NULL;
  uint8_t *faces = NULL;
  winding_forest_t w = {NULL, NULL, NULL};
  if (!cluster) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "periodicity: out of memory for %zu cluster labels", n);
    return 1;
  }
  if (mdp_image_label_clusters(img, cluster, &nc, err)) goto done;
  size = calloc((size_t)nc + 1, sizeof *size);
  faces = calloc((size_t)nc + 1, 1); /* bit 2a: face 0 of axis a, bit 2a+1: face n-1 */
  w.parent = malloc(((size_t)nc + 1) * sizeof *w.parent);
  w.offset = malloc(((size_t)nc + 1) * sizeof *w.offset);
  w.winds = malloc((size_t)nc + 1);
  if (!size || !faces || !w.parent || !w.offset || !w.winds) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "periodicity: out of memory for %d clusters", nc);
    goto done;
  }
  const int dim[3] = {img->nx, img->ny, img->nz};
  for (int k = 0; k < dim[2]; k++)
    for (int j = 0; j < dim[1]; j++)
      for (int i = 0; i < dim[0]; i++) {
        const int32_t c = cluster[mdp_image_index(img, i, j, k)];
        if (c < 0) continue;
        size[c]++;
        const int ijk[3] = {i, j, k};
        for (int a = 0; a < 3; a++) {
          if (ijk[a] == 0) faces[c] |= (uint8_t)(1u << (2 * a));
          if (ijk[a] == dim[a] - 1) faces[c] |= (uint8_t)(1u << (2 * a + 1));
        }
      }
  for (int a = 0; a < 3; a++) axis_periodicity(img, cluster, nc, size, faces, a, &w, &per[a]);
  rc = 0;
done:
  free(cluster), free(size), free(faces), free(w.parent), free(w.offset), free(w.winds);
  return rc;
}
