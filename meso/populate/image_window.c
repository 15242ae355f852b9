/* The rank's window of a geometry image (image_walls.h): which voxels it owns, which it generates
 * particles for, and the halo those need, read from the file with partial reads (mdpore_image.h:
 * HDF5 hyperslabs, raw runs, TIFF pages) so that no rank holds the whole image. Along a periodic
 * axis a range is taken modulo the image size (a window across the periodic face is read as two
 * pieces); a range as long as the axis is the whole axis, never more, so no voxel is held twice. */
#include "populate/image_walls.h"
#include "scene/scene_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* First voxel whose centre lies at or after the cut x (box coordinates): the owners of the voxels
 * are decided by their centres, the same arithmetic on both sides of a cut, so the ranks' own
 * ranges partition the image. */
static int centre_edge(double x, double lo, double h, int n) {
  const double t = ceil((x - lo) / h - 0.5);
  return t < 0 ? 0 : t > n ? n : (int)t;
}

/* [a, b) in unwrapped voxel coordinates into start + [0, len): clipped to the image along a
 * non-periodic axis, modulo n (and at most n long) along a periodic one. */
static void wrap_range(long a, long b, int n, int periodic, int *start, int *len) {
  if (!periodic) {
    a = a < 0 ? 0 : a > n ? n : a;
    b = b < a ? a : b > n ? n : b;
    *start = (int)a, *len = (int)(b - a);
  } else if (b - a >= n) {
    *start = 0, *len = n;
  } else {
    *start = (int)(((a % n) + n) % n), *len = (int)(b - a);
  }
}

long long image_walls_win(const image_walls_t *g, const int q[3]) {
  long long idx = 0, stride = 1;
  for (int d = 0; d < 3; d++) {
    int w = q[d];
    if (w < 0 || w >= g->n[d]) {
      if (!g->periodic[d]) return -1;
      w = ((w % g->n[d]) + g->n[d]) % g->n[d];
    }
    const int off = ((w - g->win_lo[d]) % g->n[d] + g->n[d]) % g->n[d];
    if (off >= g->win_n[d]) return -1;
    idx += stride * off;
    stride *= g->win_n[d];
  }
  return idx;
}

int image_walls_in_range(const image_walls_t *g, const int start[3], const int len[3],
                         const int q[3]) {
  for (int d = 0; d < 3; d++)
    if (((q[d] - start[d]) % g->n[d] + g->n[d]) % g->n[d] >= len[d]) return 0;
  return 1;
}

void image_walls_mem(image_walls_t *g, long long bytes) {
  g->mem_now += bytes;
  if (g->mem_now > g->mem_peak) g->mem_peak = g->mem_now;
}

int image_window_ranges(const scene_t *s, image_walls_t *g, const double sub_lo[3],
                        const double sub_hi[3], int halo, char *err, size_t errlen) {
  const scene_geometry_t *geo = &s->geometry;
  char e[MDP_IMAGE_ERR_LEN] = "";
  mdp_image_read_opts_t opts;
  mdp_image_read_opts_init(&opts);
  if (geo->labels[0]) snprintf(opts.labels, sizeof opts.labels, "%s", geo->labels);
  mdp_image_t img;
  int dims[3];
  if (mdp_image_read_box(geo->image, &opts, NULL, NULL, &img, dims, e)) {
    snprintf(err, errlen, "%s: key 'geometry.image': %s", s->file, e);
    return -1;
  }
  int seen = 0;
  for (int d = 0; d < 3; d++) {
    const int a = geo->axis_map[d];
    if (a < 0 || a > 2 || (seen & (1 << a))) {
      snprintf(err, errlen, "%s: key 'geometry.axis_map': expected a permutation of 0, 1, 2",
               s->file);
      return -1;
    }
    seen |= 1 << a;
    g->n[d] = dims[a];
  }
  const int *n = g->n;
  for (int d = 0; d < 3; d++) {
    const double want = n[d] * geo->rc_per_voxel, got = s->box_hi[d] - s->box_lo[d];
    if (fabs(got - want) > 1e-9 * want) {
      snprintf(err, errlen,
               "%s: key 'box.hi': expected a box of %g x %g x %g rc (the image's %d x %d x %d "
               "voxels times rc_per_voxel %g, after axis_map) (got %g along %c)",
               s->file, n[0] * geo->rc_per_voxel, n[1] * geo->rc_per_voxel,
               n[2] * geo->rc_per_voxel, n[0], n[1], n[2], geo->rc_per_voxel, got, "xyz"[d]);
      return -1;
    }
  }
  for (int d = 0; d < 3; d++) {
    if (g->whole) {
      g->own_lo[d] = g->gen_lo[d] = g->win_lo[d] = 0;
      g->own_n[d] = g->gen_n[d] = g->win_n[d] = n[d];
      continue;
    }
    const int a = centre_edge(sub_lo[d], g->lo[d], g->h, n[d]);
    const int b = centre_edge(sub_hi[d], g->lo[d], g->h, n[d]);
    g->own_lo[d] = a, g->own_n[d] = b - a;
    /* the voxels that overlap the subdomain, and one more each side: a particle on a voxel face
     * may round into the neighbouring subdomain */
    const long ga = (long)floor((sub_lo[d] - g->lo[d]) / g->h) - 1;
    const long gb = (long)ceil((sub_hi[d] - g->lo[d]) / g->h) + 1;
    wrap_range(ga, gb, n[d], g->periodic[d], &g->gen_lo[d], &g->gen_n[d]);
    wrap_range(ga - halo, gb + halo, n[d], g->periodic[d], &g->win_lo[d], &g->win_n[d]);
  }
  return 0;
}

int image_window_read(const scene_t *s, image_walls_t *g, const double sub_lo[3],
                      const double sub_hi[3], int halo, uint8_t **phase, char *err, size_t errlen) {
  const scene_geometry_t *geo = &s->geometry;
  char e[MDP_IMAGE_ERR_LEN] = "";
  mdp_image_read_opts_t opts;
  mdp_image_read_opts_init(&opts);
  if (geo->labels[0]) snprintf(opts.labels, sizeof opts.labels, "%s", geo->labels);
  *phase = NULL;
  mdp_image_t img;
  if (image_window_ranges(s, g, sub_lo, sub_hi, halo, err, errlen)) return -1;
  const int *n = g->n;
  long long total = 1;
  for (int d = 0; d < 3; d++)
    if (__builtin_mul_overflow(total, (long long)g->win_n[d], &total)) total = -1;
  if (total < 0 || (size_t)total > SIZE_MAX / 4) {
    snprintf(err, errlen, "%s: geometry: the window of %d x %d x %d voxels overflows", s->file,
             g->win_n[0], g->win_n[1], g->win_n[2]);
    return -1;
  }
  uint8_t *ph = malloc(total ? (size_t)total : 1);
  if (!ph) {
    snprintf(err, errlen, "%s: geometry: out of memory for a window of %lld voxels", s->file,
             total);
    return -1;
  }
  image_walls_mem(g, total);
  if (geo->n_species_labels > 0) { /* geometry.fluid_species_labels: which entry each voxel is */
    g->label_sp = calloc(total ? (size_t)total : 1, 1);
    if (!g->label_sp) {
      free(ph);
      snprintf(err, errlen, "%s: geometry: out of memory for a window of %lld voxels", s->file,
               total);
      return -1;
    }
    image_walls_mem(g, total);
  }
  uint8_t entry_of[256] = {0}; /* label -> fluid_species_labels entry + 1 */
  for (int k = 0; k < geo->n_species_labels; k++)
    entry_of[geo->species_label[k]] = (uint8_t)(k + 1);
  /* up to two pieces per axis (a window across a periodic face), so up to 8 boxes */
  int pn[3], plo[3][2], plen[3][2], poff[3][2];
  for (int d = 0; d < 3; d++) {
    const int st = g->win_lo[d], len = g->win_n[d];
    plo[d][0] = st, poff[d][0] = 0;
    if (st + len <= n[d]) {
      pn[d] = 1, plen[d][0] = len;
    } else {
      pn[d] = 2, plen[d][0] = n[d] - st;
      plo[d][1] = 0, plen[d][1] = st + len - n[d], poff[d][1] = n[d] - st;
    }
  }
  g->voxels_read = 0;
  for (int p2 = 0; p2 < pn[2]; p2++)
    for (int p1 = 0; p1 < pn[1]; p1++)
      for (int p0 = 0; p0 < pn[0]; p0++) {
        const int pi[3] = {p0, p1, p2};
        int flo[3], fsz[3]; /* in the file's axes */
        for (int d = 0; d < 3; d++) {
          flo[geo->axis_map[d]] = plo[d][pi[d]];
          fsz[geo->axis_map[d]] = plen[d][pi[d]];
        }
        if (mdp_image_read_box(geo->image, &opts, flo, fsz, &img, NULL, e)) {
          snprintf(err, errlen, "%s: key 'geometry.image': %s", s->file, e);
          free(ph);
          image_walls_mem(g, -total);
          return -1;
        }
        for (int k = 0; k < geo->n_species_labels; k++)
          if (img.phase_of[geo->species_label[k]] != MDP_PHASE_PORE) {
            char map[512];
            mdp_image_format_labels(img.phase_of, map, sizeof map);
            snprintf(err, errlen,
                     "%s: key 'geometry.fluid_species_labels.%d': expected a label that is pore "
                     "in the label map of %s (%s) (got %d: %s)",
                     s->file, geo->species_label[k], geo->image, map, geo->species_label[k],
                     img.phase_of[geo->species_label[k]] == MDP_PHASE_UNSET
                         ? "not in the map"
                         : mdp_phase_name(img.phase_of[geo->species_label[k]]));
            mdp_image_free(&img);
            free(ph);
            return -1;
          }
        g->voxels_read += (long long)fsz[0] * fsz[1] * fsz[2];
        image_walls_mem(g, (long long)fsz[0] * fsz[1] * fsz[2]);
        for (int k = 0; k < fsz[2]; k++)
          for (int j = 0; j < fsz[1]; j++)
            for (int i = 0; i < fsz[0]; i++) {
              const int f[3] = {i, j, k};
              long long w = 0, stride = 1;
              for (int d = 0; d < 3; d++) {
                w += stride * (poff[d][pi[d]] + f[geo->axis_map[d]]);
                stride *= g->win_n[d];
              }
              ph[w] = (uint8_t)mdp_image_phase(&img, mdp_image_index(&img, i, j, k));
              if (g->label_sp) g->label_sp[w] = entry_of[img.label[mdp_image_index(&img, i, j, k)]];
            }
        mdp_image_free(&img);
        image_walls_mem(g, -(long long)fsz[0] * fsz[1] * fsz[2]);
      }
  *phase = ph;
  return 0;
}
