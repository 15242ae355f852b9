/* Exact Euclidean distance transform of the pore space: the squared distance from each point of a
 * lattice to the nearest solid voxel centre, by the separable lower-envelope-of-parabolas algorithm
 * of Felzenszwalb & Huttenlocher, "Distance transforms of sampled functions", Theory of Computing 8
 * (2012) 415: one 1D transform per line along x, then y, then z, O(voxels) each. Coordinates are
 * doubled (voxel centres at even positions, corners at odd ones) so that both lattices have
 * integer squared distances. */
#include "image_internal.h"
#include "mdpore_image.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define EDT_BLOCK 32

/* out[q] = min over sites s (f[s] finite) of (x_q - 2 s)^2 + f[s], with x_q = 2 (q - off) + shift
 * (off: the first query is site off of the line; shift 0 for centres, 1 for corners) for q in [0,
 * n_out); HUGE_VAL when there is no site. site (m ints) and edge (m + 1 doubles) hold the lower
 * envelope: the parabolas' sites and the boundaries between them. */
static void envelope_1d(const double *f, int m, int off, int shift, double *out, int n_out,
                        int *site, double *edge) {
  int k = -1;
  for (int s = 0; s < m; s++) {
    if (f[s] == HUGE_VAL) continue;
    const double xs = 2.0 * s;
    double cross = -HUGE_VAL;
    while (k >= 0) {
      const double xk = 2.0 * site[k];
      cross = ((f[s] + xs * xs) - (f[site[k]] + xk * xk)) / (2.0 * (xs - xk));
      if (cross > edge[k]) break;
      k--;
    }
    k++;
    site[k] = s;
    edge[k] = k == 0 ? -HUGE_VAL : cross;
    edge[k + 1] = HUGE_VAL;
  }
  if (k < 0) {
    for (int q = 0; q < n_out; q++) out[q] = HUGE_VAL;
    return;
  }
  k = 0;
  for (int q = 0; q < n_out; q++) {
    const double x = 2.0 * (q + off) + shift;
    while (edge[k + 1] < x) k++;
    const double dx = x - 2.0 * site[k];
    out[q] = dx * dx + f[site[k]];
  }
}

/* The first pass, on the image itself (f is 0 at a solid site, HUGE_VAL at a pore one): the
 * squared distance to the nearest solid site, from the nearest one on each side (two sweeps; no
 * envelope needed). left (m ints) is work space. */
static void nearest_site_1d(const double *f, int m, int off, int shift, double *out, int n_out,
                            int *left) {
  int last = -1;
  for (int s = 0; s < m; s++) {
    if (f[s] == 0) last = s;
    left[s] = last;
  }
  int next = -1;
  for (int q = n_out - 1 + off; q < m; q++) /* the first solid site at or after the last query */
    if (f[q] == 0) {
      next = q;
      break;
    }
  for (int q = n_out - 1; q >= 0; q--) {
    const int s = q + off;
    if (f[s] == 0) next = s;
    /* a corner query (shift 1) lies between sites s and s + 1: s + 1 is its right neighbour */
    const int right = shift && s + 1 < m && f[s + 1] == 0 ? s + 1 : next;
    const double x = 2.0 * s + shift;
    double best = HUGE_VAL;
    if (left[s] >= 0) best = (x - 2.0 * left[s]) * (x - 2.0 * left[s]);
    if (right >= 0 && (2.0 * right - x) * (2.0 * right - x) < best)
      best = (2.0 * right - x) * (2.0 * right - x);
    out[q] = best;
  }
}

int mdp_image_pore_distance(const mdp_image_t *img, int lattice, const int periodic[3],
                            uint32_t *d4, char *err) {
  const int n[3] = {img->nx, img->ny, img->nz};
  const size_t stride[3] = {1, (size_t)n[0], (size_t)n[0] * (size_t)n[1]};
  const size_t total = mdp_image_count(img);
  const double reach = 4.0 * ((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
  if (reach >= (double)MDP_EDT_NO_SOLID) {
    snprintf(err, MDP_IMAGE_ERR_LEN,
             "distance transform: %d x %d x %d voxels: squared distances do not fit 32 bits", n[0],
             n[1], n[2]);
    return 1;
  }
  if (lattice != MDP_EDT_CENTRES && lattice != MDP_EDT_CORNERS) {
    snprintf(err, MDP_IMAGE_ERR_LEN, "distance transform: unknown lattice %d", lattice);
    return 1;
  }
  int nmax = n[0] > n[1] ? n[0] : n[1];
  if (n[2] > nmax) nmax = n[2];
  const size_t len = 3 * (size_t)nmax; /* a periodic line is read three times over */
  /* Lines along y and z are transformed EDT_BLOCK at a time, neighbours in x, so that each read
   * and write touches EDT_BLOCK consecutive values instead of one per cache line. */
  double *f = malloc(EDT_BLOCK * len * sizeof *f), *out = malloc(len * sizeof *out);
  double *edge = malloc((len + 1) * sizeof *edge);
  int *site = malloc(len * sizeof *site);
  if (!f || !out || !edge || !site) {
    free(f), free(out), free(edge), free(site);
    snprintf(err, MDP_IMAGE_ERR_LEN, "distance transform: out of memory for a line of %d", nmax);
    return 1;
  }
  for (size_t v = 0; v < total; v++) d4[v] = mdp_image_is_pore(img, v) ? MDP_EDT_NO_SOLID : 0;
  const int shift = lattice == MDP_EDT_CORNERS;
  for (int a = 0; a < 3; a++) {
    /* lines along a, indexed by (x, the third axis) for a = y, z and by (y, z) for a = x */
    const int b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
    const int block = a == 0 ? 1 : EDT_BLOCK;
    /* Periodic axis: sites of three periods, queries in the middle one (every image of a site
     * within half a period is then seen). */
    const int m = periodic[a] ? 3 * n[a] : n[a], off = periodic[a] ? n[a] : 0;
    for (int kc = 0; kc < n[c]; kc++)
      for (int kb0 = 0; kb0 < n[b]; kb0 += block) {
        const int nb = n[b] - kb0 < block ? n[b] - kb0 : block;
        const size_t base = (size_t)kb0 * stride[b] + (size_t)kc * stride[c];
        for (int s = 0; s < m; s++) {
          const uint32_t *row = d4 + base + (size_t)(s % n[a]) * stride[a];
          for (int l = 0; l < nb; l++)
            f[(size_t)l * m + s] = row[l] == MDP_EDT_NO_SOLID ? HUGE_VAL : (double)row[l];
        }
        for (int l = 0; l < nb; l++) {
          if (a == 0)
            nearest_site_1d(f + (size_t)l * m, m, off, shift, out, n[a], site);
          else
            envelope_1d(f + (size_t)l * m, m, off, shift, out, n[a], site, edge);
          for (int q = 0; q < n[a]; q++) f[(size_t)l * m + q] = out[q];
        }
        for (int q = 0; q < n[a]; q++) {
          uint32_t *row = d4 + base + (size_t)q * stride[a];
          for (int l = 0; l < nb; l++) {
            const double x = f[(size_t)l * m + q];
            row[l] = x >= (double)MDP_EDT_NO_SOLID ? MDP_EDT_NO_SOLID : (uint32_t)x;
          }
        }
      }
  }
  free(f), free(out), free(edge), free(site);
  return 0;
}
