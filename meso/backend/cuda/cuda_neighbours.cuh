/* Neighbour traversal of the device pair passes: the bins around a particle's bin, with periodic
 * wrap. Positions are packed relative to their own bin's lower corner (dev_pos), so the separation
 * to a particle of the bin at offset o along an axis is r_i - r_j = (x_i - x_j) - o w: a bin
 * reached across a periodic face gives exactly the image the CPU path's ghost copy gives. A
 * periodic axis too short for 3 bins has one bin the box long, packed from the box's lower face,
 * and takes the nearest image (dev_nearest). The visit order
 * (bins z, y, x, then slots in bin order) is fixed, so every sum is deterministic. */
#ifndef MESO_BACKEND_CUDA_NEIGHBOURS_CUH
#define MESO_BACKEND_CUDA_NEIGHBOURS_CUH

#include "cuda_state.cuh"

#include <type_traits>

/* Fine bin along one axis: the coarse coordinate s scaled by sub (exact: sub is a power of 2), so the
 * fine bin lies in coarse bin floor(s) (the pack packs relative to that one). */
__device__ __forceinline__ int dev_bin_of(double x, double lo, double inv, int sub, int nf) {
  const double s = (x - lo) * inv * sub;
  if (!(s >= 0.0)) return 0; /* NaN goes to bin 0 (the step check stops the run) */
  const int b = s < (double)nf ? (int)s : nf - 1;
  return b;
}

/* The (fine) bin a particle at (x, y, z) is sorted into: its key. */
__device__ __forceinline__ uint32_t dev_cell_key(const struct dev_params &q, double x, double y,
                                                 double z) {
  const int bx = dev_bin_of(x, q.lo[0], q.inv_bin[0], q.sub[0], q.nf[0]);
  const int by = dev_bin_of(y, q.lo[1], q.inv_bin[1], q.sub[1], q.nf[1]);
  const int bz = dev_bin_of(z, q.lo[2], q.inv_bin[2], q.sub[2], q.nf[2]);
  return (uint32_t)(bx + q.nf[0] * (by + q.nf[1] * bz));
}

/* Neighbour bin along axis d at offset o from bin b; -1 outside a non-periodic box. */
__device__ __forceinline__ int dev_nbr_bin(const struct dev_params &q, int d, int b, int o) {
  int c = b + o;
  if (c < 0 || c >= q.nb[d]) {
    if (!q.periodic[d]) return -1;
    c += c < 0 ? q.nb[d] : -q.nb[d];
  }
  return c;
}

/* The minimum image along axis d (near_L, near_inv_L are 0 along an axis that does not take it:
 * x comes back as it is, with no branch and no per-axis flag to read). */
__device__ __forceinline__ meso_real dev_nearest(const struct dev_params &q, int d, meso_real x) {
  return x - q.near_L[d] * rint(x * q.near_inv_L[d]);
}

/* AX: the axes (bit d for axis d) whose separations go through dev_nearest; the others' are taken
 * as they are (the same value dev_nearest gives along an axis without the minimum image). 0: no
 * axis takes it (q.near_axes = 0); the row scan's slot loop is also compiled for the quasi-2D boxes'
 * one thin axis (2: y, 4: z); 7 serves any set. */
template <int AX>
__device__ __forceinline__ meso_real dev_nearest_ax(const struct dev_params &q, int d,
                                                    meso_real x) {
  return ((AX >> d) & 1) ? dev_nearest(q, d, x) : x;
}

/* The position of particle i as seen from a bin at offset o along an axis of bin width w: every
 * pass computes the separation to a partner of that bin as dev_shifted(p_i, o, w) - p_j, so a list
 * entry replays the traversal's value exactly. */
__device__ __forceinline__ meso_real dev_shifted(meso_real p, int o, meso_real w) {
  return p - (meso_real)o * w;
}

/* 1 / sqrt(x) for a normal float x > 0 (x >= FLT_MIN): the hardware approximation without the
 * denormal guard that rsqrt() wraps around it (3 instructions less; for such x the same bits). */
__device__ __forceinline__ meso_real dev_rsqrt_normal(meso_real x) {
#ifdef MESO_REAL_FLOAT
  float y;
  asm("rsqrt.approx.ftz.f32 %0, %1;" : "=f"(y) : "f"(x));
  return y;
#else
  return rsqrt(x);
#endif
}

/* Separation of a partner at bin offset code (ox + 1) + 3 (oy + 1) + 9 (oz + 1): the same float
 * operations as the traversal below. The code (< 27) is split with multiply-shifts: c / 9 =
 * (57 c) >> 9 and r / 3 = (11 r) >> 5 hold for every c < 27 and r < 9. AX: the axes that take the
 * minimum image (dev_nearest_ax; 7 serves every box, and along an axis without it dev_nearest
 * gives x itself, so a narrower AX gives the same bits with fewer instructions). */
template <int AX = 7>
__device__ __forceinline__ void dev_offset_sep(const struct dev_params &q, const struct dev_pos &pi,
                                               const struct dev_pos &pj, uint32_t code,
                                               meso_real *dx, meso_real *dy, meso_real *dz) {
  const uint32_t oz1 = (code * 57u) >> 9, r = code - 9u * oz1, oy1 = (r * 11u) >> 5;
  const int ox = (int)(r - 3u * oy1) - 1, oy = (int)oy1 - 1, oz = (int)oz1 - 1;
  *dx = dev_nearest_ax<AX>(q, 0, dev_shifted(pi.x, ox, q.bin_w[0]) - pj.x);
  *dy = dev_nearest_ax<AX>(q, 1, dev_shifted(pi.y, oy, q.bin_w[1]) - pj.y);
  *dz = dev_nearest_ax<AX>(q, 2, dev_shifted(pi.z, oz, q.bin_w[2]) - pj.z);
}

/* g(std::integral_constant<int, AX>()) with AX the minimum-image axes of the slot loops
 * (dev_nearest_ax): 0 where no axis takes it (MI 0), the quasi-2D boxes' one thin axis (2: y,
 * 4: z), or every axis (7). */
template <int MI, class G>
__device__ __forceinline__ void dev_with_ax(const struct dev_params &q, G &&g) {
  if (!MI)
    g(std::integral_constant<int, 0>());
  else if (q.near_axes == 2)
    g(std::integral_constant<int, 2>());
  else if (q.near_axes == 4)
    g(std::integral_constant<int, 4>());
  else
    g(std::integral_constant<int, 7>());
}

/* Fine bin index along axis d at fine offset o from a particle in coarse bin b, fine bin r within
 * it (0 <= r < sub); *co gets the coarse offset (floor((r + o) / sub), the offset the separation
 * and the list code use). -1 outside a non-periodic box. */
__device__ __forceinline__ int dev_fine_bin(const struct dev_params &q, int d, int b, int r, int o,
                                            int *co) {
  const int u = r + o; /* fine offset from the coarse bin's first fine bin, >= -sub */
  *co = ((u + 2 * q.sub[d]) >> q.sub_shift[d]) - 2; /* floor(u / sub): u >= -sub */
  const int cb = dev_nbr_bin(q, d, b, *co);
  return cb < 0 ? -1 : (cb << q.sub_shift[d]) + (u - (*co << q.sub_shift[d]));
}

/* The fine offsets along axis d that can hold a partner: +-sub with fine bins (a bin is at least
 * the cutoff wide), else the coarse offsets. */
__device__ __forceinline__ int dev_fine_lo(const struct dev_params &q, int d) {
  return q.sub[d] > 1 ? -q.sub[d] : q.off_lo[d];
}
__device__ __forceinline__ int dev_fine_hi(const struct dev_params &q, int d) {
  return q.sub[d] > 1 ? q.sub[d] : q.off_hi[d];
}

/* Shortest distance along axis d from a position p (relative to its coarse bin's corner) to the
 * fine bin at fine offset u from that corner's first fine bin (0 along a minimum-image axis: no
 * trimming there). */
__device__ __forceinline__ meso_real dev_gap(const struct dev_params &q, int d, meso_real p,
                                             int u) {
  if (q.min_image[d]) return MESO_R(0.0);
  const meso_real lo = (meso_real)u * q.fine_w[d], hi = lo + q.fine_w[d];
  return p < lo ? lo - p : (p > hi ? p - hi : MESO_R(0.0));
}

/* Slot t of a row, coarse x offset -1 before slot s1, 0 in [s1, s2), +1 from s2: the particle's
 * position shifted by that offset is picked (the values dev_shifted gives), the list code computed
 * for partners only. AX: dev_nearest_ax. */
template <int AX, class F>
__device__ __forceinline__ void
dev_visit_slot(const struct dev_params &q, const struct dev_pos *__restrict__ pos, int t, int s1,
               int s2, const meso_real sx3[3], meso_real sy, meso_real sz, int code_yz, F &f) {
  const struct dev_pos pj = pos[t];
  const meso_real sx = t < s1 ? sx3[0] : (t < s2 ? sx3[1] : sx3[2]);
  const meso_real dx = dev_nearest_ax<AX>(q, 0, sx - pj.x);
  const meso_real dy = dev_nearest_ax<AX>(q, 1, sy - pj.y);
  const meso_real dz = dev_nearest_ax<AX>(q, 2, sz - pj.z);
  f(t, (t >= s1) + (t >= s2) + code_yz, pj, dx, dy, dz);
}

/* The slots [t0, t1) of one row (no wrap), coarse edges s1, s2 (dev_visit_slot). */
template <int AX, class F>
__device__ __forceinline__ void dev_scan_slots(const struct dev_params &q,
                                               const struct dev_pos *__restrict__ pos, int t0,
                                               int t1, int s1, int s2, const meso_real sx3[3],
                                               meso_real sy, meso_real sz, int code_yz, F &f) {
  for (int t = t0; t < t1; t++) dev_visit_slot<AX>(q, pos, t, s1, s2, sx3, sy, sz, code_yz, f);
}

/* The same over [t0, t1) and then the static tail's slots [u0, u1) of the row (its coarse edges
 * v1, v2) in one loop, so a warp runs as long as its longest lane's sum of the two ranges, not the
 * sum of each range's longest (two loops cost the density scan 495 -> 638 us on porous 33, one
 * loop 557: bench/RESULTS.md, 2026-11-26 76c87e8). */
template <int AX, class F>
__device__ __forceinline__ void
dev_scan_slots2(const struct dev_params &q, const struct dev_pos *__restrict__ pos, int t0, int t1,
                int s1, int s2, int u0, int u1, int v1, int v2, const meso_real sx3[3],
                meso_real sy, meso_real sz, int code_yz, F &f) {
  int t = t0, a1 = s1, a2 = s2;
  for (int k = (t1 - t0) + (u1 - u0); k > 0; k--, t++) {
    if (t == t1) { /* (once: the tail's slots are all above t1) */
      t = u0;
      a1 = v1;
      a2 = v2;
    }
    dev_visit_slot<AX>(q, pos, t, a1, a2, sx3, sy, sz, code_yz, f);
  }
}

/* The traversal of one rank (or of the interior part of several): the rows of fine bins (z, then
 * y) around the particle's fine bin; each row's fine bins along x are consecutive slots, visited in
 * one loop (the coarse x offset of a slot from the two coarse-bin edges of the row). With trimming
 * (trim2 > 0: the caller's cutoff squared, with 1e-4 of the cutoff added for the float rounding of
 * the packed positions and bin edges: q.scan_cut2 or q.scan_rd2) a row farther than that from the
 * particle is skipped and a row's fine bins along x are cut to those within reach: no candidate
 * within the caller's cutoff is skipped. Visit order: rows z, y, then slots; fixed, so every sum
 * is deterministic. MI = 0: no axis takes the minimum image (q.near_axes = 0), so the separations
 * need no rint. */
template <int MI, class F>
__device__ __forceinline__ void
dev_scan_rows(const struct dev_params &q, const int *__restrict__ start,
              const struct dev_pos *__restrict__ pos, const struct dev_pos &pi, uint32_t ci, F &f,
              meso_real trim2, int ranges) {
  const int hx = (int)ci % q.nf[0], hy = ((int)ci / q.nf[0]) % q.nf[1],
            hz = (int)ci / (q.nf[0] * q.nf[1]);
  const int bx = hx >> q.sub_shift[0], by = hy >> q.sub_shift[1], bz = hz >> q.sub_shift[2];
  const int rx = hx - (bx << q.sub_shift[0]), ry = hy - (by << q.sub_shift[1]),
            rz = hz - (bz << q.sub_shift[2]);
  const int xlo = dev_fine_lo(q, 0), xhi = dev_fine_hi(q, 0);
  /* the row along x is one slot range unless it wraps or leaves the box */
  const int x_inside = hx + xlo >= 0 && hx + xhi < q.nf[0];
  const meso_real sx_lo = dev_shifted(pi.x, -1, q.bin_w[0]),
                  sx_mid = dev_shifted(pi.x, 0, q.bin_w[0]),
                  sx_hi = dev_shifted(pi.x, 1, q.bin_w[0]);
  for (int oz = dev_fine_lo(q, 2); oz <= dev_fine_hi(q, 2); oz++) {
    int coz;
    const int fz = dev_fine_bin(q, 2, bz, rz, oz, &coz);
    if (fz < 0) continue;
    const meso_real sz = dev_shifted(pi.z, coz, q.bin_w[2]);
    const meso_real gz = trim2 > MESO_R(0.0) ? dev_gap(q, 2, pi.z, rz + oz) : MESO_R(0.0);
    for (int oy = dev_fine_lo(q, 1); oy <= dev_fine_hi(q, 1); oy++) {
      int coy;
      const int fy = dev_fine_bin(q, 1, by, ry, oy, &coy);
      if (fy < 0) continue;
      const meso_real sy = dev_shifted(pi.y, coy, q.bin_w[1]);
      const int code_yz = 3 * (coy + 1) + 9 * (coz + 1);
      const int row = q.nf[0] * (fy + q.nf[1] * fz);
      int olo = xlo, ohi = xhi;
      if (trim2 > MESO_R(0.0)) {
        const meso_real gy = dev_gap(q, 1, pi.y, ry + oy);
        const meso_real room2 = trim2 - gy * gy - gz * gz;
        if (!(room2 > MESO_R(0.0))) continue;
        if (!q.min_image[0]) {
          const meso_real e = meso_sqrt(room2);
          olo = max(xlo, (int)floorf((float)((pi.x - e) * q.inv_fine_w[0])) - rx);
          ohi = min(xhi, (int)floorf((float)((pi.x + e) * q.inv_fine_w[0])) - rx);
          if (olo > ohi) continue; /* (a position far outside its bin, or NaN) */
        }
      }
      if (x_inside) {
        /* slots of coarse x offset -1 before s1, 0 in [s1, s2), +1 from s2 (the tail's alone
         * with ranges 2) */
        const int *st0 = q.tail && ranges == 2 ? start + q.tail_off : start;
        const int t0 = st0[row + hx + olo], t1 = st0[row + hx + ohi + 1];
        const int s1 = st0[row + (bx << q.sub_shift[0])],
                  s2 = st0[row + ((bx + 1) << q.sub_shift[0])];
        const meso_real sx3[3] = {sx_lo, sx_mid, sx_hi};
        if (q.tail && ranges == 3) { /* the static tail's slots of the row after the others */
          const int *st = start + q.tail_off;
          const int u0 = st[row + hx + olo], u1 = st[row + hx + ohi + 1];
          const int v1 = st[row + (bx << q.sub_shift[0])],
                    v2 = st[row + ((bx + 1) << q.sub_shift[0])];
          dev_with_ax<MI>(q, [&](auto ax) {
            dev_scan_slots2<decltype(ax)::value>(q, pos, t0, t1, s1, s2, u0, u1, v1, v2, sx3, sy,
                                                 sz, code_yz, f);
          });
          continue;
        }
        dev_with_ax<MI>(q, [&](auto ax) {
          dev_scan_slots<decltype(ax)::value>(q, pos, t0, t1, s1, s2, sx3, sy, sz, code_yz, f);
        });
        continue;
      }
      for (int ox = olo; ox <= ohi; ox++) { /* bin by bin, wrapping (the box's x ends) */
        int cox;
        const int fx = dev_fine_bin(q, 0, bx, rx, ox, &cox);
        if (fx < 0) continue;
        const meso_real sx = dev_shifted(pi.x, cox, q.bin_w[0]);
        const int code = (cox + 1) + code_yz;
        for (int part = 0; part <= q.tail; part++) { /* the static tail's slots second */
          if (q.tail && !((ranges >> part) & 1)) continue;
          const int *st = part ? start + q.tail_off : start;
          for (int t = st[row + fx]; t < st[row + fx + 1]; t++) {
            const struct dev_pos pj = pos[t];
            f(t, code, pj, dev_nearest_ax < MI ? 7 : 0 > (q, 0, sx - pj.x),
              dev_nearest_ax < MI ? 7 : 0 > (q, 1, sy - pj.y),
              dev_nearest_ax < MI ? 7 : 0 > (q, 2, sz - pj.z));
          }
        }
      }
    }
  }
}

/* (gstart: the ghosts' bin starts, relative to slot goff, with several ranks; else NULL. trim2:
 * see dev_scan_rows; 0 visits every bin around the particle. ranges, with the static tail: 1 the
 * slots before the tail only, 2 the tail's only, 3 both.)
 * Call f(t, code, pj, dx, dy, dz) for every slot t of the bins around particle i (slot i, packed
 * position pi, bin key ci), i itself included (callers skip it); d = r_i - r_j of the nearest
 * image. */
template <class F>
__device__ __forceinline__ void
dev_for_each_neighbour(const struct dev_params &q, const int *__restrict__ start,
                       const int *__restrict__ gstart, int goff,
                       const struct dev_pos *__restrict__ pos, const struct dev_pos &pi,
                       uint32_t ci, F &&f, meso_real trim2, int ranges = 3) {
  if (!gstart && q.row_scan) {
    if (!q.trim_any) trim2 = MESO_R(0.0);
    if (q.near_axes)
      dev_scan_rows<1>(q, start, pos, pi, ci, f, trim2, ranges);
    else
      dev_scan_rows<0>(q, start, pos, pi, ci, f, trim2, ranges);
    return;
  }
  /* the nested loops over coarse bins (sub = 1 here: the ghosts of several ranks, or
   * MDPORE_CUDA_SCAN=nested) */
  const int bx = (int)ci % q.nb[0], by = ((int)ci / q.nb[0]) % q.nb[1],
            bz = (int)ci / (q.nb[0] * q.nb[1]);
  for (int oz = q.off_lo[2]; oz <= q.off_hi[2]; oz++) {
    const int cz = dev_nbr_bin(q, 2, bz, oz);
    if (cz < 0) continue;
    const meso_real sz = dev_shifted(pi.z, oz, q.bin_w[2]);
    for (int oy = q.off_lo[1]; oy <= q.off_hi[1]; oy++) {
      const int cy = dev_nbr_bin(q, 1, by, oy);
      if (cy < 0) continue;
      const meso_real sy = dev_shifted(pi.y, oy, q.bin_w[1]);
      if (!gstart && q.off_lo[0] == -1 && q.off_hi[0] == 1 && bx >= 1 && bx + 1 < q.nb[0]) {
        /* One rank, an x row that does not wrap: the three bins' slots are consecutive, so one
         * loop visits them in the same order as three (fewer loop heads, less lane imbalance). */
        const int c0 = (bx - 1) + q.nb[0] * (cy + q.nb[1] * cz);
        const int t0 = start[c0], s1 = start[c0 + 1], s2 = start[c0 + 2], t1 = start[c0 + 3];
        const int code_yz = 3 * (oy + 1) + 9 * (oz + 1);
        for (int t = t0; t < t1; t++) {
          const int ox = (t >= s1) + (t >= s2) - 1;
          const meso_real sx = dev_shifted(pi.x, ox, q.bin_w[0]);
          const struct dev_pos pj = pos[t];
          f(t, (ox + 1) + code_yz, pj, dev_nearest(q, 0, sx - pj.x), dev_nearest(q, 1, sy - pj.y),
            dev_nearest(q, 2, sz - pj.z));
        }
        continue;
      }
      for (int ox = q.off_lo[0]; ox <= q.off_hi[0]; ox++) {
        const int cx = dev_nbr_bin(q, 0, bx, ox);
        if (cx < 0) continue;
        const meso_real sx = dev_shifted(pi.x, ox, q.bin_w[0]);
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
