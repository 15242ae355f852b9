/* The mirror extension and the seam continuity behind the boundary treatments of non-periodic
 * images: the mirrored image is the reflection, keeps every phase fraction and is periodic across
 * its seam; a periodic image's seam reads as periodic and a crop's does not. */
#include "check.h"
#include "mdpore_image.h"

#include <stdlib.h>

static char err[MDP_IMAGE_ERR_LEN];

static void test_mirror_is_the_reflection(void) {
  mdp_image_t img, out;
  mdp_image_alloc(&img, 5, 4, 3, err);
  mdp_image_parse_labels("pore=0,inorganic=1", img.phase_of, err);
  srand(7);
  long long pore = 0;
  for (size_t v = 0; v < mdp_image_count(&img); v++) pore += !(img.label[v] = rand() % 3 == 0);
  const int mirror[3] = {1, 0, 1};
  CHECK(mdp_image_mirror(&img, mirror, &out, err) == 0, "%s", err);
  CHECK(out.nx == 10 && out.ny == 4 && out.nz == 6, "dims %dx%dx%d", out.nx, out.ny, out.nz);
  int wrong = 0;
  long long pore_out = 0;
  for (int k = 0; k < out.nz; k++)
    for (int j = 0; j < out.ny; j++)
      for (int i = 0; i < out.nx; i++) {
        const int si = i < 5 ? i : 9 - i, sk = k < 3 ? k : 5 - k;
        const uint8_t l = out.label[mdp_image_index(&out, i, j, k)];
        wrong += l != img.label[mdp_image_index(&img, si, j, sk)];
        pore_out += l == 0;
      }
  CHECK(wrong == 0, "%d voxels differ from the reflection", wrong);
  CHECK(pore_out == 4 * pore, "pore voxels %lld, expected 4 x %lld", pore_out, pore);
  /* every mirrored axis joins its last slice to its first: the seam continues the image */
  mdp_image_seam_t seam;
  CHECK(mdp_image_seam(&out, 0, &seam) == 0, "seam");
  CHECK_CLOSE(seam.seam_overlap, 1.0, 0);
  CHECK(seam.periodic, "a mirrored axis must read periodic (continuity %g)", seam.continuity);
  mdp_image_free(&out);
  const int none[3] = {0, 0, 0};
  CHECK(mdp_image_mirror(&img, none, &out, err) == 0, "%s", err);
  CHECK(out.nx == 5 && !memcmp(out.label, img.label, mdp_image_count(&img)), "identity");
  mdp_image_free(&out);
  mdp_image_free(&img);
}

static void test_seam_of_periodic_and_cropped(void) {
  mdp_image_t img, crop;
  /* a Boolean model of spheres stamped periodically: its seam is one more interior step */
  CHECK(mdp_make_random_spheres(&img, 48, 5.0, 0.45, 3, err) == 0, "%s", err);
  for (int a = 0; a < 3; a++) {
    mdp_image_seam_t s;
    mdp_image_seam(&img, a, &s);
    printf("periodic Boolean spheres along %c: continuity %.3f\n", 'x' + a, s.continuity);
    CHECK(s.periodic && s.continuity > 0.9,
          "periodic spheres along %c: continuity %g (seam %g, interior %g)", 'x' + a, s.continuity,
          s.seam_overlap, s.interior_overlap);
  }
  /* cut at 29 of 48 along x: the end slices are 19 voxels apart, about two sphere diameters */
  const int lo[3] = {0, 0, 0}, size[3] = {29, 48, 48};
  CHECK(mdp_image_crop(&img, lo, size, &crop, err) == 0, "%s", err);
  mdp_image_seam_t sx, sy;
  mdp_image_seam(&crop, 0, &sx);
  mdp_image_seam(&crop, 1, &sy);
  CHECK(!sx.periodic && sx.continuity < 0.8 * MDP_SEAM_PERIODIC_CONTINUITY,
        "cropped along x: continuity %g must read non-periodic", sx.continuity);
  CHECK(sy.periodic, "the crop keeps y periodic (continuity %g)", sy.continuity);
  mdp_image_free(&crop);
  mdp_image_free(&img);
}

int main(void) {
  test_mirror_is_the_reflection();
  test_seam_of_periodic_and_cropped();
  if (check_failures) fprintf(stderr, "%d check(s) failed\n", check_failures);
  return check_failures ? 1 : 0;
}
