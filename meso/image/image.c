/* Image basics: allocation, metadata, voxel-size units. */
#include "image_internal.h"
#include "common/memory_limit.h"
#include "mdpore_image.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void mdp_image_read_opts_init(mdp_image_read_opts_t *o) {
  memset(o, 0, sizeof *o);
  o->header_bytes = -1;
}

int mdp_image_check_memory(double bytes, const char *path, const char *what, char *err) {
  const double limit = mdp_memory_limit();
  if (bytes <= limit) return 0;
  snprintf(err, MDP_IMAGE_ERR_LEN,
           "%.400s: %.200s needs %.3g GB of memory, more than the %.3g GB this machine allows "
           "(physical memory, or MDPORE_MEMORY_LIMIT in bytes)",
           path, what, bytes / 1e9, limit / 1e9);
  return 1;
}

int mdp_image_alloc(mdp_image_t *img, int nx, int ny, int nz, char *err) {
  return mdp_image_alloc_beside(img, nx, ny, nz, 0, err);
}

int mdp_image_alloc_beside(mdp_image_t *img, int nx, int ny, int nz, double held, char *err) {
  memset(img, 0, sizeof *img);
  if (nx <= 0 || ny <= 0 || nz <= 0) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "image dimensions %dx%dx%d: each must be >= 1", nx, ny, nz);
    return 1;
  }
  /* the count in double: three int dimensions can overflow 64 bits (2^31 cubed) */
  const double count = (double)nx * (double)ny * (double)nz;
  char what[160];
  if (held > 0)
    snprintf(what, sizeof what,
             "an image of %dx%dx%d voxels made beside the %.4g voxels it is made from", nx, ny, nz,
             held);
  else
    snprintf(what, sizeof what, "an image of %dx%dx%d voxels", nx, ny, nz);
  if (count > MDP_IMAGE_MAX_VOXELS) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "%s: %.3g voxels, more than the %.3g an image can index (expected a product of the "
             "dimensions of at most %.3g)",
             what, count, MDP_IMAGE_MAX_VOXELS, MDP_IMAGE_MAX_VOXELS);
    return 1;
  }
  if (mdp_image_check_memory(count + held, "image", what, err)) return 1;
  const size_t n = (size_t)nx * (size_t)ny * (size_t)nz;
  img->label = calloc(n, 1);
  if (!img->label) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "out of memory for a %dx%dx%d image (%zu bytes)", nx, ny, nz,
             n);
    return 1;
  }
  img->nx = nx;
  img->ny = ny;
  img->nz = nz;
  img->voxel_size = 1.0;
  strcpy(img->unit, "voxel");
  memset(img->phase_of, MDP_PHASE_UNSET, sizeof img->phase_of);
  return 0;
}

void mdp_image_free(mdp_image_t *img) {
  free(img->label);
  img->label = NULL;
  img->nx = img->ny = img->nz = 0;
}

int mdp_image_copy_meta(mdp_image_t *dst, const mdp_image_t *src) {
  dst->voxel_size = src->voxel_size;
  memcpy(dst->unit, src->unit, sizeof dst->unit);
  memcpy(dst->phase_of, src->phase_of, sizeof dst->phase_of);
  return 0;
}

static const struct {
  const char *name;
  double metres;
} units[] = {{"m", 1.0}, {"mm", 1e-3}, {"um", 1e-6}, {"nm", 1e-9}, {"voxel", 0.0}};

double mdp_image_voxel_size_m(const mdp_image_t *img) {
  for (size_t u = 0; u < sizeof units / sizeof units[0]; u++)
    if (!strcmp(img->unit, units[u].name)) return img->voxel_size * units[u].metres;
  return 0.0;
}

int mdp_image_parse_voxel_size(const char *text, double *size, char unit[8], char *err) {
  errno = 0;
  char *end = NULL;
  double v = strtod(text, &end);
  if (end == text || errno || !(v > 0) || !isfinite(v)) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "voxel size '%s': expected a finite positive number with a unit, e.g. 10um", text);
    return 1;
  }
  while (isspace((unsigned char)*end)) end++;
  if (!*end) {
    *size = v;
    return 0; /* caller keeps its unit */
  }
  for (size_t u = 0; u < sizeof units / sizeof units[0]; u++)
    if (!strcmp(end, units[u].name)) {
      *size = v;
      snprintf(unit, 8, "%s", units[u].name);
      return 0;
    }
  snprintf(err, MDP_IMAGE_ERR_LEN,
           "voxel size '%s': unknown unit '%s' (expected m, mm, um, nm or voxel)", text, end);
  return 1;
}

const char *mdp_phase_name(int phase) {
  switch (phase) {
  case MDP_PHASE_PORE:
    return "pore";
  case MDP_PHASE_ORGANIC:
    return "organic";
  case MDP_PHASE_INORGANIC:
    return "inorganic";
  default:
    return "unset";
  }
}
