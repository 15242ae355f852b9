#define _GNU_SOURCE /* strverscmp */
/* TIFF stacks via libtiff: one multi-page file or a folder of single-page slices (sorted by name,
 * numbers compared by value). Each page is one z slice: width nx, height ny, 8- or 16-bit grey. */
#include "image_internal.h"
#include "mdpore_image.h"

#include <stdio.h>
#include <string.h>

#ifndef MDPORE_HAVE_TIFF

int mdp_image_tiff_available(void) {
  return 0;
}
int mdp_image_read_tiff(const char *path, const mdp_image_read_opts_t *opts, mdp_image_t *img,
                        char *err) {
  return mdp_image_read_tiff_box(path, opts, NULL, img, NULL, err);
}
int mdp_image_read_tiff_box(const char *path, const mdp_image_read_opts_t *opts,
                            const mdp_image_box_t *box, mdp_image_t *img, int dims[3], char *err) {
  (void)opts, (void)box, (void)dims;
  (void)img;
  snprintf(err, MDP_IMAGE_ERR_LEN,
           "%s: mdpore was built without libtiff; install libtiff-dev and rebuild, or convert the "
           "stack to raw/HDF5",
           path);
  return 1;
}
int mdp_image_write_tiff(const mdp_image_t *img, const char *path, char *err) {
  (void)img;
  snprintf(err, MDP_IMAGE_ERR_LEN, "%s: mdpore was built without libtiff", path);
  return 1;
}

#else

#include <dirent.h>
#include <limits.h>
#include <stdlib.h>
#include <strings.h>
#include <sys/stat.h>
#include <tiffio.h>

int mdp_image_tiff_available(void) {
  return 1;
}

/* The pages read so far (nz: all pages seen). With a box, data holds only the box (allocated
 * once) and pages outside it are skipped undecoded; size 0 (dims only) decodes nothing. */
typedef struct {
  int nx, ny, nz, cap;
  uint8_t *data;
  const mdp_image_box_t *box;
} stack_t_;

static void quiet_handler(const char *module, const char *fmt, va_list ap) {
  (void)module, (void)fmt, (void)ap;
}

/* Append every page of one TIFF file to the stack. whole_stack: the file is the whole stack (not a
 * slice of a folder), so its PageNumber tags count its own pages. */
static int read_pages(const char *file, stack_t_ *st, int whole_stack, char *err) {
  TIFF *t = TIFFOpen(file, "r");
  if (!t) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: cannot open as TIFF", file);
    return 1;
  }
  int page = 0, rc = 0;
  do {
    uint32_t w = 0, h = 0;
    uint16_t bps = 8, spp = 1;
    TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &w);
    TIFFGetField(t, TIFFTAG_IMAGELENGTH, &h);
    TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &bps);
    TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &spp);
    if (spp != 1 || (bps != 8 && bps != 16) || TIFFIsTiled(t)) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "%s page %d: %u samples/pixel, %u bits%s; expected one 8- or 16-bit grey sample per "
               "pixel in strips (a segmented label image)",
               file, page, spp, bps, TIFFIsTiled(t) ? ", tiled" : "");
      rc = 1;
      break;
    }
    if (w < 1 || h < 1 || w > INT_MAX || h > INT_MAX) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "%s page %d: size %ux%u (expected 1 to %d pixels per axis in tags ImageWidth and "
               "ImageLength)",
               file, page, w, h, INT_MAX);
      rc = 1;
      break;
    }
    if (st->nz == 0) st->nx = (int)w, st->ny = (int)h;
    if ((int)w != st->nx || (int)h != st->ny) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s page %d: size %ux%u differs from the first slice %dx%d",
               file, page, w, h, st->nx, st->ny);
      rc = 1;
      break;
    }
    size_t per = (size_t)w * h;
    const mdp_image_box_t *b = st->box;
    const int z = st->nz,
              in_box = b && b->size[0] > 0 && z >= b->lo[2] && z < b->lo[2] + b->size[2];
    if (b && !in_box) { /* a page outside the box: counted, not decoded */
      st->nz++;
      page++;
      if (TIFFLastDirectory(t)) break;
      if (!TIFFReadDirectory(t)) {
        snprintf(err, MDP_IMAGE_ERR_LEN,
                 "%s: page %d cannot be read after %d pages (expected a complete stack: a "
                 "truncated or damaged file?)",
                 file, page, page);
        rc = 1;
        break;
      }
      continue;
    }
    if (b && (b->lo[0] + b->size[0] > (int)w || b->lo[1] + b->size[1] > (int)h)) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "%s page %d: size %ux%u, smaller than the box read (x %d..%d, y %d..%d)", file, page,
               w, h, b->lo[0], b->lo[0] + b->size[0] - 1, b->lo[1], b->lo[1] + b->size[1] - 1);
      rc = 1;
      break;
    }
    if (!b && st->nz == st->cap) {
      const int cap = st->cap ? 2 * st->cap : 1;
      char what[96];
      snprintf(what, sizeof what, "page %d of %ux%u pixels", page, w, h);
      /* the stack grown to cap pages, and the image it is copied into */
      if (mdp_image_check_memory(2.0 * (double)per * cap, file, what, err)) {
        rc = 1;
        break;
      }
      st->cap = cap;
      uint8_t *d = realloc(st->data, per * (size_t)st->cap);
      if (!d) {
        snprintf(err, MDP_IMAGE_ERR_LEN, "%s: out of memory", file);
        rc = 1;
        break;
      }
      st->data = d;
    }
    const tmsize_t line_bytes = TIFFScanlineSize(t);
    if (line_bytes < (tmsize_t)w * (bps / 8)) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "%s page %d: rows of %lld bytes (expected %u pixels of %u bits; damaged tags)", file,
               page, (long long)line_bytes, w, bps);
      rc = 1;
      break;
    }
    tdata_t line = _TIFFmalloc(line_bytes);
    if (!line) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s page %d: out of memory for a row", file, page);
      rc = 1;
      break;
    }
    /* rows are decoded in order up to the last one the box needs (strips may be compressed) */
    const uint32_t y_end = b ? (uint32_t)(b->lo[1] + b->size[1]) : h;
    for (uint32_t y = 0; y < y_end && !rc; y++) {
      if (TIFFReadScanline(t, line, y, 0) < 0) {
        snprintf(err, MDP_IMAGE_ERR_LEN, "%s page %d: cannot read row %u", file, page, y);
        rc = 1;
        break;
      }
      for (uint32_t x = 0; x < w; x++) {
        unsigned v = bps == 8 ? ((uint8_t *)line)[x] : ((uint16_t *)line)[x];
        if (v > 255) {
          snprintf(err, MDP_IMAGE_ERR_LEN,
                   "%s page %d: pixel (%u,%u) has label %u; labels must be 0..255", file, page, x,
                   y, v);
          rc = 1;
          break;
        }
        if (!b)
          st->data[per * (size_t)st->nz + (size_t)y * w + x] = (uint8_t)v;
        else if ((int)y >= b->lo[1] && (int)x >= b->lo[0] && (int)x < b->lo[0] + b->size[0])
          st->data[(size_t)b->size[0] * ((size_t)(y - (uint32_t)b->lo[1]) +
                                         (size_t)b->size[1] * (size_t)(z - b->lo[2])) +
                   (x - (uint32_t)b->lo[0])] = (uint8_t)v;
      }
    }
    _TIFFfree(line);
    if (rc) break;
    st->nz++;
    page++;
    uint16_t pnum = 0, ptotal = 0;
    if (TIFFLastDirectory(t)) {
      /* the last page: a PageNumber tag that counts more pages means a truncated stack */
      if (whole_stack && TIFFGetField(t, TIFFTAG_PAGENUMBER, &pnum, &ptotal) && ptotal > page) {
        snprintf(err, MDP_IMAGE_ERR_LEN,
                 "%s: %d pages, but tag PageNumber says %u (expected every page: a truncated "
                 "stack?)",
                 file, page, ptotal);
        rc = 1;
      }
      break;
    }
    if (!TIFFReadDirectory(t)) {
      snprintf(err, MDP_IMAGE_ERR_LEN,
               "%s: page %d cannot be read after %d pages (expected a complete stack: a truncated "
               "or damaged file?)",
               file, page, page);
      rc = 1;
      break;
    }
  } while (1);
  TIFFClose(t);
  return rc;
}

static int by_version(const void *a, const void *b) {
  return strverscmp(*(char *const *)a, *(char *const *)b);
}

static int has_tiff_ext(const char *name) {
  const char *dot = strrchr(name, '.');
  return dot && (!strcasecmp(dot, ".tif") || !strcasecmp(dot, ".tiff"));
}

int mdp_image_read_tiff(const char *path, const mdp_image_read_opts_t *opts, mdp_image_t *img,
                        char *err) {
  return mdp_image_read_tiff_box(path, opts, NULL, img, NULL, err);
}

int mdp_image_read_tiff_box(const char *path, const mdp_image_read_opts_t *opts,
                            const mdp_image_box_t *box, mdp_image_t *img, int dims[3], char *err) {
  TIFFSetWarningHandler(quiet_handler);
  TIFFSetErrorHandler(quiet_handler);
  stack_t_ st = {0, 0, 0, 0, NULL, box};
  const int only_dims = box && (box->size[0] < 1 || box->size[1] < 1 || box->size[2] < 1);
  if (box && !only_dims) {
    char what[96];
    snprintf(what, sizeof what, "a box of %dx%dx%d voxels", box->size[0], box->size[1],
             box->size[2]);
    if (mdp_image_check_memory(2.0 * (double)box->size[0] * box->size[1] * box->size[2], path, what,
                               err))
      return 1;
    st.data = malloc((size_t)box->size[0] * (size_t)box->size[1] * (size_t)box->size[2]);
    if (!st.data) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s: out of memory for %s", path, what);
      return 1;
    }
  }
  struct stat sb;
  int rc = 0;
  memset(img, 0, sizeof *img);
  if (stat(path, &sb) != 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: no such file or folder", path);
    return 1;
  }
  if (S_ISDIR(sb.st_mode)) {
    DIR *d = opendir(path);
    char **names = NULL;
    int n = 0, cap = 0, oom = 0;
    struct dirent *e;
    while (d && (e = readdir(d))) {
      if (!has_tiff_ext(e->d_name)) continue;
      if (n == cap) {
        char **grown = realloc(names, sizeof *names * (size_t)(cap ? 2 * cap : 64));
        if (!grown) {
          oom = 1;
          break;
        }
        names = grown, cap = cap ? 2 * cap : 64;
      }
      if (!(names[n] = strdup(e->d_name))) {
        oom = 1;
        break;
      }
      n++;
    }
    if (d) closedir(d);
    if (oom) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s: out of memory listing %d slices of the folder", path,
               n);
      rc = 1;
    } else if (n == 0) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s: folder holds no .tif/.tiff slices", path);
      rc = 1;
    }
    qsort(names, (size_t)n, sizeof *names, by_version);
    for (int f = 0; f < n && !rc; f++) {
      char file[4096];
      snprintf(file, sizeof file, "%s/%s", path, names[f]);
      rc = read_pages(file, &st, 0, err);
    }
    for (int f = 0; f < n; f++) free(names[f]);
    free(names);
  } else {
    rc = read_pages(path, &st, 1, err);
  }
  if (dims) dims[0] = st.nx, dims[1] = st.ny, dims[2] = st.nz;
  if (!rc && box && !only_dims && box->lo[2] + box->size[2] > st.nz) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: %d pages, fewer than the box read (z %d..%d)", path,
             st.nz, box->lo[2], box->lo[2] + box->size[2] - 1);
    rc = 1;
  }
  if (only_dims) {
    free(st.data);
    return rc;
  }
  const int bn[3] = {box ? box->size[0] : st.nx, box ? box->size[1] : st.ny,
                     box ? box->size[2] : st.nz};
  if (!rc && (rc = mdp_image_alloc(img, bn[0], bn[1], bn[2], err)))
    mdp_image_err_prefix(err, path, "ImageWidth/ImageLength");
  else if (!rc) {
    memcpy(img->label, st.data, mdp_image_count(img));
    rc = mdp_image_parse_labels(opts->labels[0] ? opts->labels : MDP_IMAGE_DEFAULT_LABELS,
                                img->phase_of, err);
    if (rc) mdp_image_err_prefix(err, path, "labels");
    if (opts->voxel_size > 0) img->voxel_size = opts->voxel_size;
    if (opts->unit[0]) snprintf(img->unit, sizeof img->unit, "%s", opts->unit);
    if (!rc && !box) rc = mdp_image_check_labels(img, path, err);
    if (rc) mdp_image_free(img);
  }
  free(st.data);
  return rc;
}

int mdp_image_write_tiff(const mdp_image_t *img, const char *path, char *err) {
  char tmp[4096];
  mdp_image_tmp_path(path, tmp, sizeof tmp);
  TIFF *t = TIFFOpen(tmp, "w");
  if (!t) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%.800s: cannot create TIFF", tmp);
    return 1;
  }
  int bad = 0;
  for (int k = 0; k < img->nz && !bad; k++) {
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, (uint32_t)img->nx);
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, (uint32_t)img->ny);
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 8);
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, (uint32_t)img->ny);
    TIFFSetField(t, TIFFTAG_SUBFILETYPE, FILETYPE_PAGE);
    TIFFSetField(t, TIFFTAG_PAGENUMBER, (uint16_t)k, (uint16_t)img->nz);
    for (int j = 0; j < img->ny && !bad; j++)
      bad = TIFFWriteScanline(t, img->label + mdp_image_index(img, 0, j, k), (uint32_t)j, 0) < 0;
    bad |= !TIFFWriteDirectory(t);
  }
  TIFFClose(t);
  if (bad) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%.800s: writing TIFF failed", tmp);
    remove(tmp);
    return 1;
  }
  return mdp_image_commit(tmp, path, err);
}

#endif
