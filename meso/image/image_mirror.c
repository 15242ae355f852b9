/* Mirror extension and seam continuity: the two image operations behind the campaign's and the
 * continuum check's boundary treatments of a sample that is not periodic (docs/images.md). */
#include "mdpore_image.h"

#include <limits.h>
#include <stdio.h>

int mdp_image_mirror(const mdp_image_t *in, const int mirror[3], mdp_image_t *out, char *err) {
  const int n[3] = {in->nx, in->ny, in->nz};
  int m[3];
  for (int a = 0; a < 3; a++) {
    const long long len = (long long)n[a] * (mirror[a] ? 2 : 1);
    if (len > INT_MAX) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "mirror along %c: the image would have %lld voxels along it (expected at most %d)",
               'x' + a, len, INT_MAX);
      return 1;
    }
    m[a] = (int)len;
  }
  if (mdp_image_alloc_beside(out, m[0], m[1], m[2], (double)mdp_image_count(in), err)) return 1;
  mdp_image_copy_meta(out, in);
  /* out(i) = in(i) for i < n, in(2n - 1 - i) beyond: the copy is the reflection across the high
   * face, so the high face meets its own image and, across the periodic wrap, the low face too */
  for (int k = 0; k < m[2]; k++) {
    const int sk = k < n[2] ? k : 2 * n[2] - 1 - k;
    for (int j = 0; j < m[1]; j++) {
      const int sj = j < n[1] ? j : 2 * n[1] - 1 - j;
      for (int i = 0; i < m[0]; i++) {
        const int si = i < n[0] ? i : 2 * n[0] - 1 - i;
        out->label[mdp_image_index(out, i, j, k)] = in->label[mdp_image_index(in, si, sj, sk)];
      }
    }
  }
  return 0;
}

/* Pore Jaccard index of slices s and t normal to axis: pore on both / pore on either (1 when
 * neither has pore: two solid slices do not break a flow path). */
static double slice_jaccard(const mdp_image_t *img, int axis, int s, int t) {
  const int n[3] = {img->nx, img->ny, img->nz};
  const int u = axis == 0 ? 1 : 0, w = axis == 2 ? 1 : 2;
  long long both = 0, either = 0;
  for (int b = 0; b < n[w]; b++)
    for (int a = 0; a < n[u]; a++) {
      int cs[3], ct[3];
      cs[axis] = s;
      ct[axis] = t;
      cs[u] = ct[u] = a;
      cs[w] = ct[w] = b;
      const int ps = mdp_image_is_pore(img, mdp_image_index(img, cs[0], cs[1], cs[2]));
      const int pt = mdp_image_is_pore(img, mdp_image_index(img, ct[0], ct[1], ct[2]));
      both += ps && pt;
      either += ps || pt;
    }
  return either ? (double)both / (double)either : 1.0;
}

int mdp_image_seam(const mdp_image_t *img, int axis, mdp_image_seam_t *seam) {
  const int n[3] = {img->nx, img->ny, img->nz};
  if (axis < 0 || axis > 2) return 1;
  const int len = n[axis];
  seam->seam_overlap = slice_jaccard(img, axis, len - 1, 0);
  double sum = 0;
  for (int s = 0; s + 1 < len; s++) sum += slice_jaccard(img, axis, s, s + 1);
  seam->interior_overlap = len > 1 ? sum / (len - 1) : 1.0;
  seam->continuity = seam->interior_overlap > 0 ? seam->seam_overlap / seam->interior_overlap : 1.0;
  seam->periodic = seam->continuity >= MDP_SEAM_PERIODIC_CONTINUITY;
  return 0;
}
