/* The phase distribution of one two-liquid run (docs/relperm.md section 3): the morphological
 * drainage or imbibition of the image at the target non-wetting saturation 1 - Sw
 * (mdp_image_morph_at, meso/image/image_morph.c), or a labelled image given with --phase-images,
 * written as DIR/image.raw (+ sidecar with the label map) with the mirror images the boundary
 * treatment needs (campaign_boundary.c, with DIR as the work folder), and its saturations by voxels:
 * the non-wetting phase's, and the part of it in clusters that join the two faces along the axis
 * (connected) or not (disconnected, e.g. trapped ganglia). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "common/atomic_file.h"
#include "relperm.h"

int rp_free_label(const mdp_image_t *img) {
  int used[256] = {0};
  const size_t n = mdp_image_count(img);
  for (size_t v = 0; v < n; v++) used[img->label[v]] = 1;
  for (int l = 3; l < 256; l++)
    if (!used[l] && img->phase_of[l] == MDP_PHASE_UNSET) return l;
  return -1;
}

void rp_nw_connectivity(const mdp_image_t *img, uint8_t nw_label, int axis, rp_run *r) {
  mdp_image_t nw = *img; /* shares the labels: only the map differs */
  for (int v = 0; v < 256; v++) nw.phase_of[v] = MDP_PHASE_INORGANIC;
  nw.phase_of[nw_label] = MDP_PHASE_PORE;
  const size_t n = mdp_image_count(img);
  long long pore = 0, nw_voxels = 0, connected = 0;
  for (size_t v = 0; v < n; v++) {
    pore += mdp_image_is_pore(img, v);
    nw_voxels += img->label[v] == nw_label;
  }
  r->snw_image = r->snw_connected = r->snw_disconnected = NAN;
  if (pore == 0) return;
  r->snw_image = (double)nw_voxels / (double)pore;
  int32_t *cl = malloc(n * sizeof *cl);
  int n_cl = 0;
  char err[MDP_IMAGE_ERR_LEN];
  if (!cl || mdp_image_label_clusters(&nw, cl, &n_cl, err)) {
    free(cl);
    return;
  }
  unsigned char *lo = calloc((size_t)n_cl + 1, 1), *hi = calloc((size_t)n_cl + 1, 1);
  const int dims[3] = {img->nx, img->ny, img->nz};
  for (int k = 0; lo && hi && k < img->nz; k++)
    for (int j = 0; j < img->ny; j++)
      for (int i = 0; i < img->nx; i++) {
        const int32_t c = cl[mdp_image_index(img, i, j, k)];
        if (c < 0) continue;
        const int at = axis == 0 ? i : axis == 1 ? j : k;
        if (at == 0) lo[c] = 1;
        if (at == dims[axis] - 1) hi[c] = 1;
      }
  for (size_t v = 0; lo && hi && v < n; v++)
    if (cl[v] >= 0 && lo[cl[v]] && hi[cl[v]]) connected++;
  if (lo && hi) {
    r->snw_connected = (double)connected / (double)pore;
    r->snw_disconnected = (double)(nw_voxels - connected) / (double)pore;
  }
  free(lo);
  free(hi);
  free(cl);
}

/* A given phase image: the input's dimensions and pore space, its non-wetting pore voxels labelled
 * nw_label. */
static int read_given(const char *path, const mdp_image_t *img, uint8_t nw_label,
                      mdp_image_t *out) {
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_read_opts_t ro;
  mdp_image_read_opts_init(&ro);
  if (mdp_image_read(path, &ro, out, err)) {
    fprintf(stderr, "mdpore relperm: --phase-images: %s: %s\n", path, err);
    return -1;
  }
  const char *why = NULL;
  if (out->nx != img->nx || out->ny != img->ny || out->nz != img->nz)
    why = "the IMAGE's dimensions";
  else if (out->phase_of[nw_label] != MDP_PHASE_PORE)
    why = "the non-wetting label (--nw-label) mapped to pore in its label map";
  else
    for (size_t v = 0; v < mdp_image_count(img) && !why; v++)
      if (mdp_image_is_pore(img, v) != mdp_image_is_pore(out, v))
        why = "the IMAGE's pore space (a pore voxel of one is solid in the other)";
  if (why) {
    fprintf(stderr,
            "mdpore relperm: --phase-images: %s: expected a phase distribution in the IMAGE "
            "(%dx%dx%d voxels) with %s (label %d for the non-wetting liquid)\n",
            path, img->nx, img->ny, img->nz, why, nw_label);
    mdp_image_free(out);
    return -1;
  }
  return 0;
}

int rp_phase_image(const rp_opts *o, const mdp_image_t *img, double sw_target, const char *given,
                   uint8_t nw_label, const char *dir, rp_run *r) {
  char err[MDP_IMAGE_ERR_LEN], path[CAMP_PATH + 32];
  mdp_image_t out;
  r->radius = NAN;
  if (given) {
    if (read_given(given, img, nw_label, &out)) return -1;
  } else {
    const camp_opts *co = &o->co;
    const int periodic_axis = co->boundary_of_axis[o->axis] == CAMP_BOUNDARY_PERIODIC;
    mdp_morph_opts_t mo = {
        .mode = o->mode, .axis = periodic_axis ? -1 : o->axis, .trapping = o->trapping};
    for (int d = 0; d < 3; d++) mo.periodic[d] = d == o->axis ? periodic_axis : !co->sides_mirror;
    mdp_morph_step_t step;
    if (mdp_image_morph_at(img, &mo, 1.0 - sw_target, nw_label, &out, &step, err)) {
      fprintf(stderr, "mdpore relperm: %s: the %s at Sw = %g: %s\n", co->input,
              o->mode == MDP_MORPH_IMBIBITION ? "imbibition" : "drainage", sw_target, err);
      return -1;
    }
    r->radius = step.radius;
  }
  rp_nw_connectivity(&out, nw_label, o->axis, r);
  if (make_dirs(dir)) {
    mdp_image_free(&out);
    return -1;
  }
  snprintf(path, sizeof path, "%s/image.raw", dir);
  snprintf(r->image, sizeof r->image, "%.4000s", path);
  int rc = mdp_image_write_raw(&out, path, err);
  if (rc) fprintf(stderr, "mdpore relperm: %s: %s\n", path, err);
  camp_opts sub = o->co; /* the mirror images of this distribution beside it */
  snprintf(sub.workdir, sizeof sub.workdir, "%.4000s", dir);
  if (!rc) rc = camp_write_boundary_images(&sub, &out);
  mdp_image_free(&out);
  return rc ? -1 : 0;
}
