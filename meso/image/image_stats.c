/* Porosity and pore connectivity: 6-connected clusters of pore voxels by union-find (path halving,
 * union by index), then per cluster which box faces it touches. A cluster "spans" an axis when it
 * touches both faces normal to it (inlet and outlet of a flow along that axis). */
#include "image_internal.h"
#include "mdpore_image.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int32_t find(int32_t *parent, int32_t a) {
  while (parent[a] != a) {
    parent[a] = parent[parent[a]];
    a = parent[a];
  }
  return a;
}

static void unite(int32_t *parent, int32_t a, int32_t b) {
  a = find(parent, a);
  b = find(parent, b);
  if (a < b)
    parent[b] = a;
  else if (b < a)
    parent[a] = b;
}

int mdp_image_label_clusters(const mdp_image_t *img, int32_t *cluster, int *n_clusters, char *err) {
  size_t n = mdp_image_count(img);
  if (n > (size_t)INT32_MAX) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "image of %zu voxels is too large for cluster labelling", n);
    return 1;
  }
  const size_t sx = 1, sy = (size_t)img->nx, sz = (size_t)img->nx * img->ny;
  for (size_t idx = 0; idx < n; idx++)
    cluster[idx] = mdp_image_is_pore(img, idx) ? (int32_t)idx : -1;
  for (int k = 0; k < img->nz; k++)
    for (int j = 0; j < img->ny; j++)
      for (int i = 0; i < img->nx; i++) {
        size_t idx = mdp_image_index(img, i, j, k);
        if (cluster[idx] < 0) continue;
        if (i > 0 && cluster[idx - sx] >= 0) unite(cluster, (int32_t)idx, (int32_t)(idx - sx));
        if (j > 0 && cluster[idx - sy] >= 0) unite(cluster, (int32_t)idx, (int32_t)(idx - sy));
        if (k > 0 && cluster[idx - sz] >= 0) unite(cluster, (int32_t)idx, (int32_t)(idx - sz));
      }
  /* Renumber clusters 0..n_clusters-1 in order of their first voxel. Union by index makes every
   * root the smallest index of its cluster, so a root is met before the rest of its cluster. */
  for (size_t idx = 0; idx < n; idx++)
    if (cluster[idx] >= 0) cluster[idx] = find(cluster, (int32_t)idx);
  int nc = 0;
  for (size_t idx = 0; idx < n; idx++) {
    int32_t r = cluster[idx];
    if (r < 0) continue;
    cluster[idx] = (size_t)r == idx ? -2 - nc++ : cluster[r]; /* -2 - id: already renumbered */
  }
  for (size_t idx = 0; idx < n; idx++)
    if (cluster[idx] <= -2) cluster[idx] = -2 - cluster[idx];
  *n_clusters = nc;
  return 0;
}

int mdp_image_stats(const mdp_image_t *img, mdp_image_stats_t *st, char *err) {
  memset(st, 0, sizeof *st);
  size_t n = mdp_image_count(img);
  st->n_voxels = (long long)n;
  for (size_t idx = 0; idx < n; idx++) {
    int p = mdp_image_phase(img, idx);
    st->n_pore += p == MDP_PHASE_PORE;
    st->n_organic += p == MDP_PHASE_ORGANIC;
    st->n_inorganic += p == MDP_PHASE_INORGANIC;
  }
  st->porosity = (double)st->n_pore / (double)n;
  /* the labels (4 bytes a voxel) beside the image's byte, against the memory limit */
  if (mdp_image_check_memory(5.0 * (double)n, "image", "its cluster labels (4 bytes a voxel)", err))
    return 1;
  int32_t *cl = malloc(n * sizeof *cl);
  if (!cl) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "out of memory for cluster labels (%zu voxels)", n);
    return 1;
  }
  int nc = 0;
  if (mdp_image_label_clusters(img, cl, &nc, err)) {
    free(cl);
    return 1;
  }
  st->n_clusters = nc;
  unsigned char *faces =
      calloc((size_t)nc + 1, 1); /* bit 2a: face 0 of axis a; bit 2a+1: face n-1 */
  long long *size = calloc((size_t)nc + 1, sizeof *size);
  if (!faces || !size) {
    free(cl), free(faces), free(size);
    snprintf(err, MDP_IMAGE_ERR_LEN, "out of memory for %d clusters", nc);
    return 1;
  }
  const int dim[3] = {img->nx, img->ny, img->nz};
  for (int k = 0; k < img->nz; k++)
    for (int j = 0; j < img->ny; j++)
      for (int i = 0; i < img->nx; i++) {
        int32_t c = cl[mdp_image_index(img, i, j, k)];
        if (c < 0) continue;
        size[c]++;
        const int ijk[3] = {i, j, k};
        for (int a = 0; a < 3; a++) {
          if (ijk[a] == 0) faces[c] |= (unsigned char)(1u << (2 * a));
          if (ijk[a] == dim[a] - 1) faces[c] |= (unsigned char)(1u << (2 * a + 1));
        }
      }
  for (int c = 0; c < nc; c++) {
    int any = 0;
    for (int a = 0; a < 3; a++) {
      unsigned both = 3u << (2 * a);
      if ((faces[c] & both) == both) {
        st->spans[a] = 1;
        st->connected_voxels[a] += size[c];
        any = 1;
      }
    }
    if (!any) st->n_nonspanning_clusters++, st->nonspanning_voxels += size[c];
    if (!faces[c]) st->n_isolated_clusters++, st->isolated_voxels += size[c];
    if (size[c] > st->largest_cluster) st->largest_cluster = size[c];
  }
  for (int a = 0; a < 3; a++)
    st->connected_porosity[a] = (double)st->connected_voxels[a] / (double)n;
  free(cl), free(faces), free(size);
  return 0;
}

int mdp_image_require_percolation(const mdp_image_t *img, const mdp_image_stats_t *st, int axis,
                                  const char *source, char *err) {
  if (st->n_pore == 0) {
    char map[512];
    mdp_image_format_labels(img->phase_of, map, sizeof map);
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: empty pore space: no voxel is labelled pore under the label map '%s'", source,
             map);
    return 1;
  }
  if (!st->spans[axis]) {
    snprintf(
        err, MDP_IMAGE_ERR_LEN,
        "%s: axis %c does not percolate: no pore cluster connects the %c = 0 face to the %c = %d "
        "face (%d clusters, largest %lld voxels); choose another axis or a larger crop",
        source, 'x' + axis, 'x' + axis, 'x' + axis,
        (axis == 0   ? img->nx
         : axis == 1 ? img->ny
                     : img->nz) -
            1,
        st->n_clusters, st->largest_cluster);
    return 1;
  }
  return 0;
}
