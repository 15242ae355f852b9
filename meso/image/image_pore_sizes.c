/* Pore and throat sizes of the percolating pore space (mdpore_image.h, docs/images.md): the
 * inscribed diameter at each pore voxel from the exact distance transform (image_edt.c), and the
 * critical throat per axis, the breakthrough diameter of mercury intrusion (Katz & Thompson, Phys.
 * Rev. B 34 (1986) 8179): the largest ball diameter whose admissible centres still connect the two
 * faces normal to the axis. Digital balls of diameter d voxels are centred on voxel centres (d odd)
 * or voxel corners (d even) so that each is d voxels across and a slit of w voxels passes exactly
 * d = w; the centres of each parity are bisected on d with the cluster labelling of
 * mdp_image_stats. */
#include "image_internal.h"
#include "mdpore_image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 1 for each pore voxel in a cluster that touches both faces of some axis. */
static int mark_percolating(const mdp_image_t *img, uint8_t *in_space, char *err) {
  const size_t n = mdp_image_count(img);
  int32_t *cluster = malloc(n * sizeof *cluster);
  int nc = 0;
  if (!cluster) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "pore sizes: out of memory for %zu cluster labels", n);
    return 1;
  }
  if (mdp_image_label_clusters(img, cluster, &nc, err)) {
    free(cluster);
    return 1;
  }
  uint8_t *faces = calloc((size_t)nc + 1, 1); /* bit 2a: face 0 of axis a, bit 2a+1: face n-1 */
  if (!faces) {
    free(cluster);
    snprintf(err, MDP_IMAGE_ERR_LEN, "pore sizes: out of memory for %d clusters", nc);
    return 1;
  }
  const int dim[3] = {img->nx, img->ny, img->nz};
  for (int k = 0; k < dim[2]; k++)
    for (int j = 0; j < dim[1]; j++)
      for (int i = 0; i < dim[0]; i++) {
        const int32_t c = cluster[mdp_image_index(img, i, j, k)];
        if (c < 0) continue;
        const int ijk[3] = {i, j, k};
        for (int a = 0; a < 3; a++) {
          if (ijk[a] == 0) faces[c] |= (uint8_t)(1u << (2 * a));
          if (ijk[a] == dim[a] - 1) faces[c] |= (uint8_t)(1u << (2 * a + 1));
        }
      }
  for (size_t v = 0; v < n; v++) {
    const int32_t c = cluster[v];
    in_space[v] = 0;
    if (c < 0) continue;
    for (int a = 0; a < 3; a++)
      if (((faces[c] >> (2 * a)) & 3u) == 3u) in_space[v] = 1;
  }
  free(cluster), free(faces);
  return 0;
}

/* Quantiles and mean of D = sqrt(d4) - 1 over the voxels of the space (histogram of d4). */
static int diameter_stats(const uint32_t *d4, const uint8_t *in_space, size_t n,
                          mdp_image_pore_sizes_t *ps, char *err) {
  uint32_t top = 0;
  long long count = 0;
  for (size_t v = 0; v < n; v++)
    if (in_space[v]) {
      count++;
      if (d4[v] > top) top = d4[v];
    }
  ps->voxels = count;
  if (count == 0) return 0;
  if (top == MDP_EDT_NO_SOLID) { /* no solid voxel: nothing bounds a ball */
    ps->no_solid = 1;
    return 0;
  }
  long long *hist = calloc((size_t)top + 1, sizeof *hist);
  if (!hist) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "pore sizes: out of memory for a histogram of %u", top);
    return 1;
  }
  for (size_t v = 0; v < n; v++)
    if (in_space[v]) hist[d4[v]]++;
  static const double level[5] = {0.10, 0.25, 0.50, 0.75, 0.90};
  long long seen = 0;
  double sum = 0;
  int next = 0;
  for (uint32_t x = 0; x <= top; x++) {
    if (!hist[x]) continue;
    const double diameter = sqrt((double)x) - 1.0;
    seen += hist[x];
    sum += diameter * (double)hist[x];
    while (next < 5 && (double)seen >= level[next] * (double)count)
      ps->diameter_q[next++] = diameter;
  }
  ps->diameter_mean = sum / (double)count;
  ps->diameter_max = sqrt((double)top) - 1.0;
  free(hist);
  return 0;
}

/* Per axis the largest d of one parity (odd: d4 of the centres, even: of the corners) whose
 * admissible ball centres (d4 > d^2) percolate face to face: a bisection on d for the three axes at
 * once (each test labels the clusters once and answers every axis). best[a] becomes d where d is
 * larger. */
static int bisect_throats(const uint32_t *d4, int parity, mdp_image_t *mask, int best[3],
                          int *labellings, char *err) {
  const size_t n = mdp_image_count(mask);
  uint32_t top = 0;
  for (size_t v = 0; v < n; v++)
    if (d4[v] > top) top = d4[v];
  /* d(j) = 2 j + 1 (centres) or 2 j + 2 (corners); hi: the first j with d^2 >= top (fails). */
  const int first = parity ? 2 : 1;
  int hi = 0;
  while ((double)(2 * hi + first) * (2 * hi + first) < (double)top) hi++;
  int lo_of[3] = {-1, -1, -1}, hi_of[3] = {hi, hi, hi};
  for (;;) {
    int axis = -1;
    for (int a = 0; a < 3; a++)
      if (hi_of[a] - lo_of[a] > 1 && (axis < 0 || hi_of[a] - lo_of[a] > hi_of[axis] - lo_of[axis]))
        axis = a;
    if (axis < 0) break;
    const int mid = lo_of[axis] + (hi_of[axis] - lo_of[axis]) / 2;
    const double d = 2 * mid + first;
    for (size_t v = 0; v < n; v++) mask->label[v] = (double)d4[v] > d * d ? 0 : 1;
    mdp_image_stats_t st;
    if (mdp_image_stats(mask, &st, err)) return 1;
    (*labellings)++;
    for (int a = 0; a < 3; a++) {
      if (mid <= lo_of[a] || mid >= hi_of[a]) continue;
      if (st.spans[a])
        lo_of[a] = mid;
      else
        hi_of[a] = mid;
    }
  }
  for (int a = 0; a < 3; a++)
    if (lo_of[a] >= 0 && 2 * lo_of[a] + first > best[a]) best[a] = 2 * lo_of[a] + first;
  return 0;
}

int mdp_image_pore_sizes(const mdp_image_t *img, const int periodic[3], mdp_image_pore_sizes_t *ps,
                         char *err) {
  memset(ps, 0, sizeof *ps);
  for (int a = 0; a < 3; a++) ps->periodic[a] = periodic[a] != 0;
  const size_t n = mdp_image_count(img);
  /* d4 + the space + the mask image + mdp_image_stats' cluster labels, 4 + 1 + 1 + 4 bytes */
  if (mdp_image_check_memory(10.0 * (double)n, "image", "the pore-size analysis", err)) return 1;
  uint32_t *d4 = malloc(n * sizeof *d4);
  uint8_t *in_space = malloc(n);
  mdp_image_t mask;
  memset(&mask, 0, sizeof mask);
  int rc = 1;
  if (!d4 || !in_space) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "pore sizes: out of memory for %zu voxels", n);
    goto done;
  }
  if (mark_percolating(img, in_space, err) ||
      mdp_image_pore_distance(img, MDP_EDT_CENTRES, periodic, d4, err) ||
      diameter_stats(d4, in_space, n, ps, err))
    goto done;
  if (ps->voxels == 0) { /* nothing percolates: every throat 0 */
    rc = 0;
    goto done;
  }
  if (ps->no_solid) { /* the throat is the narrowest side of the cross-section */
    const int dim[3] = {img->nx, img->ny, img->nz};
    for (int a = 0; a < 3; a++) {
      const int b = dim[(a + 1) % 3], c = dim[(a + 2) % 3];
      ps->throat[a] = b < c ? b : c;
    }
    ps->diameter_max = ps->diameter_mean = NAN;
    for (int q = 0; q < 5; q++) ps->diameter_q[q] = NAN;
    rc = 0;
    goto done;
  }
  free(in_space);
  in_space = NULL;
  if (mdp_image_alloc(&mask, img->nx, img->ny, img->nz, err) ||
      mdp_image_parse_labels("pore=0,inorganic=1", mask.phase_of, err))
    goto done;
  if (bisect_throats(d4, 0, &mask, ps->throat, &ps->labellings, err) ||
      mdp_image_pore_distance(img, MDP_EDT_CORNERS, periodic, d4, err) ||
      bisect_throats(d4, 1, &mask, ps->throat, &ps->labellings, err))
    goto done;
  rc = 0;
done:
  free(d4), free(in_space);
  mdp_image_free(&mask);
  return rc;
}
