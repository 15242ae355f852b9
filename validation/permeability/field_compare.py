#!/usr/bin/env python3
"""Where an image's mDPD flow differs from OpenFOAM's on the same voxels: the
mean flow velocity of both, binned by the distance of the voxel to the solid.

Inputs: an `mdpore run` folder of a body-force run on a geometry image with HDF5 snapshots
(`output.snapshot`), and an `mdpore foam IMAGE --drive periodic --case DIR` case of the same image
with its cell centres written (`postProcess -func writeCellCentres -latestTime` in DIR).
The foam field (voxel units, nu = 1, kinematic gradient --foam-gradient) is scaled to the run's
driving: u_pred = (G / mu) h^2 u_foam / g_foam with h the voxel edge in rc, G = n g from the run's
summary and mu the viscosity given (--mu; campaigns: the water's at the pore core's density).
Per shell of 0.5 rc of distance: the mDPD mean velocity over the fluid particles of its voxels
(snapshots from --start on), the foam mean over the same voxels, their ratio, and the shell's
share of the flow. A ratio that is flat across shells says the bulk flows too slowly (a viscosity);
one that dips near the solid says the walls hold the fluid back (an effective wall offset).

    /usr/bin/python3 validation/permeability/field_compare.py RUN_DIR FOAM_CASE --mu 5.509 [--start 4000]

Run with /usr/bin/python3 (numpy, h5py, yaml).
"""
import argparse
import glob
import json
import os
import re
import sys

import h5py
import numpy as np
import yaml

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pore_density import solid_distance  # noqa: E402


def foam_vectors(path):
    text = open(path).read()
    m = re.search(r"internalField\s+nonuniform\s+List<vector>\s*(\d+)\s*\(", text)
    if not m:
        sys.exit(f"field_compare: {path}: no nonuniform vector internalField")
    n = int(m.group(1))
    body = text[m.end():]
    vals = re.findall(r"\(([^()]+)\)", body[:body.index("\n)")])
    arr = np.array([[float(x) for x in v.split()] for v in vals[:n]])
    if arr.shape != (n, 3):
        sys.exit(f"field_compare: {path}: expected {n} vectors, read {arr.shape}")
    return arr


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run")
    ap.add_argument("foam")
    ap.add_argument("--mu", type=float, required=True, help="the mDPD viscosity for u_pred")
    ap.add_argument("--start", type=int, default=4000, help="first snapshot step averaged")
    ap.add_argument("--foam-gradient", type=float, default=1e-5)
    ap.add_argument("--max-distance", type=float, default=4.0)
    a = ap.parse_args()

    scene = yaml.safe_load(open(os.path.join(a.run, "scene.yaml")))
    geo = scene["geometry"]
    h = float(geo["rc_per_voxel"])
    with h5py.File(geo["image"], "r") as f:
        solid = np.transpose(np.asarray(f["labels"]) != 0, (2, 1, 0)).copy()
    shape = np.array(solid.shape)
    dist = solid_distance(solid, h, a.max_distance)

    summ = json.load(open(os.path.join(a.run, "summary.json")))
    G = summ["flux"]["G"]
    # mDPD: particle velocity sums and counts per voxel
    vs, cnt, K = np.zeros(solid.shape), np.zeros(solid.shape), 0
    for path in sorted(glob.glob(os.path.join(a.run, "snap_*.h5"))):
        with h5py.File(path, "r") as f:
            if int(f.attrs["step"]) < a.start:
                continue
            p = f["particles"]
            sel = p["species"][:] == 0
            x = p["position"][:][sel]
            v = p["velocity"][:][sel]
            lo = np.asarray(f.attrs["box_lo"])
        idx = np.floor((x - lo) / h).astype(int) % shape
        np.add.at(vs, (idx[:, 0], idx[:, 1], idx[:, 2]), v[:, 0])
        np.add.at(cnt, (idx[:, 0], idx[:, 1], idx[:, 2]), 1.0)
        K += 1
    if K == 0:
        sys.exit(f"field_compare: {a.run}: no snapshot from step {a.start}")
    # foam: cell centres (voxel units) -> voxel, u_x scaled to the run's G / mu
    times = sorted((d for d in os.listdir(a.foam) if re.fullmatch(r"[0-9.]+", d) and d != "0"), key=float)
    last = os.path.join(a.foam, times[-1])
    C = foam_vectors(os.path.join(last, "C"))
    U = foam_vectors(os.path.join(last, "U"))
    vox = np.floor(C).astype(int)
    uf = np.zeros(solid.shape)
    uf[vox[:, 0], vox[:, 1], vox[:, 2]] = U[:, 0] * (G / a.mu) * h * h / a.foam_gradient
    pore = ~solid
    print(f"run {a.run}: {K} snapshots from step {a.start}, G = {G:.5g}, mu = {a.mu}; foam {last}: "
          f"{len(C)} cells")
    q_md = vs[pore].sum() / cnt[pore].sum() * pore.mean()  # mean particle velocity x porosity
    q_f = uf[pore].mean() * pore.mean()
    print(f"superficial velocity: mDPD {q_md:.5g} (mean particle velocity x porosity), foam scaled "
          f"{q_f:.5g}: ratio {q_md / q_f:.4f}")
    print("| distance to the solid (rc) | voxels | fluid per rc^3 | mDPD u | foam u | mDPD / foam | share of foam flow |")
    print("|---|---|---|---|---|---|---|")
    total = uf[pore].sum()
    for s0 in np.arange(0.5, a.max_distance + 1e-9, 0.5):
        m = pore & (dist >= s0) & (dist < s0 + 0.5) if s0 < a.max_distance else pore & (dist >= s0)
        if not m.any():
            continue
        u_m = vs[m].sum() / max(cnt[m].sum(), 1)
        u_f = uf[m].mean()
        dens = cnt[m].sum() / (m.sum() * h ** 3 * K)
        print(f"| {s0:.1f}-{'inf' if s0 >= a.max_distance else f'{s0 + 0.5:.1f}'} | {m.sum()} | {dens:.3f} | "
              f"{u_m:.5g} | {u_f:.5g} | {u_m / u_f:.3f} | {uf[m].sum() / total:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
