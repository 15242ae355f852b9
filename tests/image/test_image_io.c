/* Image readers and writers: raw layouts (type, byte order, axis order, header, sidecar), HDF5 and
 * TIFF round trips, and the errors for wrong sizes and unknown labels. */
#include "check.h"
#include "mdpore_image.h"

#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

static char dir[256];

/* Reference image: label(i,j,k) = (i + 2j + 3k) % 3, 5 x 4 x 3 voxels. */
static uint8_t ref_label(int i, int j, int k) {
  return (uint8_t)((i + 2 * j + 3 * k) % 3);
}

static void write_bytes(const char *path, const void *data, size_t n) {
  FILE *f = fopen(path, "wb");
  fwrite(data, 1, n, f);
  fclose(f);
}

static void test_labels(void) {
  char err[MDP_IMAGE_ERR_LEN], text[512];
  uint8_t map[256];
  CHECK(mdp_image_parse_labels("pore=0,organic=2,inorganic=1,3-5", map, err) == 0, "%s", err);
  CHECK(map[0] == MDP_PHASE_PORE && map[2] == MDP_PHASE_ORGANIC && map[4] == MDP_PHASE_INORGANIC &&
            map[6] == MDP_PHASE_UNSET,
        "map values");
  mdp_image_format_labels(map, text, sizeof text);
  uint8_t back[256];
  CHECK(mdp_image_parse_labels(text, back, err) == 0 && !memcmp(map, back, 256), "round trip '%s'",
        text);
  CHECK_ERR_HAS(mdp_image_parse_labels("pore=0,shale=1", map, err), err, "unknown phase 'shale'");
  CHECK_ERR_HAS(mdp_image_parse_labels("pore=0,inorganic=0", map, err), err, "both");
  CHECK_ERR_HAS(mdp_image_parse_labels("inorganic=1", map, err), err, "no value is mapped to pore");
}

static void test_raw_layouts(void) {
  char err[MDP_IMAGE_ERR_LEN], path[512];
  const int nx = 5, ny = 4, nz = 3;
  /* uint16, big endian, z fastest (axis order zyx), 7-byte header */
  unsigned char buf[7 + 2 * 60];
  memset(buf, 0xAB, 7);
  size_t p = 7;
  for (int i = 0; i < nx; i++)
    for (int j = 0; j < ny; j++)
      for (int k = 0; k < nz; k++) {
        buf[p++] = 0;
        buf[p++] = ref_label(i, j, k);
      }
  snprintf(path, sizeof path, "%s/zyx.raw", dir);
  write_bytes(path, buf, sizeof buf);
  mdp_image_read_opts_t o;
  mdp_image_read_opts_init(&o);
  o.nx = nx, o.ny = ny, o.nz = nz, o.header_bytes = 7;
  strcpy(o.type, "uint16");
  strcpy(o.byte_order, "big");
  strcpy(o.axis_order, "zyx");
  strcpy(o.labels, "pore=0,organic=2,inorganic=1");
  mdp_image_t img;
  int rc = mdp_image_read_raw(path, &o, &img, err);
  CHECK(rc == 0, "%s", err);
  if (!rc) {
    int bad = 0;
    for (int k = 0; k < nz; k++)
      for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
          bad += img.label[mdp_image_index(&img, i, j, k)] != ref_label(i, j, k);
    CHECK(bad == 0, "%d voxels differ after zyx/big-endian/header read", bad);
    mdp_image_free(&img);
  }
  /* wrong size: named in bytes */
  o.nx = 6;
  CHECK_ERR_HAS(mdp_image_read_raw(path, &o, &img, err), err, "file has 127 bytes");
  /* unknown label: map without value 2 */
  o.nx = nx;
  strcpy(o.labels, "pore=0,inorganic=1");
  CHECK_ERR_HAS(mdp_image_read_raw(path, &o, &img, err), err, "has label 2");

  /* sidecar header supplies everything */
  char side[600];
  snprintf(side, sizeof side, "%s.hdr", path);
  FILE *f = fopen(side, "w");
  fprintf(f,
          "# test\ndims: 5x4x3\ntype: uint16\nbyte_order: big\naxis_order: zyx\nheader_bytes: 7\n"
          "voxel_size: 8 nm\nlabels: pore=0;organic=2;inorganic=1\n");
  fclose(f);
  mdp_image_read_opts_init(&o);
  rc = mdp_image_read(path, &o, &img, err);
  CHECK(rc == 0, "%s", err);
  if (!rc) {
    CHECK(img.nx == 5 && img.ny == 4 && img.nz == 3, "dims from sidecar");
    CHECK_CLOSE(mdp_image_voxel_size_m(&img), 8e-9, 1e-20);
    CHECK(img.label[mdp_image_index(&img, 4, 3, 2)] == ref_label(4, 3, 2), "voxel (4,3,2)");
    mdp_image_free(&img);
  }
  f = fopen(side, "w");
  fprintf(f, "dims: 5x4x3\ncolour: blue\n");
  fclose(f);
  CHECK_ERR_HAS(mdp_image_read(path, &o, &img, err), err, ".hdr:2: unknown key 'colour'");
  remove(side);
  CHECK_ERR_HAS(mdp_image_read(path, &o, &img, err), err, "dimensions unknown");
}

static void make_reference(mdp_image_t *img) {
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_alloc(img, 5, 4, 3, err);
  mdp_image_parse_labels("pore=0,organic=2,inorganic=1", img->phase_of, err);
  for (int k = 0; k < 3; k++)
    for (int j = 0; j < 4; j++)
      for (int i = 0; i < 5; i++) img->label[mdp_image_index(img, i, j, k)] = ref_label(i, j, k);
  img->voxel_size = 2.5;
  strcpy(img->unit, "um");
}

static void test_round_trips(void) {
  char err[MDP_IMAGE_ERR_LEN], path[512];
  mdp_image_t ref, back;
  make_reference(&ref);
  const char *ext[] = {"h5", "raw", "tif"};
  for (int e = 0; e < 3; e++) {
    if (e == 2 && !mdp_image_tiff_available()) {
      printf("TIFF round trip skipped: built without libtiff\n");
      continue;
    }
    snprintf(path, sizeof path, "%s/ref.%s", dir, ext[e]);
    int rc = e == 0   ? mdp_image_write_hdf5(&ref, path, err)
             : e == 1 ? mdp_image_write_raw(&ref, path, err)
                      : mdp_image_write_tiff(&ref, path, err);
    CHECK(rc == 0, "write %s: %s", ext[e], err);
    mdp_image_read_opts_t o;
    mdp_image_read_opts_init(&o);
    if (e == 2) strcpy(o.labels, "pore=0,organic=2,inorganic=1"); /* TIFF carries no map */
    rc = mdp_image_read(path, &o, &back, err);
    CHECK(rc == 0, "read %s: %s", ext[e], err);
    if (rc) continue;
    CHECK(back.nx == 5 && back.ny == 4 && back.nz == 3, "%s dims %dx%dx%d", ext[e], back.nx,
          back.ny, back.nz);
    CHECK(!memcmp(back.label, ref.label, 60), "%s labels differ", ext[e]);
    CHECK(!memcmp(back.phase_of, ref.phase_of, 256), "%s label map differs", ext[e]);
    if (e < 2) CHECK_CLOSE(mdp_image_voxel_size_m(&back), 2.5e-6, 1e-18);
    mdp_image_free(&back);
  }
  /* HDF5 with a label outside the map given on the command line */
  snprintf(path, sizeof path, "%s/ref.h5", dir);
  mdp_image_read_opts_t o;
  mdp_image_read_opts_init(&o);
  strcpy(o.labels, "pore=0,inorganic=1");
  CHECK_ERR_HAS(mdp_image_read(path, &o, &back, err), err, "has label 2");
  mdp_image_read_opts_init(&o);
  strcpy(o.dataset, "/nope");
  CHECK_ERR_HAS(mdp_image_read(path, &o, &back, err), err, "no dataset '/nope'");
  mdp_image_free(&ref);
}

/* A folder of single-page TIFF slices named slice_1 ... slice_12: numeric, not text, order. */
static void test_tiff_folder(void) {
  if (!mdp_image_tiff_available()) return;
  char err[MDP_IMAGE_ERR_LEN], sub[512], path[600];
  snprintf(sub, sizeof sub, "%s/slices", dir);
  mkdir(sub, 0755);
  mdp_image_t s;
  mdp_image_alloc(&s, 3, 2, 1, err);
  mdp_image_parse_labels("pore=0-20", s.phase_of, err);
  for (int z = 1; z <= 12; z++) {
    memset(s.label, z, 6);
    snprintf(path, sizeof path, "%s/slice_%d.tif", sub, z);
    CHECK(mdp_image_write_tiff(&s, path, err) == 0, "%s", err);
  }
  mdp_image_read_opts_t o;
  mdp_image_read_opts_init(&o);
  strcpy(o.labels, "pore=0-20");
  mdp_image_t img;
  int rc = mdp_image_read(sub, &o, &img, err);
  CHECK(rc == 0, "%s", err);
  if (!rc) {
    CHECK(img.nz == 12, "nz %d", img.nz);
    int bad = 0;
    for (int z = 0; z < img.nz; z++) bad += img.label[mdp_image_index(&img, 2, 1, z)] != z + 1;
    CHECK(bad == 0, "%d slices out of numeric order", bad);
    mdp_image_free(&img);
  }
  mdp_image_free(&s);
}

int main(void) {
  snprintf(dir, sizeof dir, "%s/mdpore-image-test-XXXXXX",
           getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  if (!mkdtemp(dir)) return 1;
  test_labels();
  test_raw_layouts();
  test_round_trips();
  test_tiff_folder();
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
  printf("%s: %d failures\n", __FILE__, check_failures);
  return check_failures ? 1 : 0;
}
