/* Neighbour traversal of the device pair passes: the bins around a particle's bin, with periodic
 * wrap. A bin reached across a periodic face is visited with its image shift (x_j -/+ L), so a pair
 * sees exactly the separation that the CPU path's ghost image gives; along an axis with only 2 bins
 * both bins are visited once and the nearest image is taken. The visit order (bins z, y, x, then
 * slots in bin order) is fixed, so every sum is deterministic. */
#ifndef MESO_BACKEND_CUDA_NEIGHBOURS_CUH
#define MESO_BACKEND_CUDA_NEIGHBOURS_CUH

#include "cuda_state.cuh"

__device__ __forceinline__ int dev_bin(double x, double lo, double inv, int nb) {
  const double s = (x - lo) * inv;
  if (!(s >= 0.0)) return 0;
  const int b = (int)s;
  return b < nb ? b : nb - 1;
}

/* Neighbour bin along axis d at offset o from bin b: -1 when outside a non-periodic box; shift is
 * the image offset to add to the partner's position. */
__device__ __forceinline__ int dev_nbr_bin(const struct dev_params &q, int d, int b, int o,
                                           double *shift) {
  int c = b + o;
  *shift = 0.0;
  if (c < 0) {
    if (!q.periodic[d]) return -1;
    c += q.nb[d];
    if (!q.min_image[d]) *shift = -q.L[d];
  } else if (c >= q.nb[d]) {
    if (!q.periodic[d]) return -1;
    c -= q.nb[d];
    if (!q.min_image[d]) *shift = q.L[d];
  }
  return c;
}

/* Call f(t, dx, dy, dz) for every slot t of the bins around (xi, yi, zi), the particle itself
 * included (callers skip it); d = r_i - r_j of the nearest image, in double. */
template <class F>
__device__ __forceinline__ void dev_for_each_neighbour(const struct dev_params &q,
                                                       const int *__restrict__ start,
                                                       const double *__restrict__ x,
                                                       const double *__restrict__ y,
                                                       const double *__restrict__ z, double xi,
                                                       double yi, double zi, F &&f) {
  const int bx = dev_bin(xi, q.lo[0], q.inv_bin[0], q.nb[0]);
  const int by = dev_bin(yi, q.lo[1], q.inv_bin[1], q.nb[1]);
  const int bz = dev_bin(zi, q.lo[2], q.inv_bin[2], q.nb[2]);
  for (int oz = q.off_lo[2]; oz <= q.off_hi[2]; oz++) {
    double sz;
    const int cz = dev_nbr_bin(q, 2, bz, oz, &sz);
    if (cz < 0) continue;
    for (int oy = q.off_lo[1]; oy <= q.off_hi[1]; oy++) {
      double sy;
      const int cy = dev_nbr_bin(q, 1, by, oy, &sy);
      if (cy < 0) continue;
      for (int ox = q.off_lo[0]; ox <= q.off_hi[0]; ox++) {
        double sx;
        const int cx = dev_nbr_bin(q, 0, bx, ox, &sx);
        if (cx < 0) continue;
        const int c = cx + q.nb[0] * (cy + q.nb[1] * cz);
        const int t1 = start[c + 1];
        for (int t = start[c]; t < t1; t++) {
          double dx = xi - (x[t] + sx), dy = yi - (y[t] + sy), dz = zi - (z[t] + sz);
          if (q.min_image[0]) dx -= q.L[0] * rint(dx / q.L[0]);
          if (q.min_image[1]) dy -= q.L[1] * rint(dy / q.L[1]);
          if (q.min_image[2]) dz -= q.L[2] * rint(dz / q.L[2]);
          f(t, dx, dy, dz);
        }
      }
    }
  }
}

#endif
