/* Helpers over the serial HDF5 C API (see h5_util.h). */
#include "io/h5_util.h"

#include <stdio.h>
#include <string.h>

static void attr_write(hid_t loc, const char *name, hid_t type, const void *v, hsize_t n) {
  hid_t sp = n ? H5Screate_simple(1, &n, NULL) : H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(loc, name, type, sp, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, v);
  H5Aclose(a);
  H5Sclose(sp);
}

void h5_attr_double(hid_t loc, const char *name, const double *v, hsize_t n) {
  attr_write(loc, name, H5T_NATIVE_DOUBLE, v, n);
}
void h5_attr_long(hid_t loc, const char *name, long v) {
  attr_write(loc, name, H5T_NATIVE_LONG, &v, 0);
}
void h5_attr_u64(hid_t loc, const char *name, unsigned long long v) {
  attr_write(loc, name, H5T_NATIVE_ULLONG, &v, 0);
}

void h5_attr_string(hid_t loc, const char *name, const char *v) {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, strlen(v) + 1);
  attr_write(loc, name, t, v, 0);
  H5Tclose(t);
}

static int attr_read(hid_t loc, const char *name, hid_t type, void *v) {
  if (H5Aexists(loc, name) <= 0) return -1;
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  herr_t e = H5Aread(a, type, v);
  H5Aclose(a);
  return e < 0 ? -1 : 0;
}

int h5_read_attr_double(hid_t loc, const char *name, double *v, hsize_t n) {
  (void)n;
  return attr_read(loc, name, H5T_NATIVE_DOUBLE, v);
}
int h5_read_attr_long(hid_t loc, const char *name, long *v) {
  return attr_read(loc, name, H5T_NATIVE_LONG, v);
}
int h5_read_attr_u64(hid_t loc, const char *name, unsigned long long *v) {
  return attr_read(loc, name, H5T_NATIVE_ULLONG, v);
}

int h5_read_attr_string(hid_t loc, const char *name, char *v, size_t len) {
  v[0] = 0;
  if (H5Aexists(loc, name) <= 0) return -1;
  hid_t a = H5Aopen(loc, name, H5P_DEFAULT);
  hid_t t = H5Aget_type(a);
  int rc = -1;
  if (H5Tget_class(t) == H5T_STRING && H5Tget_size(t) <= len) rc = H5Aread(a, t, v) < 0 ? -1 : 0;
  H5Tclose(t);
  H5Aclose(a);
  return rc;
}

int h5_write_dataset(hid_t loc, const char *name, hid_t type, const void *data, hsize_t n,
                     hsize_t m) {
  hsize_t dims[2] = {n, m};
  hid_t sp = H5Screate_simple(m > 1 ? 2 : 1, dims, NULL);
  hid_t d = H5Dcreate2(loc, name, type, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  herr_t e = d < 0 ? -1 : (n ? H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) : 0);
  if (d >= 0) H5Dclose(d);
  H5Sclose(sp);
  return d < 0 || e < 0 ? -1 : 0;
}

long h5_dataset_rows(hid_t loc, const char *name) {
  if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) return -1;
  hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
  hid_t sp = H5Dget_space(d);
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(sp, dims, NULL);
  H5Sclose(sp);
  H5Dclose(d);
  return (long)dims[0];
}

hid_t h5_create_row_table(hid_t loc, const char *name, hsize_t ncol) {
  hsize_t dims[2] = {0, ncol}, maxd[2] = {H5S_UNLIMITED, ncol}, chunk[2] = {256, ncol};
  hid_t sp = H5Screate_simple(2, dims, maxd), pl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(pl, 2, chunk);
  const hid_t d = H5Dcreate2(loc, name, H5T_NATIVE_DOUBLE, sp, H5P_DEFAULT, pl, H5P_DEFAULT);
  H5Pclose(pl);
  H5Sclose(sp);
  return d;
}

void h5_append_row(hid_t file, hid_t dset, long rows, hsize_t ncol, const double *row) {
  hsize_t dims[2] = {(hsize_t)rows + 1, ncol}, start[2] = {(hsize_t)rows, 0}, count[2] = {1, ncol};
  H5Dset_extent(dset, dims);
  hid_t fs = H5Dget_space(dset), ms = H5Screate_simple(2, count, NULL);
  H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL);
  H5Dwrite(dset, H5T_NATIVE_DOUBLE, ms, fs, H5P_DEFAULT, row);
  H5Sclose(ms);
  H5Sclose(fs);
  H5Fflush(file, H5F_SCOPE_LOCAL);
}

int h5_read_dataset(hid_t loc, const char *name, hid_t type, void *data, hsize_t n, hsize_t m,
                    const char *file) {
  if (H5Lexists(loc, name, H5P_DEFAULT) <= 0) {
    fprintf(stderr, "%s: expected dataset '%s' (missing)\n", file, name);
    return -1;
  }
  hid_t d = H5Dopen2(loc, name, H5P_DEFAULT);
  hid_t sp = H5Dget_space(d);
  hsize_t dims[2] = {0, 0};
  const int rank = H5Sget_simple_extent_dims(sp, dims, NULL);
  H5Sclose(sp);
  if (dims[0] != n || (m > 1 ? rank != 2 || dims[1] != m : rank != 1)) {
    fprintf(stderr, "%s: dataset '%s': expected %llu x %llu values (got %llu x %llu)\n", file, name,
            (unsigned long long)n, (unsigned long long)m, (unsigned long long)dims[0],
            (unsigned long long)(rank == 2 ? dims[1] : 1));
    H5Dclose(d);
    return -1;
  }
  herr_t e = n ? H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) : 0;
  H5Dclose(d);
  return e < 0 ? -1 : 0;
}
