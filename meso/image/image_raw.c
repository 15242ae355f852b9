/* Raw binary images: user-given layout or a sidecar header (PATH.hdr, "key: value" lines). */
#include "image_internal.h"
#include "mdpore_image.h"
#include "common/text.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int mdp_image_read_sidecar(const char *path, mdp_image_read_opts_t *o, char *err) {
  FILE *f = fopen(path, "r");
  if (!f) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: cannot open sidecar header: %s", path, strerror(errno));
    return 1;
  }
  char line[1024];
  int lineno = 0, rc = 0;
  while (!rc && fgets(line, sizeof line, f)) {
    lineno++;
    char *hash = strchr(line, '#');
    if (hash) *hash = 0;
    char *s = text_trim(line);
    if (!*s) continue;
    char *sep = strpbrk(s, ":=");
    if (!sep) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s:%d: expected 'key: value', got '%s'", path, lineno, s);
      rc = 1;
      break;
    }
    *sep = 0;
    char *key = text_trim(s), *val = text_trim(sep + 1);
    int bad = 0;
    if (!strcmp(key, "dims")) {
      int d[3];
      bad = mdp_image_parse_dims(val, d);
      if (!bad && !o->nx) o->nx = d[0], o->ny = d[1], o->nz = d[2];
    } else if (!strcmp(key, "type")) {
      if (!o->type[0]) snprintf(o->type, sizeof o->type, "%s", val);
    } else if (!strcmp(key, "byte_order")) {
      if (!o->byte_order[0]) snprintf(o->byte_order, sizeof o->byte_order, "%s", val);
    } else if (!strcmp(key, "axis_order")) {
      if (!o->axis_order[0]) snprintf(o->axis_order, sizeof o->axis_order, "%s", val);
      bad = strlen(val) != 3;
    } else if (!strcmp(key, "header_bytes")) {
      char *end;
      long long v = strtoll(val, &end, 10);
      bad = end == val || *end || v < 0;
      if (!bad && o->header_bytes < 0) o->header_bytes = v;
    } else if (!strcmp(key, "voxel_size")) {
      double size = 0;
      char unit[8] = "";
      if (mdp_image_parse_voxel_size(val, &size, unit, err)) {
        snprintf(err, MDP_IMAGE_ERR_LEN, "%s:%d: voxel_size '%s': expected e.g. '10 um'", path,
                 lineno, val);
        rc = 1;
        break;
      }
      if (o->voxel_size <= 0) {
        o->voxel_size = size;
        if (unit[0] && !o->unit[0]) memcpy(o->unit, unit, sizeof unit);
      }
    } else if (!strcmp(key, "unit")) {
      if (!o->unit[0]) snprintf(o->unit, sizeof o->unit, "%s", val);
    } else if (!strcmp(key, "labels")) {
      if (!o->labels[0]) snprintf(o->labels, sizeof o->labels, "%s", val);
    } else {
      snprintf(
          err, MDP_IMAGE_ERR_LEN,
          "%s:%d: unknown key '%s' (expected dims, type, byte_order, axis_order, header_bytes, "
          "voxel_size, unit, labels)",
          path, lineno, key);
      rc = 1;
      break;
    }
    if (bad) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s:%d: bad value '%s' for key '%s'", path, lineno, val,
               key);
      rc = 1;
    }
  }
  fclose(f);
  return rc;
}

static int type_size(const char *type) {
  if (!strcmp(type, "uint8") || !strcmp(type, "int8")) return 1;
  if (!strcmp(type, "uint16") || !strcmp(type, "int16")) return 2;
  if (!strcmp(type, "uint32") || !strcmp(type, "int32")) return 4;
  return 0;
}

/* One element of the given type and byte order as a signed 64-bit value. */
static long long element(const unsigned char *p, const char *type, int big) {
  int size = type_size(type);
  unsigned long long u = 0;
  for (int b = 0; b < size; b++) u |= (unsigned long long)p[big ? size - 1 - b : b] << (8 * b);
  if (type[0] == 'i') { /* sign-extend */
    unsigned long long sign = 1ull << (8 * size - 1);
    return (long long)((u ^ sign) - sign);
  }
  return (long long)u;
}

/* The file's layout: the options completed from the sidecar and defaults, checked against the
 * file size. axis[f] = box axis (0 x, 1 y, 2 z) of the f-th fastest file index. 0 or 1 + err. */
static int raw_layout(const char *path, const mdp_image_read_opts_t *opts,
                      mdp_image_read_opts_t *out, int axis[3], int *esize, int *big_endian,
                      char *err) {
  mdp_image_read_opts_t o = *opts;
  char side[4096];
  snprintf(side, sizeof side, "%s.hdr", path);
  struct stat sb;
  if (stat(side, &sb) == 0 && mdp_image_read_sidecar(side, &o, err)) return 1;
  if (!o.nx) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%.400s: dimensions unknown: give --dims NXxNYxNZ or write a sidecar header %.400s "
             "(see docs/images.md)",
             path, side);
    return 1;
  }
  if (!o.type[0]) strcpy(o.type, "uint8");
  if (!o.byte_order[0]) strcpy(o.byte_order, "little");
  if (!o.axis_order[0]) strcpy(o.axis_order, "xyz");
  if (o.header_bytes < 0) o.header_bytes = 0;
  if (!o.labels[0]) snprintf(o.labels, sizeof o.labels, "%s", MDP_IMAGE_DEFAULT_LABELS);
  int size = type_size(o.type);
  if (!size) {
    snprintf(
        err, MDP_IMAGE_ERR_LEN,
        "%s: data type '%s' not supported (expected uint8, int8, uint16, int16, uint32, int32)",
        path, o.type);
    return 1;
  }
  int big = !strcmp(o.byte_order, "big");
  if (!big && strcmp(o.byte_order, "little")) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: byte order '%s': expected little or big", path,
             o.byte_order);
    return 1;
  }
  int seen = 0;
  for (int f = 0; f < 3; f++) {
    char c = (char)tolower((unsigned char)o.axis_order[f]);
    axis[f] = c == 'x' ? 0 : c == 'y' ? 1 : c == 'z' ? 2 : -1;
    if (axis[f] < 0 || (seen & (1 << axis[f]))) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "%s: axis order '%s': expected a permutation of x, y, z, fastest first (e.g. xyz)",
               path, o.axis_order);
      return 1;
    }
    seen |= 1 << axis[f];
  }
  if (stat(path, &sb) != 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: cannot open: %s", path, strerror(errno));
    return 1;
  }
  long long n, data_bytes, need;
  if (__builtin_mul_overflow((long long)o.nx, (long long)o.ny, &n) ||
      __builtin_mul_overflow(n, (long long)o.nz, &n) ||
      __builtin_mul_overflow(n, (long long)size, &data_bytes) ||
      __builtin_add_overflow(o.header_bytes, data_bytes, &need)) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: key 'dims' %dx%dx%d of %s after a %lld-byte header: the file size overflows 64 "
             "bits (expected dims of an image that fits in a file)",
             path, o.nx, o.ny, o.nz, o.type, o.header_bytes);
    return 1;
  }
  if ((long long)sb.st_size != need) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: file has %lld bytes but %dx%dx%d voxels of %s after a %lld-byte header need %lld "
             "bytes: check --dims/--type/--header-bytes",
             path, (long long)sb.st_size, o.nx, o.ny, o.nz, o.type, o.header_bytes, need);
    return 1;
  }
  *out = o;
  *esize = size;
  *big_endian = big;
  return 0;
}

/* The box [lo, lo + size) (box == NULL: the whole image), read run by run along the file's fastest
 * axis: a rank reading its part of a large image seeks past the rest. */
int mdp_image_read_raw_box(const char *path, const mdp_image_read_opts_t *opts,
                           const mdp_image_box_t *box, mdp_image_t *img, int dims[3], char *err) {
  mdp_image_read_opts_t o;
  int axis[3], size, big;
  memset(img, 0, sizeof *img);
  if (raw_layout(path, opts, &o, axis, &size, &big, err)) return 1;
  const int dim[3] = {o.nx, o.ny, o.nz};
  if (dims) memcpy(dims, dim, sizeof dim);
  int lo[3] = {0, 0, 0}, sz[3] = {o.nx, o.ny, o.nz};
  if (box) memcpy(lo, box->lo, sizeof lo), memcpy(sz, box->size, sizeof sz);
  if (box && (sz[0] < 1 || sz[1] < 1 || sz[2] < 1)) return 0; /* dims only */
  const long long n = (long long)sz[0] * sz[1] * sz[2];
  char what[128];
  snprintf(what, sizeof what, "key 'dims' %dx%dx%d of %s", o.nx, o.ny, o.nz, o.type);
  if (mdp_image_check_memory((double)n + (double)sz[axis[0]] * size, path, what, err)) return 1;
  if (mdp_image_alloc(img, sz[0], sz[1], sz[2], err)) {
    mdp_image_err_prefix(err, path, "dims");
    return 1;
  }
  if (mdp_image_parse_labels(o.labels, img->phase_of, err)) {
    mdp_image_err_prefix(err, path, "labels");
    goto fail;
  }
  if (o.voxel_size > 0) img->voxel_size = o.voxel_size;
  if (o.unit[0]) snprintf(img->unit, sizeof img->unit, "%s", o.unit);
  const int nf[3] = {dim[axis[0]], dim[axis[1]], dim[axis[2]]};
  const int run = sz[axis[0]];
  FILE *f = fopen(path, "rb");
  unsigned char *buf = malloc((size_t)run * (size_t)size);
  long long at = -1; /* the file position after the last run: seek only where runs are apart */
  for (int c2 = lo[axis[2]]; f && buf && c2 < lo[axis[2]] + sz[axis[2]]; c2++)
    for (int c1 = lo[axis[1]]; c1 < lo[axis[1]] + sz[axis[1]]; c1++) {
      const long long first = ((long long)c2 * nf[1] + c1) * nf[0] + lo[axis[0]];
      const long long off = o.header_bytes + first * size;
      if ((off != at && fseeko(f, (off_t)off, SEEK_SET) != 0) ||
          fread(buf, (size_t)size, (size_t)run, f) != (size_t)run) {
        snprintf(err, MDP_IMAGE_ERR_LEN, "%s: read failed: short read", path);
        fclose(f);
        free(buf);
        goto fail;
      }
      at = off + (long long)run * size;
      for (int c0 = 0; c0 < run; c0++) {
        int ijk[3];
        ijk[axis[0]] = lo[axis[0]] + c0, ijk[axis[1]] = c1, ijk[axis[2]] = c2;
        long long v = element(buf + (size_t)c0 * size, o.type, big);
        if (v < 0 || v > 255) {
          snprintf(err, MDP_IMAGE_ERR_LEN,
                   "%s: voxel (%d,%d,%d) has label %lld; labels must be 0..255 (segmented image "
                   "expected)",
                   path, ijk[0], ijk[1], ijk[2], v);
          fclose(f);
          free(buf);
          goto fail;
        }
        img->label[mdp_image_index(img, ijk[0] - lo[0], ijk[1] - lo[1], ijk[2] - lo[2])] =
            (uint8_t)v;
      }
    }
  if (!f || !buf) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: read failed: %s", path,
             f ? "out of memory" : strerror(errno));
    if (f) fclose(f);
    free(buf);
    goto fail;
  }
  fclose(f);
  free(buf);
  if (!box && mdp_image_check_labels(img, path, err)) goto fail;
  return 0;
fail:
  mdp_image_free(img);
  return 1;
}

int mdp_image_read_raw(const char *path, const mdp_image_read_opts_t *opts, mdp_image_t *img,
                       char *err) {
  return mdp_image_read_raw_box(path, opts, NULL, img, NULL, err);
}

int mdp_image_write_raw(const mdp_image_t *img, const char *path, char *err) {
  char tmp[4096], side[4096], stmp[4096], map[512];
  mdp_image_tmp_path(path, tmp, sizeof tmp);
  snprintf(side, sizeof side, "%s.hdr", path);
  mdp_image_tmp_path(side, stmp, sizeof stmp);
  FILE *f = fopen(tmp, "wb");
  size_t n = mdp_image_count(img);
  if (!f || fwrite(img->label, 1, n, f) != n || fclose(f) != 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%.800s: cannot write: %s", tmp, strerror(errno));
    remove(tmp);
    return 1;
  }
  mdp_image_format_labels(img->phase_of, map, sizeof map);
  FILE *h = fopen(stmp, "w");
  if (!h) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%.800s: cannot write: %s", stmp, strerror(errno));
    remove(tmp);
    return 1;
  }
  fprintf(
      h,
      "# mdpore raw image sidecar (docs/images.md)\ndims: %d %d %d\ntype: uint8\n"
      "byte_order: little\naxis_order: xyz\nheader_bytes: 0\nvoxel_size: %.17g %s\nlabels: %s\n",
      img->nx, img->ny, img->nz, img->voxel_size, img->unit, map);
  if (fclose(h) != 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%.800s: cannot write: %s", stmp, strerror(errno));
    remove(tmp);
    remove(stmp);
    return 1;
  }
  if (mdp_image_commit(tmp, path, err)) {
    remove(stmp);
    return 1;
  }
  return mdp_image_commit(stmp, side, err);
}
