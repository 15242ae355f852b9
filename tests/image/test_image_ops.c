/* Crop, majority downsampling, padding, porosity and pore connectivity, and the synthetic
 * generators (exact voxel solid fractions, Boolean-model porosity, periodic sphere stamping). */
#include "check.h"
#include "mdpore_image.h"

#include <stdlib.h>

static char err[MDP_IMAGE_ERR_LEN];

static void test_crop_downsample_pad(void) {
  mdp_image_t img, out;
  mdp_image_alloc(&img, 4, 4, 2, err);
  mdp_image_parse_labels("pore=0,organic=2,inorganic=1", img.phase_of, err);
  for (int k = 0; k < 2; k++)
    for (int j = 0; j < 4; j++)
      for (int i = 0; i < 4; i++)
        img.label[mdp_image_index(&img, i, j, k)] = (uint8_t)((i + j + k) % 3);
  /* block (0..1)^3 holds labels i+j+k = 0,1,1,2,1,2,2,3 -> mod 3: 0,1,1,2,1,2,2,0: 1 and 2 tie (3
   * each), the smaller label wins */
  CHECK(mdp_image_downsample(&img, 2, &out, err) == 0, "%s", err);
  CHECK(out.nx == 2 && out.ny == 2 && out.nz == 1, "dims");
  CHECK(out.label[0] == 1, "tie must go to the smaller label, got %d", out.label[0]);
  CHECK_CLOSE(out.voxel_size, 2.0, 0);
  mdp_image_free(&out);
  /* majority: set block (2..3, 0..1, 0..1) to mostly 2 */
  for (int k = 0; k < 2; k++)
    for (int j = 0; j < 2; j++)
      for (int i = 2; i < 4; i++)
        img.label[mdp_image_index(&img, i, j, k)] = (i == 2 && j == 0 && k == 0) ? 0 : 2;
  mdp_image_downsample(&img, 2, &out, err);
  CHECK(out.label[1] == 2, "majority 2 expected, got %d", out.label[1]);
  mdp_image_free(&out);
  CHECK_ERR_HAS(mdp_image_downsample(&img, 3, &out, err), err, "factor 3");

  const int lo[3] = {1, 2, 0}, size[3] = {3, 2, 1};
  CHECK(mdp_image_crop(&img, lo, size, &out, err) == 0, "%s", err);
  CHECK(out.label[mdp_image_index(&out, 2, 1, 0)] == img.label[mdp_image_index(&img, 3, 3, 0)],
        "crop");
  mdp_image_free(&out);
  const int too[3] = {2, 2, 3};
  CHECK_ERR_HAS(mdp_image_crop(&img, lo, too, &out, err), err, "crop along z");

  const int w[6] = {1, 2, 0, 0, 3, 0};
  CHECK(mdp_image_pad(&img, w, 0, &out, err) == 0, "%s", err);
  CHECK(out.nx == 7 && out.ny == 4 && out.nz == 5, "pad dims %dx%dx%d", out.nx, out.ny, out.nz);
  CHECK(out.label[mdp_image_index(&out, 0, 0, 0)] == 0 &&
            out.label[mdp_image_index(&out, 6, 3, 4)] == 0,
        "pad label");
  CHECK(out.label[mdp_image_index(&out, 1 + 3, 3, 3 + 1)] ==
            img.label[mdp_image_index(&img, 3, 3, 1)],
        "interior after pad");
  mdp_image_free(&out);
  CHECK_ERR_HAS(mdp_image_pad(&img, w, 7, &out, err), err, "pad label 7");
  mdp_image_free(&img);
}

/* 10 x 7 x 7 solid block with: a straight channel along x (row y=1, z=1), an enclosed 2-voxel
 * cavity, a dead end entering from the y = 0 face, and an L-shaped path joining y = 0 to z = 6. */
static void test_connectivity(void) {
  mdp_image_t img;
  mdp_image_alloc(&img, 10, 7, 7, err);
  mdp_image_parse_labels("pore=0,inorganic=1", img.phase_of, err);
  memset(img.label, 1, mdp_image_count(&img));
  for (int i = 0; i < 10; i++) img.label[mdp_image_index(&img, i, 1, 1)] = 0; /* channel: 10 */
  img.label[mdp_image_index(&img, 5, 4, 4)] = 0;                              /* cavity: 2 */
  img.label[mdp_image_index(&img, 6, 4, 4)] = 0;
  for (int j = 0; j < 3; j++) img.label[mdp_image_index(&img, 8, j, 4)] = 0; /* dead end: 3 */
  for (int j = 0; j < 5; j++) img.label[mdp_image_index(&img, 2, j, 5)] = 0; /* L: 5 + 1 */
  img.label[mdp_image_index(&img, 2, 4, 6)] = 0;
  mdp_image_stats_t st;
  CHECK(mdp_image_stats(&img, &st, err) == 0, "%s", err);
  CHECK(st.n_pore == 21, "pore voxels %lld", st.n_pore);
  CHECK(st.n_clusters == 4, "clusters %d", st.n_clusters);
  CHECK(st.spans[0] && !st.spans[1] && !st.spans[2], "spans %d %d %d", st.spans[0], st.spans[1],
        st.spans[2]);
  CHECK(st.connected_voxels[0] == 10, "x-connected %lld", st.connected_voxels[0]);
  CHECK(st.n_isolated_clusters == 1 && st.isolated_voxels == 2, "isolated %d / %lld",
        st.n_isolated_clusters, st.isolated_voxels);
  CHECK(st.n_nonspanning_clusters == 3 && st.nonspanning_voxels == 11, "non-spanning %d / %lld",
        st.n_nonspanning_clusters, st.nonspanning_voxels);
  CHECK(mdp_image_require_percolation(&img, &st, 0, "t", err) == 0, "%s", err);
  CHECK_ERR_HAS(mdp_image_require_percolation(&img, &st, 1, "t", err), err,
                "axis y does not percolate");
  memset(img.label, 1, mdp_image_count(&img));
  mdp_image_stats(&img, &st, err);
  CHECK_ERR_HAS(mdp_image_require_percolation(&img, &st, 0, "t", err), err, "empty pore space");
  mdp_image_free(&img);
}

static void test_generators(void) {
  mdp_image_t img;
  mdp_image_stats_t st;
  CHECK(mdp_make_slit(&img, 8, 2, 5, 3, err) == 0, "%s", err);
  mdp_image_stats(&img, &st, err);
  CHECK_CLOSE(st.porosity, 8.0 / 12.0, 1e-12);
  CHECK(st.spans[0] && !st.spans[1] && st.spans[2], "slit spans x and z only");
  mdp_image_free(&img);

  double c = 0;
  /* 40^2 cells: c L^2 is a multiple of the 4-voxel mirror orbit, so c is met exactly */
  const double cs[] = {0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
  for (int n = 0; n < 7; n++) {
    CHECK(mdp_make_cylinders(&img, 40, cs[n], 2, 1, &c, err) == 0, "%s", err);
    mdp_image_stats(&img, &st, err);
    CHECK_CLOSE(c, cs[n], 1e-12);
    CHECK_CLOSE(1 - st.porosity, cs[n], 1e-12);
    /* mirror symmetry about the cell centre lines */
    int asym = 0;
    for (int j = 0; j < 40; j++)
      for (int i = 0; i < 40; i++)
        asym += img.label[mdp_image_index(&img, i, j, 0)] !=
                    img.label[mdp_image_index(&img, 39 - i, j, 0)] ||
                img.label[mdp_image_index(&img, i, j, 0)] !=
                    img.label[mdp_image_index(&img, i, 39 - j, 0)];
    CHECK(asym == 0, "cylinder c=%g not mirror symmetric (%d voxels)", cs[n], asym);
    mdp_image_free(&img);
  }
  CHECK(mdp_make_spheres(&img, 32, 0.125, 1, &c, err) == 0, "%s", err);
  CHECK_CLOSE(c, 0.125, 1e-12);
  /* the body is a ball: every solid voxel is nearer the centre than every pore voxel, up to the
   * partly taken outermost shell */
  double rmax_solid = 0, rmin_pore = 1e9;
  for (int k = 0; k < 32; k++)
    for (int j = 0; j < 32; j++)
      for (int i = 0; i < 32; i++) {
        double r2 = (i - 15.5) * (i - 15.5) + (j - 15.5) * (j - 15.5) + (k - 15.5) * (k - 15.5);
        if (img.label[mdp_image_index(&img, i, j, k)])
          rmax_solid = fmax(rmax_solid, r2);
        else
          rmin_pore = fmin(rmin_pore, r2);
      }
  CHECK(rmax_solid <= rmin_pore + 1e-9, "not a ball: solid up to r2 %g, pore from r2 %g",
        rmax_solid, rmin_pore);
  CHECK_CLOSE(pow(3 * 4096 / (4 * M_PI), 1.0 / 3), sqrt(rmax_solid), 0.5);
  mdp_image_free(&img);
  CHECK_ERR_HAS(mdp_make_spheres(&img, 32, 0.6, 1, &c, err), err, "touching");

  /* Boolean model: stops at the first sphere that takes the porosity to or below the target */
  CHECK(mdp_make_random_spheres(&img, 48, 4.0, 0.6, 42, err) == 0, "%s", err);
  mdp_image_stats(&img, &st, err);
  double one_sphere = 4.0 / 3 * M_PI * 64 / (48.0 * 48 * 48);
  CHECK(st.porosity <= 0.6 && st.porosity > 0.6 - 1.5 * one_sphere, "porosity %g", st.porosity);
  mdp_image_free(&img);
}

/* One sphere stamped across the periodic corner keeps its whole volume. */
static void test_sphere_file(const char *dir) {
  char path[512];
  snprintf(path, sizeof path, "%s/centres.txt", dir);
  FILE *f = fopen(path, "w");
  fprintf(f, "# x y z\n0.1 9.9 0.2 7\n");
  fclose(f);
  mdp_image_t img;
  mdp_image_stats_t st;
  const double box[3] = {10, 10, 10};
  CHECK(mdp_make_sphere_file(&img, path, box, 3.0, 0.1, err) == 0, "%s", err);
  mdp_image_stats(&img, &st, err);
  CHECK_CLOSE(1 - st.porosity, 4.0 / 3 * M_PI * 27 / 1000, 2e-4);
  mdp_image_free(&img);
  f = fopen(path, "w");
  fprintf(f, "1 2\n");
  fclose(f);
  CHECK_ERR_HAS(mdp_make_sphere_file(&img, path, box, 3.0, 0.1, err), err, "centres.txt:1:");
  remove(path);
}

int main(void) {
  test_crop_downsample_pad();
  test_connectivity();
  test_generators();
  test_sphere_file(getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  printf("%s: %d failures\n", __FILE__, check_failures);
  return check_failures ? 1 : 0;
}
