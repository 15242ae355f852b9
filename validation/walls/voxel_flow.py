#!/usr/bin/env python3
"""The continuum flow rate of a straight channel whose cross-section is a set of voxels: the
reference a tube or duct made as an image should be held to, besides the smooth
Hagen-Poiseuille or series formula.

A body force along a straight prism gives Stokes flow u(y, z) with -mu lap u = G in the pore and
u = 0 on the voxel faces. So Q = (G / mu) Qhat with Qhat the integral of the solution of -lap u = 1.
Each voxel is cut into m x m cells (finite volumes; a wall face holds u = 0 half a cell away), the
system solved by conjugate gradients (numpy, matrix-free), for m = 4, 8, 16, and Qhat extrapolated
with the order the three levels show (a staircase's re-entrant corners make it less than 2). The
viscosity may vary from voxel to voxel (solve_field: layers of two liquids, validation/relperm/tube.py).
The square duct checks it: the series solution is reproduced to 1e-3 (test in __main__ --check).

  voxel_flow.py --check                      the square duct against its series solution
  voxel_flow.py [--rc-per-voxel H] CSV ...   for tube_duct.py result tables made at H rc per voxel:
                                             per row Qhat_vox / Qhat_ana (geometry only) and the run's
                                             Q / Q_vox = (Q / Q_ana) / (Qhat_vox / Qhat_ana)
"""
import argparse
import csv
import math
import os
import sys

import numpy as np


def solve_field(fine, h, mu=None, tol=1e-10, maxit=20000):
    """u on the cells of mask `fine` (cell size h) with -div(mu grad u) = 1, u = 0 on faces to cells
    outside (half a cell away); mu per cell (default 1). A face between two cells takes the harmonic
    mean 2 mu_i mu_j / (mu_i + mu_j) (the flux through two half cells in series: continuity of u and
    of the shear stress mu du/dn at an interface on the face, exact for layers), a wall face 2 mu_i.
    Conjugate gradients with the diagonal as preconditioner (numpy, matrix-free)."""
    f = np.pad(fine, 1)
    inner = f[1:-1, 1:-1]
    m = np.where(inner, 1.0 if mu is None else mu, 0.0)
    mp = np.pad(m, 1)
    faces = []  # (neighbour slice, coefficient) for the four faces of every cell
    for sl in ((slice(2, None), slice(1, -1)), (slice(None, -2), slice(1, -1)),
               (slice(1, -1), slice(2, None)), (slice(1, -1), slice(None, -2))):
        mn = mp[sl]
        k = np.where(mn > 0, 2.0 * m * mn / np.where(mn > 0, m + mn, 1.0), 2.0 * m)
        faces.append((sl, np.where(inner, k, 0.0)))
    diag = np.where(inner, sum(k for _, k in faces), 1.0)

    def apply(u):
        p = np.pad(u, 1)
        out = diag * u
        for sl, k in faces:
            out = out - k * p[sl]
        return np.where(inner, out, 0.0)

    b = np.where(inner, h * h, 0.0)
    u = np.zeros_like(b)
    r = b.copy()
    z = r / diag
    p = z.copy()
    rz = float((r * z).sum())
    b2 = float((b * b).sum())
    for _ in range(maxit):
        Ap = apply(p)
        alpha = rz / float((p * Ap).sum())
        u += alpha * p
        r -= alpha * Ap
        if float((r * r).sum()) <= tol * tol * b2:
            break
        z = r / diag
        rz_new = float((r * z).sum())
        p = z + (rz_new / rz) * p
        rz = rz_new
    return u


def _solve(fine, h):
    """Integral of u over the cells of mask `fine` (cell size h) with -lap u = 1 (solve_field)."""
    return float(solve_field(fine, h).sum()) * h * h


def qhat_voxels(pore, levels=(4, 8, 16)):
    """Qhat (voxel units: voxel edge 1) of the 2D pore mask, extrapolated in the cell size."""
    return extrapolate([_solve(np.kron(pore, np.ones((m, m), bool)), 1.0 / m) for m in levels], levels)


def extrapolate(q, levels):
    """Richardson extrapolation of q at three cell sizes 1/levels (levels in a constant ratio) with the
    order the three show; the correction is returned as its own uncertainty."""
    d1, d2 = q[0] - q[1], q[1] - q[2]
    if d1 * d2 <= 0 or abs(d2) < 1e-15:
        return q[-1], 0.0
    order = math.log(d1 / d2) / math.log(levels[1] / levels[0])
    extra = d2 / ((levels[2] / levels[1]) ** order - 1.0)  # Richardson: q_inf = q_16 - extra
    return q[-1] - extra, abs(extra)  # the correction as its own uncertainty


def q_tube(G, mu, R):
    """Hagen-Poiseuille: Q of a circular tube of radius R under the pressure gradient G."""
    return math.pi * G * R ** 4 / (8 * mu)


def q_duct(G, mu, a, b=None, terms=200):
    """Q of a rectangular duct a x b (b <= a) under the pressure gradient G (physics.md section 4)."""
    b = a if b is None else b
    a, b = max(a, b), min(a, b)
    s = sum(math.tanh(k * math.pi * a / (2 * b)) / k ** 5 for k in range(1, 2 * terms, 2))
    return a * b ** 3 * G / (12 * mu) * (1 - 192 * b / (math.pi ** 5 * a) * s)


def cross_section(kind, size, h):
    """The pore of a tube of radius `size` (voxel centres within it) or of a square duct of side
    `size`, at h rc per voxel, as a 2D mask exactly as wide as the pore (tube_duct.py pads it with
    its solid voxels)."""
    across = 2 * size if kind == "tube" else size
    n = int(round(across / h))
    c = (np.arange(n) + 0.5) * h - n * h / 2  # voxel centres relative to the axis
    Y, Z = np.meshgrid(c, c, indexing="ij")
    return (Y ** 2 + Z ** 2 < size ** 2) if kind == "tube" else (np.maximum(abs(Y), abs(Z)) < size / 2)


def continuum_ratio(kind, size, h):
    """(Qhat on the voxels) / (Qhat of the formula tube_duct.py compares with: q_tube with the
    area-equivalent radius R_A, or q_duct), and its extrapolation uncertainty."""
    pore = cross_section(kind, size, h)
    qv, err = qhat_voxels(pore)
    qv, err = qv * h ** 4, err * h ** 4
    qa = q_tube(1.0, 1.0, math.sqrt(pore.sum() * h * h / math.pi)) if kind == "tube" else q_duct(1.0, 1.0, size)
    return qv / qa, err / qa


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv", nargs="*")
    ap.add_argument("--rc-per-voxel", type=float, default=0.5)
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    if a.check:
        r, e = continuum_ratio("duct", 4.0, 0.5)
        ok = abs(r - 1.0) < 2e-3
        print(f"square duct a = 4 rc at 0.5 rc voxels: Qhat_vox / series = {r:.5f} +- {e:.1e}: "
              f"{'ok' if ok else 'FAIL'} (|ratio - 1| < 2e-3)")
        return 0 if ok else 1
    cache = {}
    print("| file | shape | size (rc) | rc/voxel | Q / Q_ana (run) | Qhat_vox / Qhat_ana | **Q / Q_vox** |")
    print("|---|---|---|---|---|---|---|")
    for path in a.csv:
        for row in csv.DictReader(open(path)):
            kind, size = row["kind"], float(row["size"])
            key = (kind, size, a.rc_per_voxel)
            if key not in cache:
                cache[key] = continuum_ratio(kind, size, a.rc_per_voxel)
            c, ce = cache[key]
            ratio, rerr = float(row["ratio"]), float(row["ratio_err"])
            rv = ratio / c
            rv_err = rv * math.hypot(rerr / ratio, ce / c)
            print(f"| {os.path.basename(path)} | {kind} | {size:g} | {a.rc_per_voxel:g} | {ratio:.3f} +- {rerr:.3f} "
                  f"| {c:.4f} | **{rv:.3f} +- {rv_err:.3f}** |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
