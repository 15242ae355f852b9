#!/usr/bin/env python3
"""The density drift of a long run (docs/stability.md): from a LAMMPS text dump
(`output.dump` with the mDPD density column rho), the frames of the first and of the last 10% of
the run (step 0 left out), and for the fluid (type 1) in each window:
  - the mean local mDPD density <rho_i> (the many-body density each particle feels);
  - the number-density profile along x and along y (BINS bins over the box, particles per volume of
    the bin, solid included: the pore space does not move, so a drift shows as a change here).
Prints the drift of <rho_i> in %, and per axis the largest change of a bin between the two windows
in % of the window mean and in units of its frame-to-frame standard error. numpy only (the GPU
machine has no h5py). Exit 0 (a report, not a test: the caller reads the numbers).

usage: long_run_density.py DUMP STEPS [--bins 16]
"""
import argparse
import sys

import numpy as np


def frames(path):
    """(step, box lo, box hi, columns, rows as a float array) per frame, read in turn."""
    with open(path) as f:
        while True:
            line = f.readline()
            if not line:
                return
            if not line.startswith("ITEM: TIMESTEP"):
                continue
            step = int(f.readline())
            f.readline()  # ITEM: NUMBER OF ATOMS
            n = int(f.readline())
            f.readline()  # ITEM: BOX BOUNDS
            lo, hi = [], []
            for _ in range(3):
                a, b = f.readline().split()[:2]
                lo.append(float(a))
                hi.append(float(b))
            cols = f.readline().split()[2:]
            text = "".join(f.readline() for _ in range(n))
            yield step, np.array(lo), np.array(hi), cols, text, n


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dump")
    ap.add_argument("steps", type=int)
    ap.add_argument("--bins", type=int, default=16)
    a = ap.parse_args()
    first, last = 0.1 * a.steps, 0.9 * a.steps
    win = {"first": [], "last": []}
    for step, lo, hi, cols, text, n in frames(a.dump):
        if step == 0 or first < step < last:
            continue
        data = np.fromstring(text, sep=" ").reshape(n, len(cols))
        fluid = data[data[:, cols.index("type")] == 1]
        rec = {"step": step, "n": len(fluid)}
        if "rho" in cols:
            rec["rho"] = float(fluid[:, cols.index("rho")].mean())
        for ax, name in ((0, "x"), (1, "y")):
            L = hi[ax] - lo[ax]
            h, _ = np.histogram(fluid[:, cols.index(name)], bins=a.bins, range=(lo[ax], hi[ax]))
            vol = L / a.bins * np.prod(np.delete(hi - lo, ax))
            rec["prof_" + name] = h / vol
        win["first" if step <= first else "last"].append(rec)
    if not win["first"] or not win["last"]:
        sys.exit(f"{a.dump}: no frames in the first or last 10% of {a.steps} steps")
    f, l = win["first"], win["last"]
    print(f"density drift (first vs last 10% of {a.steps} steps; {len(f)} and {len(l)} dump frames):")
    print(f"  fluid particles: {f[0]['n']} -> {l[-1]['n']}")
    if "rho" in f[0]:
        rf = np.array([r["rho"] for r in f])
        rl = np.array([r["rho"] for r in l])
        print(f"  mean local mDPD density <rho_i>: {rf.mean():.5f} -> {rl.mean():.5f} "
              f"({100 * (rl.mean() - rf.mean()) / rf.mean():+.3f}%)")
    for name in ("x", "y"):
        pf = np.array([r["prof_" + name] for r in f])
        pl = np.array([r["prof_" + name] for r in l])
        mf, ml = pf.mean(0), pl.mean(0)
        # frame-to-frame standard error of each window's bin mean (frames a long time apart:
        # taken as independent)
        se = np.sqrt(pf.var(0, ddof=1) / len(pf) + pl.var(0, ddof=1) / len(pl)) if min(len(pf), len(pl)) > 1 \
            else np.full_like(mf, np.nan)
        rel = 100 * np.abs(ml - mf) / mf.mean()
        z = np.abs(ml - mf) / np.where(se > 0, se, np.nan)
        print(f"  number-density profile along {name} ({a.bins} bins, mean {mf.mean():.4f}): largest change "
              f"{rel.max():.3f}% of the mean (bin {int(rel.argmax())}), largest |change| / standard error "
              f"{np.nanmax(z) if np.isfinite(z).any() else float('nan'):.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
