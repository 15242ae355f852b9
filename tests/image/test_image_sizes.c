/* The distance transform against brute force, the critical throat of a slit, a tube and a channel
 * with a constriction, and the periodicity numbers of a sphere array, a crop of it and hand-made
 * channels (mdp_image_pore_distance, mdp_image_pore_sizes, mdp_image_periodicity). */
#include "check.h"
#include "mdpore_image.h"

#include <stdint.h>
#include <stdlib.h>

static char err[MDP_IMAGE_ERR_LEN];

static void solid_block(mdp_image_t *img, int nx, int ny, int nz) {
  CHECK(mdp_image_alloc(img, nx, ny, nz, err) == 0, "%s", err);
  CHECK(mdp_image_parse_labels("pore=0,inorganic=1", img->phase_of, err) == 0, "%s", err);
  memset(img->label, 1, mdp_image_count(img));
}

static void set_pore(mdp_image_t *img, int i, int j, int k) {
  img->label[mdp_image_index(img, i, j, k)] = 0;
}

/* 4 x the squared distance from lattice point (i, j, k) to the nearest solid centre, by trying
 * every solid voxel (and its periodic images one period either side). */
static uint32_t brute_d4(const mdp_image_t *img, int lattice, const int periodic[3], int i, int j,
                         int k) {
  const int n[3] = {img->nx, img->ny, img->nz}, p[3] = {i, j, k};
  uint64_t best = MDP_EDT_NO_SOLID;
  for (int z = 0; z < n[2]; z++)
    for (int y = 0; y < n[1]; y++)
      for (int x = 0; x < n[0]; x++) {
        if (mdp_image_is_pore(img, mdp_image_index(img, x, y, z))) continue;
        const int s[3] = {x, y, z};
        uint64_t d = 0;
        for (int a = 0; a < 3; a++) {
          int64_t m = INT64_MAX;
          for (int w = periodic[a] ? -1 : 0; w <= (periodic[a] ? 1 : 0); w++) {
            const int64_t dx =
                2 * (int64_t)p[a] + lattice - 2 * ((int64_t)s[a] + (int64_t)w * n[a]);
            if (dx * dx < m) m = dx * dx;
          }
          d += (uint64_t)m;
        }
        if (d < best) best = d;
      }
  return (uint32_t)best;
}

static void test_edt_brute_force(void) {
  mdp_image_t img;
  solid_block(&img, 9, 7, 8);
  uint64_t state = 12345;
  for (size_t v = 0; v < mdp_image_count(&img); v++) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    img.label[v] = (state >> 33) % 100 < 65 ? 0 : 1; /* 65% pore */
  }
  uint32_t *d4 = malloc(mdp_image_count(&img) * sizeof *d4);
  static const int periodic_of[3][3] = {{0, 0, 0}, {1, 1, 1}, {1, 0, 1}};
  for (int lattice = 0; lattice < 2; lattice++)
    for (int c = 0; c < 3; c++) {
      CHECK(mdp_image_pore_distance(&img, lattice, periodic_of[c], d4, err) == 0, "%s", err);
      int bad = 0;
      for (int k = 0; k < img.nz; k++)
        for (int j = 0; j < img.ny; j++)
          for (int i = 0; i < img.nx; i++) {
            const uint32_t want = brute_d4(&img, lattice, periodic_of[c], i, j, k);
            const uint32_t got = d4[mdp_image_index(&img, i, j, k)];
            if (want != got && bad++ < 3)
              CHECK(want == got, "lattice %d periodic %d%d%d at (%d,%d,%d): %u vs brute %u",
                    lattice, periodic_of[c][0], periodic_of[c][1], periodic_of[c][2], i, j, k, got,
                    want);
          }
      CHECK(bad == 0, "%d mismatches (lattice %d, case %d)", bad, lattice, c);
    }
  free(d4);
  mdp_image_free(&img);
}

static void sizes(const mdp_image_t *img, int periodic, mdp_image_pore_sizes_t *ps) {
  const int p[3] = {periodic, periodic, periodic};
  CHECK(mdp_image_pore_sizes(img, p, ps, err) == 0, "%s", err);
}

static void test_slit_throat(void) {
  for (int w = 1; w <= 10; w++)
    for (int periodic = 0; periodic < 2; periodic++) {
      mdp_image_t img;
      CHECK(mdp_make_slit(&img, w, 3, 10, 12, err) == 0, "%s", err);
      mdp_image_pore_sizes_t ps;
      sizes(&img, periodic, &ps);
      CHECK(ps.throat[0] == w && ps.throat[2] == w && ps.throat[1] == 0,
            "slit %d (periodic %d): throats %d %d %d", w, periodic, ps.throat[0], ps.throat[1],
            ps.throat[2]);
      if (w % 2) CHECK_CLOSE(ps.diameter_max, w, 1e-12); /* the middle voxel's inscribed diameter */
      mdp_image_free(&img);
    }
}

/* A tube along x of the voxels within radius R of a line through voxel centres (centre c = 10) or
 * voxel corners (c = 9.5): its critical throat is the widest digital ball that fits, 2 R for R =
 * k + 1/2 on centres and R = k on corners, the largest odd number <= 2 R on centres otherwise. */
static void test_tube_throat(void) {
  static const double radius[] = {2.5, 3.5, 4.5, 6.2, 3.0, 4.0, 5.0};
  static const double centre[] = {10, 10, 10, 10, 9.5, 9.5, 9.5};
  static const int across[] = {5, 7, 9, 11, 6, 8, 10};
  for (int t = 0; t < 7; t++) {
    mdp_image_t img;
    const int n = 21;
    const double c = centre[t];
    solid_block(&img, 12, n, n);
    for (int k = 0; k < n; k++)
      for (int j = 0; j < n; j++)
        if ((j - c) * (j - c) + (k - c) * (k - c) <= radius[t] * radius[t])
          for (int i = 0; i < 12; i++) set_pore(&img, i, j, k);
    mdp_image_pore_sizes_t ps;
    sizes(&img, 1, &ps);
    CHECK(ps.throat[0] == across[t] && ps.throat[1] == 0 && ps.throat[2] == 0,
          "tube R %g: throats %d %d %d, want %d along x", radius[t], ps.throat[0], ps.throat[1],
          ps.throat[2], across[t]);
    mdp_image_free(&img);
  }
}

/* A slit of width 9 (y) along x whose middle section x = 5..8 narrows to 3: the throat along x is
 * 3, along z (the slit's other direction, open at the wide part) 9. */
static void test_constriction(void) {
  mdp_image_t img;
  const int wall = 3, wide = 9, narrow = 3;
  solid_block(&img, 14, wide + 2 * wall, 10);
  for (int k = 0; k < 10; k++)
    for (int i = 0; i < 14; i++) {
      const int lo = (i >= 5 && i <= 8) ? wall + (wide - narrow) / 2 : wall;
      const int w = (i >= 5 && i <= 8) ? narrow : wide;
      for (int j = lo; j < lo + w; j++) set_pore(&img, i, j, k);
    }
  mdp_image_pore_sizes_t ps;
  sizes(&img, 0, &ps);
  CHECK(ps.throat[0] == narrow && ps.throat[2] == wide,
        "constriction: throats x %d z %d, want %d and %d", ps.throat[0], ps.throat[2], narrow,
        wide);
  CHECK(ps.labellings > 0 && ps.labellings < 40, "labellings %d", ps.labellings);
  mdp_image_free(&img);
}

static void test_periodic_spheres(void) {
  mdp_image_t img;
  double achieved;
  CHECK(mdp_make_spheres(&img, 10, 0.3, 2, &achieved, err) == 0, "%s", err);
  mdp_image_axis_periodicity_t per[3];
  CHECK(mdp_image_periodicity(&img, per, err) == 0, "%s", err);
  for (int a = 0; a < 3; a++) {
    CHECK_CLOSE(per[a].overlap, 1.0, 0);
    CHECK(per[a].pore_both == per[a].pore_first && per[a].pore_first == per[a].pore_last,
          "axis %d: end slices %lld %lld both %lld", a, per[a].pore_first, per[a].pore_last,
          per[a].pore_both);
    CHECK(per[a].percolates_open && per[a].percolates_wrap, "axis %d percolates", a);
    CHECK(per[a].connected_wrap == per[a].connected_open && per[a].wrap_only_clusters == 0 &&
              per[a].seam_blocked_clusters == 0,
          "axis %d: wrap %lld open %lld", a, per[a].connected_wrap, per[a].connected_open);
  }
  /* a crop 3 voxels short of whole cells: the end slices no longer match */
  mdp_image_t crop;
  const int lo[3] = {0, 0, 0}, size[3] = {17, 20, 20};
  CHECK(mdp_image_crop(&img, lo, size, &crop, err) == 0, "%s", err);
  CHECK(mdp_image_periodicity(&crop, per, err) == 0, "%s", err);
  CHECK(per[0].overlap < 0.95 && per[0].pore_both < per[0].pore_either, "crop: overlap %g",
        per[0].overlap);
  CHECK_CLOSE(per[1].overlap, 1.0, 0);
  mdp_image_free(&crop);
  mdp_image_free(&img);
}

/* A channel along x at (y, z) = (1, 1) with a branch up to y = 4 on slice 0, and a pocket on the
 * last slice at y = 4 that only the seam joins to it; and a Z-shaped channel whose ends miss each
 * other at the seam. */
static void test_seam(void) {
  mdp_image_t img;
  solid_block(&img, 12, 6, 3);
  for (int i = 0; i < 12; i++) set_pore(&img, i, 1, 1);
  for (int j = 2; j <= 4; j++) set_pore(&img, 0, j, 1);
  for (int i = 9; i < 12; i++) set_pore(&img, i, 4, 1);
  mdp_image_axis_periodicity_t per[3];
  CHECK(mdp_image_periodicity(&img, per, err) == 0, "%s", err);
  CHECK(per[0].pore_first == 4 && per[0].pore_last == 2 && per[0].pore_both == 2 &&
            per[0].pore_either == 4,
        "ends %lld %lld %lld %lld", per[0].pore_first, per[0].pore_last, per[0].pore_both,
        per[0].pore_either);
  CHECK_CLOSE(per[0].overlap, 0.5, 1e-12);
  CHECK_CLOSE(per[0].overlap_face, 2.0 / 18.0, 1e-12);
  CHECK(per[0].percolates_wrap && per[0].wrap_only_clusters == 1 && per[0].wrap_only_voxels == 3 &&
            per[0].seam_blocked_clusters == 0 && per[0].connected_wrap == 18,
        "pocket: wrap %d only %d (%lld) blocked %d connected %lld", per[0].percolates_wrap,
        per[0].wrap_only_clusters, per[0].wrap_only_voxels, per[0].seam_blocked_clusters,
        per[0].connected_wrap);
  mdp_image_free(&img);

  solid_block(&img, 12, 6, 3);
  for (int i = 0; i <= 5; i++) set_pore(&img, i, 1, 1);
  for (int j = 2; j <= 4; j++) set_pore(&img, 5, j, 1);
  for (int i = 5; i < 12; i++) set_pore(&img, i, 4, 1);
  CHECK(mdp_image_periodicity(&img, per, err) == 0, "%s", err);
  CHECK(per[0].percolates_open && !per[0].percolates_wrap && per[0].seam_blocked_clusters == 1 &&
            per[0].seam_blocked_voxels == 15 && per[0].pore_both == 0 && per[0].overlap == 0,
        "Z: open %d wrap %d blocked %d (%lld) both %lld", per[0].percolates_open,
        per[0].percolates_wrap, per[0].seam_blocked_clusters, per[0].seam_blocked_voxels,
        per[0].pore_both);
  mdp_image_free(&img);
}

int main(void) {
  test_edt_brute_force();
  test_slit_throat();
  test_tube_throat();
  test_constriction();
  test_periodic_spheres();
  test_seam();
  if (check_failures) {
    fprintf(stderr, "%d checks failed\n", check_failures);
    return 1;
  }
  printf("image sizes and periodicity: all checks passed\n");
  return 0;
}
