/* HDF5 images: dataset of integer labels with dims [nz][ny][nx] (x fastest in memory), attributes
 * voxel_size (double), unit (string), label_map (string, same syntax as --labels). Serial API only.
 */
#include "common/hdf5_lock.h"
#include "image_internal.h"
#include "mdpore_image.h"

#include <hdf5.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The number of elements of an attribute's dataspace (1 for a scalar, 0 for a null one). */
static long long attr_points(hid_t a) {
  hid_t sp = H5Aget_space(a);
  const long long n = sp >= 0 ? (long long)H5Sget_simple_extent_npoints(sp) : -1;
  if (sp >= 0) H5Sclose(sp);
  return n;
}

/* Read a string attribute (fixed or variable length, one value) into out (len bytes). Returns 1
 * when absent, 0 when read, -1 after a message in err (not one string, or longer than len - 1). */
static int read_string_attr(hid_t obj, const char *name, char *out, size_t len, const char *path,
                            const char *dname, char *err) {
  if (H5Aexists(obj, name) <= 0) return 1;
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT), t = a >= 0 ? H5Aget_type(a) : -1;
  int rc = -1;
  const long long points = a >= 0 ? attr_points(a) : -1;
  const int is_string = t >= 0 && H5Tget_class(t) == H5T_STRING;
  if (is_string && points == 1 && H5Tis_variable_str(t) > 0) {
    char *s = NULL;
    hid_t mt = H5Tcopy(H5T_C_S1);
    H5Tset_size(mt, H5T_VARIABLE);
    if (H5Aread(a, mt, &s) >= 0 && s) {
      rc = strlen(s) < len ? 0 : -2;
      if (!rc) snprintf(out, len, "%s", s);
      H5free_memory(s);
    }
    H5Tclose(mt);
  } else if (is_string && points == 1) {
    const size_t sz = H5Tget_size(t);
    char *buf = sz < len ? calloc(sz + 1, 1) : NULL;
    hid_t mt = H5Tcopy(H5T_C_S1);
    H5Tset_size(mt, sz + 1);
    if (sz >= len) {
      rc = -2;
    } else if (buf && H5Aread(a, mt, buf) >= 0) {
      snprintf(out, len, "%s", buf);
      rc = 0;
    }
    H5Tclose(mt);
    free(buf);
  }
  if (t >= 0) H5Tclose(t);
  if (a >= 0) H5Aclose(a);
  if (rc == -2)
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: dataset '%s' attribute '%s': expected a text of at most %zu characters", path,
             dname, name, len - 1);
  else if (rc)
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: dataset '%s' attribute '%s': expected one string (got %s%lld value%s)", path,
             dname, name, is_string ? "" : "a non-string type, ", points, points == 1 ? "" : "s");
  return rc ? -1 : 0;
}

/* The voxel_size attribute: one finite number > 0. 1 when absent, 0 when read, -1 after a message.
 */
static int read_voxel_size(hid_t obj, double *out, const char *path, const char *dname, char *err) {
  if (H5Aexists(obj, "voxel_size") <= 0) return 1;
  hid_t a = H5Aopen(obj, "voxel_size", H5P_DEFAULT), t = a >= 0 ? H5Aget_type(a) : -1;
  const H5T_class_t cls = t >= 0 ? H5Tget_class(t) : H5T_NO_CLASS;
  const long long points = a >= 0 ? attr_points(a) : -1;
  double v = NAN;
  int ok = (cls == H5T_FLOAT || cls == H5T_INTEGER) && points == 1 &&
           H5Aread(a, H5T_NATIVE_DOUBLE, &v) >= 0 && isfinite(v) && v > 0;
  if (t >= 0) H5Tclose(t);
  if (a >= 0) H5Aclose(a);
  if (ok) {
    *out = v;
    return 0;
  }
  if ((cls == H5T_FLOAT || cls == H5T_INTEGER) && points == 1)
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: dataset '%s' attribute 'voxel_size': expected a finite number > 0 (got %g)", path,
             dname, v);
  else
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: dataset '%s' attribute 'voxel_size': expected one number (got %s, %lld value%s)",
             path, dname,
             cls == H5T_STRING    ? "a string"
             : cls == H5T_FLOAT   ? "floats"
             : cls == H5T_INTEGER ? "integers"
                                  : "another type",
             points, points == 1 ? "" : "s");
  return -1;
}

static int mdp_image_read_hdf5_unlocked(const char *path, const mdp_image_read_opts_t *opts,
                                        mdp_image_t *img, char *err) {
  return mdp_image_read_hdf5_box(path, opts, NULL, img, NULL, err);
}

/* The box is a hyperslab of the dataset: only its voxels are read from the file (whole chunks of a
 * chunked dataset, decompressed by HDF5). */
static int mdp_image_read_hdf5_box_unlocked(const char *path, const mdp_image_read_opts_t *opts,
                                            const mdp_image_box_t *box, mdp_image_t *img,
                                            int dims_out[3], char *err) {
  const char *dname = opts->dataset[0] ? opts->dataset : "/labels";
  H5E_auto2_t old_func;
  void *old_data;
  H5Eget_auto2(H5E_DEFAULT, &old_func, &old_data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t file = -1, dset = -1, space = -1, mspace = -1;
  int32_t *slice = NULL;
  int rc = 1;
  memset(img, 0, sizeof *img);
  file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: cannot open as HDF5", path);
    goto done;
  }
  if (H5Lexists(file, dname, H5P_DEFAULT) <= 0 || (dset = H5Dopen2(file, dname, H5P_DEFAULT)) < 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: no dataset '%s' (choose one with --dataset PATH)", path,
             dname);
    goto done;
  }
  hid_t dtype = H5Dget_type(dset);
  H5T_class_t cls = H5Tget_class(dtype);
  H5Tclose(dtype);
  space = H5Dget_space(dset);
  hsize_t dims[3] = {0, 0, 0};
  int rank = H5Sget_simple_extent_ndims(space);
  if (cls != H5T_INTEGER || rank != 3) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: dataset '%s' must be a 3D integer array [nz][ny][nx] (has rank %d, %s)", path,
             dname, rank, cls == H5T_INTEGER ? "integer" : "not integer");
    goto done;
  }
  H5Sget_simple_extent_dims(space, dims, NULL);
  for (int a = 0; a < 3; a++)
    if (dims[a] < 1 || dims[a] > INT_MAX) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "%s: dataset '%s' has shape [%llu][%llu][%llu] (expected 1 to %d voxels per axis)",
               path, dname, (unsigned long long)dims[0], (unsigned long long)dims[1],
               (unsigned long long)dims[2], INT_MAX);
      goto done;
    }
  if (dims_out) dims_out[0] = (int)dims[2], dims_out[1] = (int)dims[1], dims_out[2] = (int)dims[0];
  int lo[3] = {0, 0, 0}, sz[3] = {(int)dims[2], (int)dims[1], (int)dims[0]};
  if (box) memcpy(lo, box->lo, sizeof lo), memcpy(sz, box->size, sizeof sz);
  if (box && (sz[0] < 1 || sz[1] < 1 || sz[2] < 1)) { /* dims only */
    rc = 0;
    goto done;
  }
  {
    char what[400];
    snprintf(what, sizeof what, "dataset '%s' of shape [%llu][%llu][%llu]", dname,
             (unsigned long long)dims[0], (unsigned long long)dims[1], (unsigned long long)dims[2]);
    /* the image, plus a slab of slices as int32 (one slice, or up to 4M voxels) */
    const double bytes = (double)sz[0] * (double)sz[1] * (double)sz[2] +
                         4.0 * (double)sz[0] * (double)sz[1] + 4.0 * (1 << 22);
    if (mdp_image_check_memory(bytes, path, what, err)) goto done;
  }
  if (mdp_image_alloc(img, sz[0], sz[1], sz[2], err)) {
    mdp_image_err_prefix(err, path, dname);
    goto done;
  }
  char text[256] = "";
  const char *labels = opts->labels[0] ? opts->labels : NULL;
  if (!labels) {
    const int got = read_string_attr(dset, "label_map", text, sizeof text, path, dname, err);
    if (got < 0) goto done;
    if (got == 0) labels = text;
  }
  if (!labels) labels = MDP_IMAGE_DEFAULT_LABELS;
  if (mdp_image_parse_labels(labels, img->phase_of, err)) {
    mdp_image_err_prefix(err, path, "label_map");
    goto done;
  }
  if (read_voxel_size(dset, &img->voxel_size, path, dname, err) < 0) goto done;
  if (read_string_attr(dset, "unit", img->unit, sizeof img->unit, path, dname, err) < 0) goto done;
  {
    static const char *const units[] = {"m", "mm", "um", "nm", "voxel"};
    int known = 0;
    for (int u = 0; u < 5; u++) known |= !strcmp(img->unit, units[u]);
    if (!known) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "%s: dataset '%s' attribute 'unit': expected m, mm, um, nm or voxel (got '%s')",
               path, dname, img->unit);
      goto done;
    }
  }
  if (opts->voxel_size > 0) img->voxel_size = opts->voxel_size;
  if (opts->unit[0]) snprintf(img->unit, sizeof img->unit, "%s", opts->unit);
  /* Slabs of whole slices as int32, so that any integer type is range-checked without a full-size
   * copy; thin slices are read several at a time (one read per slice of a tall, thin image costs
   * seconds per million slices). */
  const size_t per = (size_t)img->nx * (size_t)img->ny, slab_voxels = (size_t)1 << 22;
  const int nk = per >= slab_voxels ? 1
                                    : (int)(slab_voxels / per < (size_t)img->nz ? slab_voxels / per
                                                                                : (size_t)img->nz);
  slice = malloc(per * (size_t)nk * sizeof *slice);
  for (int k0 = 0; k0 < img->nz; k0 += nk) {
    const int kn = img->nz - k0 < nk ? img->nz - k0 : nk;
    hsize_t start[3] = {(hsize_t)(lo[2] + k0), (hsize_t)lo[1], (hsize_t)lo[0]};
    hsize_t count[3] = {(hsize_t)kn, (hsize_t)sz[1], (hsize_t)sz[0]};
    hsize_t mdim[1] = {per * (size_t)kn};
    if (mspace >= 0) H5Sclose(mspace);
    mspace = H5Screate_simple(1, mdim, NULL);
    H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL);
    if (!slice || H5Dread(dset, H5T_NATIVE_INT32, mspace, space, H5P_DEFAULT, slice) < 0) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s: reading dataset '%s' slices z=%d..%d failed", path,
               dname, lo[2] + k0, lo[2] + k0 + kn - 1);
      goto done;
    }
    for (size_t p = 0; p < per * (size_t)kn; p++) {
      if (slice[p] < 0 || slice[p] > 255) {
        const size_t q = p % per;
        snprintf(err, MDP_IMAGE_ERR_LEN,
                 "%s: dataset '%s' voxel (%d,%d,%d) has label %d; labels must be 0..255", path,
                 dname, lo[0] + (int)(q % (size_t)img->nx), lo[1] + (int)(q / (size_t)img->nx),
                 lo[2] + k0 + (int)(p / per), (int)slice[p]);
        goto done;
      }
      img->label[per * (size_t)k0 + p] = (uint8_t)slice[p];
    }
  }
  rc = box ? 0 : mdp_image_check_labels(img, path, err);
done:
  free(slice);
  if (mspace >= 0) H5Sclose(mspace);
  if (space >= 0) H5Sclose(space);
  if (dset >= 0) H5Dclose(dset);
  if (file >= 0) H5Fclose(file);
  H5Eset_auto2(H5E_DEFAULT, old_func, old_data);
  if (rc) mdp_image_free(img);
  return rc;
}

static int write_string_attr(hid_t obj, const char *name, const char *value) {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, strlen(value) + 1);
  hid_t s = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(obj, name, t, s, H5P_DEFAULT, H5P_DEFAULT);
  herr_t e = a >= 0 ? H5Awrite(a, t, value) : -1;
  if (a >= 0) H5Aclose(a);
  H5Sclose(s);
  H5Tclose(t);
  return e < 0;
}

static int mdp_image_write_hdf5_unlocked(const mdp_image_t *img, const char *path, char *err) {
  char tmp[4096], map[512];
  mdp_image_tmp_path(path, tmp, sizeof tmp);
  hid_t file = H5Fcreate(tmp, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%.800s: cannot create HDF5 file", tmp);
    return 1;
  }
  hsize_t dims[3] = {(hsize_t)img->nz, (hsize_t)img->ny, (hsize_t)img->nx};
  hid_t space = H5Screate_simple(3, dims, NULL), dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) > 0) {
    hsize_t chunk[3] = {dims[0] < 32 ? dims[0] : 32, dims[1] < 64 ? dims[1] : 64,
                        dims[2] < 64 ? dims[2] : 64};
    H5Pset_chunk(dcpl, 3, chunk);
    H5Pset_deflate(dcpl, 4);
  }
  hid_t dset = H5Dcreate2(file, "/labels", H5T_NATIVE_UINT8, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  int bad =
      dset < 0 || H5Dwrite(dset, H5T_NATIVE_UINT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, img->label) < 0;
  if (!bad) {
    hid_t s = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(dset, "voxel_size", H5T_NATIVE_DOUBLE, s, H5P_DEFAULT, H5P_DEFAULT);
    bad |= a < 0 || H5Awrite(a, H5T_NATIVE_DOUBLE, &img->voxel_size) < 0;
    if (a >= 0) H5Aclose(a);
    H5Sclose(s);
    mdp_image_format_labels(img->phase_of, map, sizeof map);
    bad |= write_string_attr(dset, "unit", img->unit);
    bad |= write_string_attr(dset, "label_map", map);
    bad |= write_string_attr(dset, "layout", "dims [nz][ny][nx]; x fastest");
  }
  if (dset >= 0) H5Dclose(dset);
  H5Pclose(dcpl);
  H5Sclose(space);
  bad |= H5Fclose(file) < 0;
  if (bad) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%.800s: writing HDF5 dataset /labels failed", tmp);
    remove(tmp);
    return 1;
  }
  return mdp_image_commit(tmp, path, err);
}

/* The public entry points: each whole call under the HDF5 lock (common/hdf5_lock.h). */
int mdp_image_read_hdf5(const char *path, const mdp_image_read_opts_t *opts, mdp_image_t *img,
                        char *err) {
  hdf5_lock();
  const int rc = mdp_image_read_hdf5_unlocked(path, opts, img, err);
  hdf5_unlock();
  return rc;
}

int mdp_image_read_hdf5_box(const char *path, const mdp_image_read_opts_t *opts,
                            const mdp_image_box_t *box, mdp_image_t *img, int dims_out[3],
                            char *err) {
  hdf5_lock();
  const int rc = mdp_image_read_hdf5_box_unlocked(path, opts, box, img, dims_out, err);
  hdf5_unlock();
  return rc;
}

int mdp_image_write_hdf5(const mdp_image_t *img, const char *path, char *err) {
  hdf5_lock();
  const int rc = mdp_image_write_hdf5_unlocked(img, path, err);
  hdf5_unlock();
  return rc;
}
