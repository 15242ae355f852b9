/* mdp_image_drop_nonspanning: pore clusters that do not join the inlet face to the outlet face are
 * turned solid; the spanning channel and a dead-end branch of it stay pore. */
#include "check.h"
#include "mdpore_image.h"

static char err[MDP_IMAGE_ERR_LEN];

enum { NX = 8, NY = 6, NZ = 6, SOLID = 1 };

static int is_pore(const mdp_image_t *img, int i, int j, int k) {
  return mdp_image_is_pore(img, mdp_image_index(img, i, j, k));
}

static void set_pore(mdp_image_t *img, int i, int j, int k) {
  img->label[mdp_image_index(img, i, j, k)] = 0;
}

/* 8 x 6 x 6 solid block (label 1) with: a channel along x at (y, z) = (1, 1), 8 voxels; a dead-end
 * branch off its middle at x = 4, y = 2..3, z = 1, 2 voxels; an enclosed pore of 3 voxels. */
static void make_image(mdp_image_t *img) {
  CHECK(mdp_image_alloc(img, NX, NY, NZ, err) == 0, "%s", err);
  CHECK(mdp_image_parse_labels("pore=0,inorganic=1", img->phase_of, err) == 0, "%s", err);
  memset(img->label, SOLID, mdp_image_count(img));
  for (int i = 0; i < NX; i++) set_pore(img, i, 1, 1);
  set_pore(img, 4, 2, 1), set_pore(img, 4, 3, 1);
  set_pore(img, 2, 4, 4), set_pore(img, 3, 4, 4), set_pore(img, 2, 4, 3);
}

static long long count_pore(const mdp_image_t *img) {
  long long n = 0;
  for (size_t idx = 0; idx < mdp_image_count(img); idx++) n += mdp_image_is_pore(img, idx);
  return n;
}

static void test_drop_isolated(void) {
  mdp_image_t img;
  make_image(&img);
  CHECK(count_pore(&img) == 13, "pore voxels %lld", count_pore(&img));
  long long dropped = -1;
  CHECK(mdp_image_drop_nonspanning(&img, 0, &dropped, err) == 0, "%s", err);
  CHECK(dropped == 3, "dropped %lld, expected the 3 voxels of the enclosed pore", dropped);
  CHECK(!is_pore(&img, 2, 4, 4) && !is_pore(&img, 3, 4, 4) && !is_pore(&img, 2, 4, 3),
        "enclosed pore still pore");
  CHECK(img.label[mdp_image_index(&img, 2, 4, 4)] == SOLID, "dropped voxel label %d",
        img.label[mdp_image_index(&img, 2, 4, 4)]);
  int channel = 1;
  for (int i = 0; i < NX; i++) channel &= is_pore(&img, i, 1, 1);
  CHECK(channel, "the spanning channel lost voxels");
  CHECK(is_pore(&img, 4, 2, 1) && is_pore(&img, 4, 3, 1), "the dead-end branch was dropped");
  CHECK(count_pore(&img) == 10, "pore voxels after %lld", count_pore(&img));
  mdp_image_stats_t st;
  CHECK(mdp_image_stats(&img, &st, err) == 0, "%s", err);
  CHECK(st.n_clusters == 1 && st.connected_voxels[0] == 10, "after: %d clusters, %lld connected",
        st.n_clusters, st.connected_voxels[0]);
  /* nothing left to drop */
  CHECK(mdp_image_drop_nonspanning(&img, 0, &dropped, err) == 0 && dropped == 0,
        "second pass dropped %lld", dropped);
  mdp_image_free(&img);
}

/* A cluster open to the inlet face only carries no flow either. */
static void test_drop_one_sided(void) {
  mdp_image_t img;
  make_image(&img);
  for (int i = 0; i < 3; i++) set_pore(&img, i, 4, 1); /* from x = 0 to x = 2: 3 voxels */
  long long dropped = -1;
  CHECK(mdp_image_drop_nonspanning(&img, 0, &dropped, err) == 0, "%s", err);
  CHECK(dropped == 6, "dropped %lld, expected 3 enclosed + 3 open to x = 0 only", dropped);
  CHECK(!is_pore(&img, 0, 4, 1), "the one-sided cluster stayed");
  mdp_image_free(&img);
}

/* No cluster spans y: the whole pore space is turned solid (the caller checks percolation first,
 * as `mdpore foam` does with mdp_image_require_percolation). */
static void test_no_spanning_axis(void) {
  mdp_image_t img;
  make_image(&img);
  mdp_image_stats_t st;
  CHECK(mdp_image_stats(&img, &st, err) == 0, "%s", err);
  CHECK_ERR_HAS(mdp_image_require_percolation(&img, &st, 1, "t", err), err,
                "axis y does not percolate");
  long long dropped = -1;
  CHECK(mdp_image_drop_nonspanning(&img, 1, &dropped, err) == 0, "%s", err);
  CHECK(dropped == 13, "dropped %lld of 13 pore voxels along y", dropped);
  CHECK(count_pore(&img) == 0, "%lld pore voxels left", count_pore(&img));
  mdp_image_free(&img);

  make_image(&img);
  CHECK_ERR_HAS(mdp_image_drop_nonspanning(&img, 3, &dropped, err), err, "flow axis 3");
  CHECK(count_pore(&img) == 13, "a refused call changed the image");
  mdp_image_free(&img);
}

int main(void) {
  test_drop_isolated();
  test_drop_one_sided();
  test_no_spanning_axis();
  if (check_failures) {
    fprintf(stderr, "%d check(s) failed\n", check_failures);
    return 1;
  }
  printf("image_drop_nonspanning: all checks passed\n");
  return 0;
}
