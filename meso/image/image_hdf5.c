/* HDF5 images: dataset of integer labels with dims [nz][ny][nx] (x fastest in memory), attributes
 * voxel_size (double), unit (string), label_map (string, same syntax as --labels). Serial API only.
 */
#include "image_internal.h"
#include "mdpore_image.h"

#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Read a string attribute (fixed or variable length) into out; 0 when present. */
static int read_string_attr(hid_t obj, const char *name, char *out, size_t len) {
  if (H5Aexists(obj, name) <= 0) return 1;
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT), t = H5Aget_type(a);
  int rc = 1;
  if (H5Tget_class(t) == H5T_STRING) {
    if (H5Tis_variable_str(t) > 0) {
      char *s = NULL;
      hid_t mt = H5Tcopy(H5T_C_S1);
      H5Tset_size(mt, H5T_VARIABLE);
      if (H5Aread(a, mt, &s) >= 0 && s) {
        snprintf(out, len, "%s", s);
        H5free_memory(s);
        rc = 0;
      }
      H5Tclose(mt);
    } else {
      size_t sz = H5Tget_size(t);
      char *buf = calloc(sz + 1, 1);
      hid_t mt = H5Tcopy(H5T_C_S1);
      H5Tset_size(mt, sz + 1);
      if (buf && H5Aread(a, mt, buf) >= 0) {
        snprintf(out, len, "%s", buf);
        rc = 0;
      }
      H5Tclose(mt);
      free(buf);
    }
  }
  H5Tclose(t);
  H5Aclose(a);
  return rc;
}

int mdp_image_read_hdf5(const char *path, const mdp_image_read_opts_t *opts, mdp_image_t *img,
                        char *err) {
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
  if (mdp_image_alloc(img, (int)dims[2], (int)dims[1], (int)dims[0], err)) goto done;
  char text[256] = "";
  const char *labels = opts->labels[0] ? opts->labels : NULL;
  if (!labels && !read_string_attr(dset, "label_map", text, sizeof text)) labels = text;
  if (!labels) labels = MDP_IMAGE_DEFAULT_LABELS;
  if (mdp_image_parse_labels(labels, img->phase_of, err)) goto done;
  if (H5Aexists(dset, "voxel_size") > 0) {
    hid_t a = H5Aopen(dset, "voxel_size", H5P_DEFAULT);
    H5Aread(a, H5T_NATIVE_DOUBLE, &img->voxel_size);
    H5Aclose(a);
  }
  read_string_attr(dset, "unit", img->unit, sizeof img->unit);
  if (opts->voxel_size > 0) img->voxel_size = opts->voxel_size;
  if (opts->unit[0]) snprintf(img->unit, sizeof img->unit, "%s", opts->unit);
  /* Slice by slice as int32 so that any integer type is range-checked without a full-size copy. */
  size_t per = (size_t)img->nx * (size_t)img->ny;
  slice = malloc(per * sizeof *slice);
  hsize_t mdim[1] = {per};
  mspace = H5Screate_simple(1, mdim, NULL);
  for (int k = 0; k < img->nz; k++) {
    hsize_t start[3] = {(hsize_t)k, 0, 0}, count[3] = {1, dims[1], dims[2]};
    H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL);
    if (!slice || H5Dread(dset, H5T_NATIVE_INT32, mspace, space, H5P_DEFAULT, slice) < 0) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s: reading dataset '%s' slice z=%d failed", path, dname,
               k);
      goto done;
    }
    for (size_t p = 0; p < per; p++) {
      if (slice[p] < 0 || slice[p] > 255) {
        snprintf(err, MDP_IMAGE_ERR_LEN,
                 "%s: dataset '%s' voxel (%d,%d,%d) has label %d; labels must be 0..255", path,
                 dname, (int)(p % (size_t)img->nx), (int)(p / (size_t)img->nx), k, (int)slice[p]);
        goto done;
      }
      img->label[per * (size_t)k + p] = (uint8_t)slice[p];
    }
  }
  rc = mdp_image_check_labels(img, path, err);
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

int mdp_image_write_hdf5(const mdp_image_t *img, const char *path, char *err) {
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
