/* The boundary treatment of the faces normal to the flow axis (docs/permeability.md,
 * "Boundaries"). A crop of a rock is not periodic: in a periodic box its last slice meets its first,
 * and where pore meets solid across that seam the flow path is closed (or a path is invented where
 * two unrelated pores meet). Three treatments:
 *   periodic   the image is one period (synthetic periodic media);
 *   mirror     the image followed by its reflection along the axis, a periodic box of twice the
 *              length in which each face meets itself. For Stokes flow the reflection symmetry
 *              makes every mirror plane a plane of uniform pressure with no tangential velocity
 *              (u_t odd, p - <p> odd under the reflection): the sample between two such planes is
 *              the sample between an inlet and an outlet face at fixed pressures, which is what
 *              `mdpore foam --boundary mirror` solves;
 *   reservoir  an open fluid reservoir between the faces and an inlet force in it (--drive
 *              pressure, campaign_scene.c).
 * AUTO keeps periodic where the seam continues the image (mdp_image_seam continuity >= 0.8) and
 * mirrors otherwise. --sides mirror mirrors the lateral faces too (symmetry planes, as foam's
 * --sides symmetry), at four times the particles. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "campaign.h"
#include "common/size_check.h"

const char *camp_boundary_name(int boundary) {
  switch (boundary) {
  case CAMP_BOUNDARY_PERIODIC:
    return "periodic";
  case CAMP_BOUNDARY_MIRROR:
    return "mirror";
  case CAMP_BOUNDARY_RESERVOIR:
    return "reservoir";
  case CAMP_BOUNDARY_AUTO:
    return "auto";
  default:
    return "none";
  }
}

int camp_boundary_parse(const char *text) {
  for (int b = CAMP_BOUNDARY_AUTO; b <= CAMP_BOUNDARY_RESERVOIR; b++)
    if (!strcmp(text, camp_boundary_name(b))) return b;
  return -1;
}

void camp_resolve_boundaries(camp_opts *o, campaign *c, const mdp_image_t *img) {
  for (int d = 0; d < 3; d++) {
    c->seam_continuity[d] = NAN;
    c->boundary[d] = 0;
    o->boundary_of_axis[d] = 0;
  }
  c->sides_mirror = o->sides_mirror;
  mdp_image_seam_t seam[3];
  for (int d = 0; img && d < 3; d++) {
    mdp_image_seam(img, d, &seam[d]);
    c->seam_continuity[d] = seam[d].continuity;
  }
  for (int a = 0; a < o->n_axes; a++) {
    const int ax = o->axes[a];
    int b = o->boundary;
    const char *why = "--boundary";
    if (o->drive == CAMP_DRIVE_PRESSURE) {
      b = CAMP_BOUNDARY_RESERVOIR;
      why = "--drive pressure";
    } else if (b == CAMP_BOUNDARY_AUTO) {
      b = !img || seam[ax].periodic ? CAMP_BOUNDARY_PERIODIC : CAMP_BOUNDARY_MIRROR;
      why = !img                ? "no image"
            : seam[ax].periodic ? "the seam continues the image"
                                : "the image is not periodic along the axis";
    }
    o->boundary_of_axis[ax] = c->boundary[ax] = b;
    if (img)
      printf("mdpore permeability: boundary along %c: %s (%s; seam overlap %.3f, interior %.3f, "
             "continuity %.2f; periodic at >= %.2f); sides %s\n",
             'x' + ax, camp_boundary_name(b), why, seam[ax].seam_overlap, seam[ax].interior_overlap,
             seam[ax].continuity, MDP_SEAM_PERIODIC_CONTINUITY,
             o->sides_mirror ? "mirror" : "periodic");
    if (img && b == CAMP_BOUNDARY_PERIODIC && !seam[ax].periodic)
      fprintf(stderr,
              "mdpore permeability: warning: --boundary periodic along %c, but the image's end "
              "slices do not continue each other (continuity %.2f): the periodic seam closes or "
              "invents flow paths; --boundary mirror or reservoir treats a crop's faces\n",
              'x' + ax, seam[ax].continuity);
  }
  fflush(stdout);
}

void camp_mirror_image_path(const camp_opts *o, int axis, char *out, int len) {
  snprintf(out, len, "%.4000s/mirror_%c.raw", o->workdir, 'x' + axis);
}

int camp_mirrored_along(const camp_opts *o, int axis, int d) {
  if (d == axis) return o->boundary_of_axis[axis] == CAMP_BOUNDARY_MIRROR;
  return o->sides_mirror;
}

static int write_image(const mdp_image_t *img, const char *path) {
  char err[MDP_IMAGE_ERR_LEN];
  if (mdp_image_write_raw(img, path, err)) {
    fprintf(stderr, "mdpore permeability: %s: %s\n", path, err);
    return -1;
  }
  return 0;
}

/* --reservoir in voxels at rc_per_voxel, in double before any int: the padded image's length along
 * the axis within the int range and its voxels, with the `held` voxels of the images it is made
 * beside (the sample and its mirrored copy), within the memory limit. 0, or -1 and a message naming
 * the option. */
static int check_reservoir(const camp_opts *o, const mdp_image_t *img, int ax, double held) {
  const int n[3] = {img->nx, img->ny, img->nz};
  const double voxels = round(o->reservoir / o->rc_per_voxel), along = n[ax] + voxels;
  char why[320] = "";
  if (along > INT_MAX)
    snprintf(why, sizeof why, "%.3g voxels along %c, more than the %d an image can index", along,
             'x' + ax, INT_MAX);
  else
    mdp_size_check(along * n[(ax + 1) % 3] * n[(ax + 2) % 3] + held, MDP_IMAGE_MAX_VOXELS, 1.0,
                   "voxels of the padded image and the images it is made from", why, sizeof why);
  if (!why[0]) return 0;
  fprintf(stderr,
          "mdpore permeability: %s: --reservoir %g: expected a reservoir the image padded with it "
          "fits: at %g rc per voxel it is %.3g voxels (%s)\n",
          o->input, o->reservoir, o->rc_per_voxel, voxels, why);
  return -1;
}

int camp_boundary_image(const camp_opts *o, const mdp_image_t *img, int ax, mdp_image_t *out) {
  const int reservoir = o->boundary_of_axis[ax] == CAMP_BOUNDARY_RESERVOIR;
  int mirror[3], any = 0;
  for (int d = 0; d < 3; d++) any |= mirror[d] = camp_mirrored_along(o, ax, d);
  if (!any && !reservoir) return 1;
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_t mirrored;
  const mdp_image_t *base = img;
  if (any) {
    if (mdp_image_mirror(img, mirror, &mirrored, err)) {
      fprintf(stderr, "mdpore permeability: %s: --boundary mirror: %s\n", o->input, err);
      return -1;
    }
    if (!reservoir) {
      *out = mirrored;
      return 0;
    }
    base = &mirrored;
  }
  int pore = -1;
  for (int v = 0; v < 256 && pore < 0; v++)
    if (img->phase_of[v] == MDP_PHASE_PORE) pore = v;
  /* the reservoir's pore voxels after the high face along the axis (the sample keeps
   * [0, L_sample); periodic, so the reservoir touches both faces) */
  const double held = (double)mdp_image_count(img) + (any ? (double)mdp_image_count(base) : 0);
  int w[6] = {0}, rc = check_reservoir(o, base, ax, held); /* refused: the message printed */
  if (!rc && (w[2 * ax + 1] = camp_reservoir_voxels(o),
              rc = pore < 0 || mdp_image_pad(base, w, (uint8_t)pore, out, err)))
    fprintf(stderr, "mdpore permeability: %s: --drive pressure: %s\n", o->input,
            pore < 0 ? "the image has no pore label for the reservoir" : err);
  if (any) mdp_image_free(&mirrored);
  return rc ? -1 : 0;
}

int camp_write_boundary_images(const camp_opts *o, const mdp_image_t *img) {
  for (int a = 0; a < o->n_axes; a++) {
    const int ax = o->axes[a];
    mdp_image_t built;
    const int rc = camp_boundary_image(o, img, ax, &built);
    if (rc > 0) continue; /* periodic: the run reads the image itself */
    if (rc < 0) return -1;
    char path[CAMP_PATH];
    if (o->boundary_of_axis[ax] == CAMP_BOUNDARY_RESERVOIR)
      camp_padded_image_path(o, ax, path, sizeof path);
    else
      camp_mirror_image_path(o, ax, path, sizeof path);
    const int written = write_image(&built, path);
    mdp_image_free(&built);
    if (written) return -1;
  }
  return 0;
}
