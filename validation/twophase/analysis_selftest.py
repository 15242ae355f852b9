#!/usr/bin/python3
"""Self-test of the two-liquid validations' analysis on synthetic data (no simulation; about 1 s).

It checks the measurements docs/twophase.md sections 5 and 7 rest on, each against a case whose answer
is known by construction:
  capillary.throat_profile   uniform liquid filling a slit throat reads the width H as its equimolar
                             width; an empty layer of 0.5 rc at each wall reads H - 1;
  capillary.meniscus_circle  water and oil split by a circle of radius 8 across a throat give R = 8;
  viscosity_ratio.interface_velocity
                             a continuum layered Poiseuille flow (equal densities; the film's
                             velocity equals the water-only profile's) gives ratio 1 and delta 0; the
                             same flow with a non-shearing water layer of 0.3 rc next to the interface
                             gives delta = 0.3 (1 + 0.3 / (2 b)) within 0.07 rc (the
                             0.25 rc bins smear the step over half a bin).
Exit 1 when one fails. ctest: validation_twophase_analysis_selftest.
"""
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import capillary  # noqa: E402
import viscosity_ratio  # noqa: E402


def throat_case(rng, H, gap, n=6.2, ws=4.0, Lc=12.0, Lt=6.0, Lz=3.0, snaps=40):
    """Water particles at density n in the chamber's water part (x < 6, all y) and in the throat
    (x in [Lc, Lc + Lt), y in [ws + gap, ws + H - gap)); no oil."""
    Ly = ws + H
    wat, oil = [], []
    for _ in range(snaps):
        nc = rng.poisson(n * 6.0 * Ly * Lz)
        ch = rng.uniform([0, 0, 0], [6.0, Ly, Lz], (nc, 3))
        nt = rng.poisson(n * Lt * (H - 2 * gap) * Lz)
        th = rng.uniform([Lc, ws + gap, 0], [Lc + Lt, ws + H - gap, Lz], (nt, 3))
        wat.append((np.vstack([ch, th]), None))
        oil.append((np.zeros((0, 3)), None))
    return capillary.throat_profile(list(range(2 * snaps)), wat + wat, oil + oil, H, ws, Lc, Lc / 2, Lc + Lt, Lz)


def meniscus_case(rng, R, H=10.0, ws=4.0, Lc=12.0, Lz=3.0, n=6.2, snaps=10):
    """Oil on the chamber side of a circle of radius R whose apex lies 1.5 rc past the mouth."""
    xc, yc = Lc + 1.5 - R, ws + H / 2
    wat, oil = [], []
    for _ in range(snaps):
        m = rng.poisson(n * 12.0 * H * Lz)
        p = rng.uniform([Lc - 4, ws, 0], [Lc + 8, ws + H, Lz], (m, 3))
        inside = np.hypot(p[:, 0] - xc, p[:, 1] - yc) < R
        wat.append((p[~inside], None))
        oil.append((p[inside], None))
    return capillary.meniscus_circle(list(range(2 * snaps)), wat + wat, oil + oil, H, ws, Lc)


def layered_case(extra, h=12.0, wt=2.0, g=0.05, mu=5.45, n=6.0, b=3.25, dy=0.25):
    """Water-only and layered profiles of a slit (no slip at y = +-h/2 from the middle, the same
    viscosity in both liquids, oil for |y| < b); with `extra` > 0 the water in b <= |y| < b + extra does
    not shear, so everything inside moves at u_single(b + extra) less the core's own shear: delta
    = (u_single(b) - u_single(b + extra)) mu / tau(b) = extra (2 b + extra) / (2 b)."""
    y = np.arange(dy / 2, h + 2 * wt, dy)
    s = y - (wt + h / 2)
    H2 = h / 2
    u1 = np.where(np.abs(s) < H2, n * g * (H2 ** 2 - s ** 2) / (2 * mu), 0.0)
    a = np.abs(s)
    u_at = lambda r: n * g * (H2 ** 2 - r ** 2) / (2 * mu)  # noqa: E731
    u2 = np.where(a < b, u1 - (u_at(b) - u_at(b + extra)), np.where(a < b + extra, u_at(b + extra), u1))
    inside = np.abs(s) < H2
    nw = np.where(inside & (np.abs(s) >= b), n, 0.0)
    no = np.where(inside & (np.abs(s) < b), n, 0.0)
    err = np.full_like(y, 1e-3)
    single = {"y": y.tolist(), "u": u1.tolist(), "u_err": err.tolist()}
    layered = {"y": y.tolist(), "u": u2.tolist(), "u_err": err.tolist(), "n_w": nw.tolist(), "n_o": no.tolist()}
    return viscosity_ratio.interface_velocity(single, layered, h, g, mu, wt)


def main():
    rng = np.random.default_rng(7)
    fails = []
    for H, gap, want in ((6.0, 0.0, 6.0), (10.0, 0.5, 9.0)):
        t = throat_case(rng, H, gap)
        print(f"throat H = {H:g}, empty layer {gap:g} rc: H_eq = {t['H_eq']:.3f} +- {t['H_eq_err']:.3f}, "
              f"half-density width {t['H_half']:.3f} (expected {want:g})")
        if abs(t["H_eq"] - want) > 0.1 or abs(t["H_half"] - want) > 0.15:
            fails.append(f"throat H = {H:g}, gap {gap:g}: H_eq {t['H_eq']:.3f}, half {t['H_half']:.3f}, "
                         f"expected {want:g}")
    m = meniscus_case(rng, 8.0)
    print(f"meniscus R = 8: fitted R = {m['R']:.3f}, apex {m['apex']:.2f} (1.5), rms {m['rms']:.3f}")
    if not (abs(m["R"] - 8.0) < 0.4 and abs(m["apex"] - 1.5) < 0.2):
        fails.append(f"meniscus: R {m['R']:.3f} (8), apex {m['apex']:.2f} (1.5)")
    for extra in (0.0, 0.3):
        f = layered_case(extra)
        print(f"layered flow, non-shearing layer {extra:g} rc: y_i = {f['y_i']:.3f} (3.25), ratio {f['r_i']:.4f}, "
              f"delta {f['delta']:.4f} (expected {extra * (2 * 3.25 + extra) / (2 * 3.25):.4f})")
        want = extra * (2 * 3.25 + extra) / (2 * 3.25)
        # tolerance: the profiles' 0.25 rc bins smear a sharp step over half a bin (0.07 rc of delta here)
        if abs(f["delta"] - want) > 0.07 or abs(f["y_i"] - 3.25) > 0.05 or (extra == 0 and abs(f["r_i"] - 1) > 1e-3):
            fails.append(f"interface_velocity with a {extra:g} rc layer: delta {f['delta']:.4f}, y_i {f['y_i']:.3f}, "
                         f"ratio {f['r_i']:.4f}")
    for f in fails:
        print("FAIL:", f)
    print("analysis self-test:", "all checks pass" if not fails else f"{len(fails)} check(s) failed")
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
