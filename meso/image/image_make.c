/* Synthetic images for tests and demos: slit, square cylinder arrays, simple-cubic sphere arrays,
 * random overlapping spheres, sphere packs from a centres file. Label 0 = pore, 1 = inorganic
 * solid. For the periodic arrays the solid voxels are the ones nearest the cell centre, as many as
 * make the voxel solid fraction equal to the requested c (to the nearest symmetric group of
 * voxels): the voxel solid fraction, not a nominal radius, is what the flow sees. Elsewhere a voxel
 * is solid when its centre is inside a body. */
#include "mdpore_image.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void set_solid_map(mdp_image_t *img) {
  char err[MDP_IMAGE_ERR_LEN];
  mdp_image_parse_labels("pore=0,inorganic=1", img->phase_of, err);
}

int mdp_make_slit(mdp_image_t *img, int n_pore, int wall, int length, int depth, char *err) {
  if (n_pore < 1 || wall < 0 || length < 1 || depth < 1) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "slit: width %d, wall %d, length %d, depth %d: need width >= 1, wall >= 0, length and "
             "depth >= 1",
             n_pore, wall, length, depth);
    return 1;
  }
  if (mdp_image_alloc(img, length, n_pore + 2 * wall, depth, err)) return 1;
  set_solid_map(img);
  for (int k = 0; k < img->nz; k++)
    for (int j = 0; j < img->ny; j++)
      for (int i = 0; i < img->nx; i++)
        img->label[mdp_image_index(img, i, j, k)] = (j < wall || j >= wall + n_pore) ? 1 : 0;
  return 0;
}

/* One mirror orbit of voxels around a cell centre: the voxels (+-x, +-y, +-z) share distance d2. */
typedef struct {
  double d2;
  int rep[3]; /* representative offsets from the centre in half-voxels, all >= 0 */
} orbit_t;

static int by_distance(const void *a, const void *b) {
  const orbit_t *x = a, *y = b;
  if (x->d2 != y->d2) return (x->d2 > y->d2) - (x->d2 < y->d2);
  for (int d = 0; d < 3; d++)
    if (x->rep[d] != y->rep[d]) return x->rep[d] - y->rep[d];
  return 0;
}

/* Solid mask of one cell (dim 2: L x L, dim 3: L^3) holding a body of as close to `target` voxels
 * as possible around the cell centre. Voxels are taken nearest first in whole mirror orbits (all
 * sign flips of the offset from the centre), so the cell keeps its three mirror planes and symmetry
 * boundary conditions at the cell faces stay exact; the outermost shell of equidistant voxels may
 * be taken in part (then the 90-degree rotations are broken by a few voxels). */
static unsigned char *centred_body(int L, int dim, double target, size_t *count, char *err) {
  const int nz = dim == 3 ? L : 1;
  size_t ncell = (size_t)L * L * nz, norb = 0;
  unsigned char *mask = calloc(ncell, 1);
  orbit_t *orb = malloc(sizeof *orb * ncell);
  if (!mask || !orb) {
    free(mask), free(orb);
    snprintf(err, MDP_IMAGE_ERR_LEN, "out of memory for a %d-voxel cell", L);
    return NULL;
  }
  for (int k = 0; k < nz; k++) /* offset of voxel i from the centre, in half-voxels: 2i + 1 - L */
    for (int j = 0; j < L; j++)
      for (int i = 0; i < L; i++) {
        int o[3] = {2 * i + 1 - L, 2 * j + 1 - L, dim == 3 ? 2 * k + 1 - L : 0};
        if (o[0] < 0 || o[1] < 0 || o[2] < 0) continue;
        orb[norb].d2 = 0.25 * ((double)o[0] * o[0] + (double)o[1] * o[1] + (double)o[2] * o[2]);
        memcpy(orb[norb].rep, o, sizeof o);
        norb++;
      }
  qsort(orb, norb, sizeof *orb, by_distance);
  size_t n = 0;
  for (size_t b = 0; b < norb && (double)n < target; b++) {
    size_t size =
        (size_t)((orb[b].rep[0] ? 2 : 1) * (orb[b].rep[1] ? 2 : 1) * (orb[b].rep[2] ? 2 : 1));
    if (fabs((double)(n + size) - target) >= fabs((double)n - target)) continue; /* overshoots */
    for (int f = 0; f < 8; f++) {
      int o[3];
      for (int d = 0; d < 3; d++) o[d] = (f >> d & 1) ? -orb[b].rep[d] : orb[b].rep[d];
      int i = (o[0] + L - 1) / 2, j = (o[1] + L - 1) / 2, k = dim == 3 ? (o[2] + L - 1) / 2 : 0;
      unsigned char *m = &mask[(size_t)i + (size_t)L * ((size_t)j + (size_t)L * k)];
      n += !*m;
      *m = 1;
    }
  }
  free(orb);
  *count = n;
  return mask;
}

int mdp_make_cylinders(mdp_image_t *img, int L, double c, int cells, int nz, double *achieved,
                       char *err) {
  if (L < 2 || !(c > 0 && c < 0.785) || cells < 1 || nz < 1) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "cylinders: cell %d, solid fraction %g, cells %d, depth %d: need cell >= 2, "
             "0 < c < pi/4 (touching), cells >= 1, depth >= 1",
             L, c, cells, nz);
    return 1;
  }
  size_t count;
  unsigned char *body = centred_body(L, 2, c * L * L, &count, err);
  if (!body) return 1;
  if (achieved) *achieved = (double)count / ((double)L * L);
  if (mdp_image_alloc(img, L * cells, L * cells, nz, err)) {
    free(body);
    return 1;
  }
  set_solid_map(img);
  for (int k = 0; k < nz; k++)
    for (int j = 0; j < img->ny; j++)
      for (int i = 0; i < img->nx; i++)
        img->label[mdp_image_index(img, i, j, k)] = body[i % L + (size_t)L * (j % L)];
  free(body);
  return 0;
}

int mdp_make_spheres(mdp_image_t *img, int L, double c, int cells, double *achieved, char *err) {
  if (L < 2 || !(c > 0 && c < 0.5236) || cells < 1) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "spheres: cell %d, solid fraction %g, cells %d: need cell >= 2, 0 < c < pi/6 "
             "(touching), cells >= 1",
             L, c, cells);
    return 1;
  }
  size_t count, n = (size_t)L * L * L;
  unsigned char *body = centred_body(L, 3, c * (double)n, &count, err);
  if (!body) return 1;
  if (achieved) *achieved = (double)count / (double)n;
  if (mdp_image_alloc(img, L * cells, L * cells, L * cells, err)) {
    free(body);
    return 1;
  }
  set_solid_map(img);
  for (int k = 0; k < img->nz; k++)
    for (int j = 0; j < img->ny; j++)
      for (int i = 0; i < img->nx; i++)
        img->label[mdp_image_index(img, i, j, k)] =
            body[i % L + (size_t)L * (j % L + (size_t)L * (k % L))];
  free(body);
  return 0;
}

/* splitmix64 (Steele, Lea, Flood 2014): small, seedable, reproducible on every platform. */
static uint64_t splitmix64(uint64_t *s) {
  uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
static double uniform01(uint64_t *s) {
  return (double)(splitmix64(s) >> 11) * 0x1.0p-53;
}

/* Mark voxels whose centre lies within r of (cx, cy, cz) (voxel units, per-axis spacing h[]),
 * periodic in all three axes; returns how many pore voxels became solid. */
static long long stamp_sphere(mdp_image_t *img, const double ctr[3], double r, const double h[3]) {
  const int n[3] = {img->nx, img->ny, img->nz};
  int lo[3], hi[3];
  for (int a = 0; a < 3; a++) {
    lo[a] = (int)floor((ctr[a] - r) / h[a] - 0.5);
    hi[a] = (int)ceil((ctr[a] + r) / h[a] - 0.5);
    if (hi[a] - lo[a] >= n[a]) lo[a] = 0, hi[a] = n[a] - 1; /* sphere wider than the box */
  }
  long long added = 0;
  for (int k = lo[2]; k <= hi[2]; k++)
    for (int j = lo[1]; j <= hi[1]; j++)
      for (int i = lo[0]; i <= hi[0]; i++) {
        double x = (i + 0.5) * h[0] - ctr[0], y = (j + 0.5) * h[1] - ctr[1],
               z = (k + 0.5) * h[2] - ctr[2];
        if (x * x + y * y + z * z >= r * r) continue;
        int wi = ((i % n[0]) + n[0]) % n[0], wj = ((j % n[1]) + n[1]) % n[1],
            wk = ((k % n[2]) + n[2]) % n[2];
        uint8_t *v = &img->label[mdp_image_index(img, wi, wj, wk)];
        added += *v == 0;
        *v = 1;
      }
  return added;
}

int mdp_make_random_spheres(mdp_image_t *img, int n, double radius, double porosity, uint64_t seed,
                            char *err) {
  if (n < 2 || !(radius >= 0.5) || !(porosity > 0 && porosity < 1)) {
    snprintf(
        err, MDP_IMAGE_ERR_LEN,
        "random-spheres: size %d, radius %g, porosity %g: need size >= 2, radius >= 0.5 voxel, "
        "0 < porosity < 1",
        n, radius, porosity);
    return 1;
  }
  if (mdp_image_alloc(img, n, n, n, err)) return 1;
  set_solid_map(img);
  long long total = (long long)n * n * n, pore = total;
  const double h[3] = {1, 1, 1};
  uint64_t s = seed;
  /* Boolean model: porosity = exp(-N V / V_box) on average; the loop just stops at the target. */
  for (long long tries = 0; (double)pore / (double)total > porosity; tries++) {
    if (tries > 100 * total) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "random-spheres: target porosity %g not reached", porosity);
      mdp_image_free(img);
      return 1;
    }
    double c[3] = {uniform01(&s) * n, uniform01(&s) * n, uniform01(&s) * n};
    pore -= stamp_sphere(img, c, radius, h);
  }
  return 0;
}

int mdp_make_sphere_file(mdp_image_t *img, const char *centres, const double box[3], double radius,
                         double dx, char *err) {
  if (!(dx > 0) || !(radius > 0) || !(box[0] > 0 && box[1] > 0 && box[2] > 0)) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "sphere-file: need positive box, radius and voxel size");
    return 1;
  }
  FILE *f = fopen(centres, "r");
  if (!f) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: cannot open: %s", centres, strerror(errno));
    return 1;
  }
  int n[3];
  double h[3];
  for (int a = 0; a < 3; a++) {
    n[a] = (int)lround(box[a] / dx);
    if (n[a] < 1) n[a] = 1;
    h[a] = box[a] / n[a]; /* the box must hold a whole number of voxels to stay periodic */
  }
  if (mdp_image_alloc(img, n[0], n[1], n[2], err)) {
    fclose(f);
    return 1;
  }
  set_solid_map(img);
  img->voxel_size = dx;
  char line[1024];
  int lineno = 0, spheres = 0;
  while (fgets(line, sizeof line, f)) {
    lineno++;
    char *s = line;
    while (*s == ' ' || *s == '\t') s++;
    if (*s == '#' || *s == '\n' || *s == '\r' || !*s) continue;
    double c[3];
    if (sscanf(s, "%lf %lf %lf", &c[0], &c[1], &c[2]) != 3) {
      snprintf(err, MDP_IMAGE_ERR_LEN, "%s:%d: expected 'x y z' sphere centre, got '%.60s'",
               centres, lineno, s);
      fclose(f);
      mdp_image_free(img);
      return 1;
    }
    stamp_sphere(img, c, radius, h);
    spheres++;
  }
  fclose(f);
  if (!spheres) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "%s: no sphere centres found", centres);
    mdp_image_free(img);
    return 1;
  }
  return 0;
}
