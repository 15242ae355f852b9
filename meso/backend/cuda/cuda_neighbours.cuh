/* Neighbour traversal of the device pair passes: the bins around a particle's bin, with periodic
 * wrap. Positions are packed relative to their own bin's lower corner (dev_pos), so the separation
 * to a particle of the bin at offset o along an axis is r_i - r_j = (x_i - x_j) - o w: a bin
 * reached across a periodic face gives exactly the image the CPU path's ghost copy gives. Along an
 * axis with only 2 bins both bins are visited once and the nearest image is taken. The visit order
 * (bins z, y, x, then slots in bin order) is fixed, so every sum is deterministic. */
#ifndef MESO_BACKEND_CUDA_NEIGHBOURS_CUH
#define MESO_BACKEND_CUDA_NEIGHBOURS_CUH

#include "cuda_state.cuh"

/* Neighbour bin along axis d at offset o from bin b; -1 outside a non-periodic box. */
__device__ __forceinline__ int dev_nbr_bin(const struct dev_params &q, int d, int b, int o) {
  int c = b + o;
  if (c < 0 || c >= q.nb[d]) {
    if (!q.periodic[d]) return -1;
    c += c < 0 ? q.nb[d] : -q.nb[d];
  }
  return c;
}

__device__ __forceinline__ meso_real dev_nearest(const struct dev_params &q, int d, meso_real x) {
  return q.min_image[d] ? x - q.box_L[d] * rint(x * q.inv_box_L[d]) : x;
}

/* Separation of a partner at bin offset code (ox + 1) + 3 (oy + 1) + 9 (oz + 1): the same float
 * operations as the traversal below, so a list entry replays the traversal's value exactly. */
__device__ __forceinline__ void dev_offset_sep(const struct dev_params &q, const struct dev_pos &pi,
                                               const struct dev_pos &pj, int code, meso_real *dx,
                                               meso_real *dy, meso_real *dz) {
  const int ox = code % 3 - 1, oy = (code / 3) % 3 - 1, oz = code / 9 - 1;
  *dx = dev_nearest(q, 0, (pi.x - (meso_real)ox * q.bin_w[0]) - pj.x);
  *dy = dev_nearest(q, 1, (pi.y - (meso_real)oy * q.bin_w[1]) - pj.y);
  *dz = dev_nearest(q, 2, (pi.z - (meso_real)oz * q.bin_w[2]) - pj.z);
}

/* (gstart: the ghosts' bin starts, relative to slot goff, with several ranks; else NULL.)
 * Call f(t, code, pj, dx, dy, dz) for every slot t of the bins around particle i (slot i, packed
 * position pi, bin key ci), i itself included (callers skip it); d = r_i - r_j of the nearest
 * image. */
template <class F>
__device__ __forceinline__ void
dev_for_each_neighbour(const struct dev_params &q, const int *__restrict__ start,
                       const int *__restrict__ gstart, int goff,
                       const struct dev_pos *__restrict__ pos, const struct dev_pos &pi,
                       uint32_t ci, F &&f) {
  const int bx = (int)ci % q.nb[0], by = ((int)ci / q.nb[0]) % q.nb[1],
            bz = (int)ci / (q.nb[0] * q.nb[1]);
  for (int oz = q.off_lo[2]; oz <= q.off_hi[2]; oz++) {
    const int cz = dev_nbr_bin(q, 2, bz, oz);
    if (cz < 0) continue;
    const meso_real sz = pi.z - (meso_real)oz * q.bin_w[2];
    for (int oy = q.off_lo[1]; oy <= q.off_hi[1]; oy++) {
      const int cy = dev_nbr_bin(q, 1, by, oy);
      if (cy < 0) continue;
      const meso_real sy = pi.y - (meso_real)oy * q.bin_w[1];
      if (!gstart && q.off_lo[0] == -1 && q.off_hi[0] == 1 && bx >= 1 && bx + 1 < q.nb[0]) {
        /* One rank, an x row that does not wrap: the three bins' slots are consecutive, so one
         * loop visits them in the same order as three (fewer loop heads, less lane imbalance). */
        const int c0 = (bx - 1) + q.nb[0] * (cy + q.nb[1] * cz);
        const int t0 = start[c0], s1 = start[c0 + 1], s2 = start[c0 + 2], t1 = start[c0 + 3];
        const int code_yz = 3 * (oy + 1) + 9 * (oz + 1);
        for (int t = t0; t < t1; t++) {
          const int ox = (t >= s1) + (t >= s2) - 1;
          const meso_real sx = pi.x - (meso_real)ox * q.bin_w[0];
          const struct dev_pos pj = pos[t];
          f(t, (ox + 1) + code_yz, pj, dev_nearest(q, 0, sx - pj.x), dev_nearest(q, 1, sy - pj.y),
            dev_nearest(q, 2, sz - pj.z));
        }
        continue;
      }
      for (int ox = q.off_lo[0]; ox <= q.off_hi[0]; ox++) {
        const int cx = dev_nbr_bin(q, 0, bx, ox);
        if (cx < 0) continue;
        const meso_real sx = pi.x - (meso_real)ox * q.bin_w[0];
        const int c = cx + q.nb[0] * (cy + q.nb[1] * cz);
        const int code = (ox + 1) + 3 * (oy + 1) + 9 * (oz + 1);
        for (int range = 0; range < (gstart ? 2 : 1); range++) {
          /* owned slots of the bin, then (several ranks) its ghosts */
          const int t0 = range ? goff + gstart[c] : start[c];
          const int t1 = range ? goff + gstart[c + 1] : start[c + 1];
          for (int t = t0; t < t1; t++) {
            const struct dev_pos pj = pos[t];
            f(t, code, pj, dev_nearest(q, 0, sx - pj.x), dev_nearest(q, 1, sy - pj.y),
              dev_nearest(q, 2, sz - pj.z));
          }
        }
      }
    }
  }
}

#endif
