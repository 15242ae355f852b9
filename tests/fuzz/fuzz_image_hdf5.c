/* Fuzz entry: HDF5 images through mdp_image_read. The input does not hold HDF5 bytes (that would
 * fuzz libhdf5's own file parser): it describes a file that this entry writes with the HDF5 API, so
 * every mutation is a well-formed file with other contents: the dataset's type, rank, shape,
 * storage and name, and the voxel_size, unit and label_map attributes with any type and shape.
 *   byte 0: dataset type   1: rank (0..4)   2: flags (1 chunked, 2 huge shape, 4 other name,
 *   8 a group named labels)   3..6: the dims   then per attribute (voxel_size, unit, label_map):
 *   kind, length, bytes (a number or text)   the rest: the voxel values' bytes, repeated. */
#include "fuzz_image_box.h"
#include "fuzz_util.h"
#include "mdpore_image.h"

#include <hdf5.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  const uint8_t *p;
  size_t n, at;
} bytes_t;

static unsigned take(bytes_t *b) {
  return b->at < b->n ? b->p[b->at++] : 0;
}

/* One attribute: kind 0 absent, 1 double scalar, 2 three doubles, 3 int scalar, 4 fixed-length
 * string, 5 variable-length string, 6 two strings, 7 a null dataspace (no value); len bytes of
 * value (a double, or text). */
typedef struct {
  unsigned kind, len;
  uint8_t raw[48];
} attr_t;

static void take_attr(bytes_t *b, attr_t *a) {
  a->kind = take(b) % 8;
  a->len = take(b) % 48;
  memset(a->raw, 0, sizeof a->raw);
  for (unsigned i = 0; i < a->len; i++) a->raw[i] = (uint8_t)take(b);
}

static void attribute(hid_t obj, const char *name, const attr_t *at) {
  const unsigned kind = at->kind, len = at->len;
  if (kind == 0) return;
  hid_t type = -1, space = -1;
  const void *value = at->raw;
  char text[49], *texts[2];
  double d[3] = {0, 0, 0};
  memcpy(text, at->raw, len);
  text[len] = 0;
  if (kind == 1 || kind == 2 || kind == 7) {
    memcpy(d, at->raw, sizeof d);
    if (len < 8) d[0] = (double)at->raw[0] * 0.5 - 2; /* short: a plain small number, maybe <= 0 */
    type = H5Tcopy(H5T_NATIVE_DOUBLE);
    value = d;
  } else if (kind == 3) {
    type = H5Tcopy(H5T_NATIVE_INT32);
  } else if (kind == 4) {
    type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, len ? len : 1);
    value = text;
  } else {
    type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    texts[0] = texts[1] = text;
    value = texts;
  }
  if (kind == 7) {
    space = H5Screate(H5S_NULL);
  } else if (kind == 2 || kind == 6) {
    hsize_t n = kind == 2 ? 3 : 2;
    space = H5Screate_simple(1, &n, NULL);
  } else {
    space = H5Screate(H5S_SCALAR);
  }
  hid_t a = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (a >= 0) {
    if (kind != 7) H5Awrite(a, type, value);
    H5Aclose(a);
  }
  H5Sclose(space);
  H5Tclose(type);
}

static void write_file(const char *path, bytes_t *b) {
  const unsigned tsel = take(b) % 8, rank = take(b) % 5, flags = take(b);
  hsize_t dims[4] = {1, 1, 1, 1}, chunk[4] = {1, 1, 1, 1};
  hsize_t count = 1;
  for (unsigned r = 0; r < 4; r++) {
    const unsigned v = take(b);
    if (r >= rank) continue;
    dims[r] = v % 9; /* 0..8 voxels; huge: up to 2^40 along one axis */
    if ((flags & 3) == 3 && r == 0) dims[r] = (hsize_t)(v % 9 + 1) << (v % 41);
    chunk[r] = dims[r] < 64 ? (dims[r] ? dims[r] : 1) : 64;
    count *= dims[r];
  }
  attr_t attrs[3];
  for (int i = 0; i < 3; i++) take_attr(b, &attrs[i]);
  H5E_auto2_t func;
  void *client;
  H5Eget_auto2(H5E_DEFAULT, &func, &client);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) abort();
  if (flags & 8) H5Gclose(H5Gcreate2(file, "/labels", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  const hid_t types[] = {H5T_NATIVE_UINT8, H5T_NATIVE_INT16,  H5T_NATIVE_INT32, H5T_NATIVE_INT64,
                         H5T_NATIVE_FLOAT, H5T_NATIVE_UINT16, H5T_NATIVE_INT8,  H5T_C_S1};
  hid_t type = H5Tcopy(types[tsel]);
  if (tsel == 7) H5Tset_size(type, 4);
  hid_t space = rank ? H5Screate_simple((int)rank, dims, NULL) : H5Screate(H5S_SCALAR);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  int chunked = (flags & 1) && rank > 0;
  for (unsigned r = 0; r < rank; r++) chunked &= dims[r] > 0;
  if (chunked) H5Pset_chunk(dcpl, (int)rank, chunk);
  if ((flags & 2) && !chunked) count = 0; /* a huge shape needs chunks: keep it small otherwise */
  const char *name = flags & 8 ? "/labels/x" : flags & 4 ? "/other" : "/labels";
  hid_t dset = H5Dcreate2(file, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (dset >= 0 && count > 0 && count <= 4096 && !((flags & 3) == 3)) {
    const size_t tsize = H5Tget_size(type);
    uint8_t *buf = malloc((size_t)count * tsize);
    const size_t rest = b->n > b->at ? b->n - b->at : 0;
    for (size_t i = 0; i < (size_t)count * tsize; i++) buf[i] = rest ? b->p[b->at + i % rest] : 0;
    H5Dwrite(dset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
    free(buf);
  }
  if (dset >= 0) {
    attribute(dset, "voxel_size", &attrs[0]);
    attribute(dset, "unit", &attrs[1]);
    attribute(dset, "label_map", &attrs[2]);
    H5Dclose(dset);
  }
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Tclose(type);
  H5Fclose(file);
  H5Eset_auto2(H5E_DEFAULT, func, client);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  char path[300], err[MDP_IMAGE_ERR_LEN] = "";
  fuzz_path("image.h5", path, sizeof path);
  bytes_t b = {data, size, 0};
  write_file(path, &b);
  mdp_image_read_opts_t o;
  mdp_image_read_opts_init(&o);
  mdp_image_t img;
  const int rc = mdp_image_read(path, &o, &img, err);
  fuzz_image_box_check(path, &o, rc == 0 ? &img : NULL); /* before the outcome replay judges */
  if (rc == 0) mdp_image_free(&img);
  fuzz_outcome(rc, err, path);
  return 0;
}
