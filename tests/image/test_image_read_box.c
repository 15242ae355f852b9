/* Partial reads (mdp_image_read_box, image_read_box.c): boxes of a 7 x 6 x 5 image read from HDF5,
 * raw (the writer's layout, and uint16 big-endian z-fastest after a header), a multi-page TIFF and
 * a folder of TIFF slices equal the same voxels of the whole image read; the size alone (size NULL)
 * reads no voxel; a box outside the image and an unknown label inside the box are errors that name
 * the box and the voxel in the whole image's coordinates. */
#include "check.h"
#include "mdpore_image.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

enum { NX = 7, NY = 6, NZ = 5 };
static char dir[256];

static uint8_t label(int i, int j, int k) {
  return (uint8_t)((7 * i + 3 * j + 5 * k + i * j) % 3);
}

/* Every box with lo in {0, 1, n - 2} and size in {1, 2, n - lo} along each axis. */
static void check_boxes(const char *path, const mdp_image_read_opts_t *o, const char *what) {
  char err[MDP_IMAGE_ERR_LEN];
  int dims[3] = {0, 0, 0}, boxes = 0, bad = 0;
  mdp_image_t img;
  int rc = mdp_image_read_box(path, o, NULL, NULL, &img, dims, err);
  CHECK(rc == 0 && dims[0] == NX && dims[1] == NY && dims[2] == NZ && !img.label,
        "%s: size only: rc %d, %dx%dx%d (%s)", what, rc, dims[0], dims[1], dims[2], err);
  const int n[3] = {NX, NY, NZ};
  int los[3][3], szs[3][3];
  for (int d = 0; d < 3; d++) los[d][0] = 0, los[d][1] = 1, los[d][2] = n[d] - 2;
  for (int a = 0; a < 27; a++) {
    const int lo[3] = {los[0][a % 3], los[1][a / 3 % 3], los[2][a / 9]};
    for (int d = 0; d < 3; d++) szs[d][0] = 1, szs[d][1] = 2, szs[d][2] = n[d] - lo[d];
    for (int b = 0; b < 27; b++) {
      const int sz[3] = {szs[0][b % 3], szs[1][b / 3 % 3], szs[2][b / 9]};
      rc = mdp_image_read_box(path, o, lo, sz, &img, NULL, err);
      boxes++;
      if (rc || img.nx != sz[0] || img.ny != sz[1] || img.nz != sz[2]) {
        bad++;
        if (bad < 3) fprintf(stderr, "%s: box read failed: %s\n", what, err);
        if (!rc) mdp_image_free(&img);
        continue;
      }
      for (int k = 0; k < sz[2]; k++)
        for (int j = 0; j < sz[1]; j++)
          for (int i = 0; i < sz[0]; i++)
            bad +=
                img.label[mdp_image_index(&img, i, j, k)] != label(lo[0] + i, lo[1] + j, lo[2] + k);
      mdp_image_free(&img);
    }
  }
  CHECK(bad == 0, "%s: %d of %d boxes differ from the image", what, bad, boxes);
  const int lo[3] = {NX - 2, 0, 0}, sz[3] = {3, 1, 1};
  CHECK_ERR_HAS(mdp_image_read_box(path, o, lo, sz, &img, NULL, err), err,
                "box x 5..7: expected voxels inside the image's 7 x 6 x 5");
  printf("%s: %d boxes read\n", what, boxes);
}

int main(void) {
  snprintf(dir, sizeof dir, "%s/mdpore-read-box-XXXXXX",
           getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
  if (!mkdtemp(dir)) return 1;
  char err[MDP_IMAGE_ERR_LEN], path[600];
  mdp_image_t ref;
  mdp_image_alloc(&ref, NX, NY, NZ, err);
  mdp_image_parse_labels("pore=0,organic=2,inorganic=1", ref.phase_of, err);
  for (int k = 0; k < NZ; k++)
    for (int j = 0; j < NY; j++)
      for (int i = 0; i < NX; i++) ref.label[mdp_image_index(&ref, i, j, k)] = label(i, j, k);
  mdp_image_read_opts_t o;
  mdp_image_read_opts_init(&o);
  snprintf(path, sizeof path, "%s/ref.h5", dir);
  CHECK(mdp_image_write_hdf5(&ref, path, err) == 0, "%s", err);
  check_boxes(path, &o, "hdf5");
  snprintf(path, sizeof path, "%s/ref.raw", dir);
  CHECK(mdp_image_write_raw(&ref, path, err) == 0, "%s", err);
  check_boxes(path, &o, "raw");
  /* raw: uint16 big endian, z fastest, 5-byte header */
  {
    unsigned char buf[5 + 2 * NX * NY * NZ];
    memset(buf, 0xCD, 5);
    size_t p = 5;
    for (int i = 0; i < NX; i++)
      for (int j = 0; j < NY; j++)
        for (int k = 0; k < NZ; k++) buf[p++] = 0, buf[p++] = label(i, j, k);
    snprintf(path, sizeof path, "%s/zyx.raw", dir);
    FILE *f = fopen(path, "wb");
    CHECK(f && fwrite(buf, 1, sizeof buf, f) == sizeof buf, "cannot write %s", path);
    if (f) fclose(f);
    mdp_image_read_opts_t z;
    mdp_image_read_opts_init(&z);
    z.nx = NX, z.ny = NY, z.nz = NZ, z.header_bytes = 5;
    strcpy(z.type, "uint16"), strcpy(z.byte_order, "big"), strcpy(z.axis_order, "zyx");
    check_boxes(path, &z, "raw uint16 zyx");
  }
  if (mdp_image_tiff_available()) {
    mdp_image_read_opts_t t;
    mdp_image_read_opts_init(&t);
    strcpy(t.labels, "pore=0,organic=2,inorganic=1");
    snprintf(path, sizeof path, "%s/ref.tif", dir);
    CHECK(mdp_image_write_tiff(&ref, path, err) == 0, "%s", err);
    check_boxes(path, &t, "tiff");
    /* a folder of slices, one page each */
    char sub[400];
    snprintf(sub, sizeof sub, "%s/slices", dir);
    mkdir(sub, 0755);
    mdp_image_t s;
    mdp_image_alloc(&s, NX, NY, 1, err);
    memcpy(s.phase_of, ref.phase_of, sizeof s.phase_of);
    for (int k = 0; k < NZ; k++) {
      memcpy(s.label, ref.label + (size_t)NX * NY * k, (size_t)NX * NY);
      snprintf(path, sizeof path, "%s/z_%d.tif", sub, k + 1);
      CHECK(mdp_image_write_tiff(&s, path, err) == 0, "%s", err);
    }
    mdp_image_free(&s);
    check_boxes(sub, &t, "tiff folder");
  } else {
    printf("TIFF boxes skipped: built without libtiff\n");
  }
  /* a label outside the map inside the box: named in the whole image's coordinates */
  snprintf(path, sizeof path, "%s/ref.h5", dir);
  strcpy(o.labels, "pore=0,inorganic=1");
  const int lo[3] = {2, 3, 1}, sz[3] = {5, 3, 4};
  mdp_image_t img;
  CHECK_ERR_HAS(mdp_image_read_box(path, &o, lo, sz, &img, NULL, err), err, "has label 2");
  char want[64];
  int first = -1;
  for (int k = 0; k < sz[2] && first < 0; k++)
    for (int j = 0; j < sz[1] && first < 0; j++)
      for (int i = 0; i < sz[0] && first < 0; i++)
        if (label(lo[0] + i, lo[1] + j, lo[2] + k) == 2) {
          first = 1;
          snprintf(want, sizeof want, "voxel (%d,%d,%d)", lo[0] + i, lo[1] + j, lo[2] + k);
        }
  CHECK(strstr(err, want) != NULL, "expected '%s' in: %s", want, err);
  mdp_image_free(&ref);
  char cmd[600];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
  if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
  printf("%s: %d failures\n", __FILE__, check_failures);
  return check_failures ? 1 : 0;
}
