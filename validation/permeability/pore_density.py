#!/usr/bin/env python3
"""The fluid's number density in the pores of an image, as a function of the distance to the solid
(which density, hence which viscosity, the pore fluid has).

For each IMAGE: the campaign's own scene (`mdpore permeability IMAGE --emit-scenes`, its template:
the same walls, fill and wall density a campaign uses) run without a body force for --steps steps on
--np ranks with HDF5 snapshots; then the fluid particles of the snapshots after the first half are
binned by the distance of their voxel's centre to the nearest solid voxel centre (Euclidean,
periodic, computed over a window of --max-distance rc) and the density of each distance shell is
printed: n(d) = particles / (voxels of the shell x voxel volume x snapshots). The "core" density is
the mean over pore voxels farther than --core rc from the solid.

    /usr/bin/python3 validation/permeability/pore_density.py WORK IMAGE [IMAGE ...] [--steps 3000]

Results: WORK/pore_density.{md,csv}. Run with /usr/bin/python3 (numpy, h5py, yaml).
"""
import argparse
import csv
import glob
import os
import subprocess
import sys

import h5py
import numpy as np
import yaml

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MDPORE = os.environ.get("MDPORE") or os.path.join(ROOT, "build", "bin", "mdpore")
MPIEXEC = os.environ.get("MPIEXEC", "mpiexec")


def sh(*args, cwd=None):
    p = subprocess.run(list(args), cwd=cwd, capture_output=True, text=True)
    if p.returncode:
        sys.exit(f"pore_density: {' '.join(args)}: exit {p.returncode}\n{p.stderr[-2000:]}")
    return p.stdout


def solid_distance(solid, edge, max_rc):
    """Distance (rc) of every voxel centre to the nearest solid voxel centre, periodic; pore voxels
    farther than max_rc get max_rc. Brute force over the offsets of a window (no scipy here)."""
    w = int(np.ceil(max_rc / edge))
    dist = np.where(solid, 0.0, max_rc)
    for dx in range(-w, w + 1):
        for dy in range(-w, w + 1):
            for dz in range(-w, w + 1):
                r = edge * np.sqrt(dx * dx + dy * dy + dz * dz)
                if r == 0 or r >= max_rc:
                    continue
                shifted = np.roll(solid, (dx, dy, dz), axis=(0, 1, 2))
                dist = np.where(shifted & (dist > r), r, dist)
    return dist


def measure(work, image, a):
    name = os.path.splitext(os.path.basename(os.path.dirname(os.path.abspath(image))) + "_" +
                            os.path.basename(image))[0]
    d = os.path.join(work, name)
    em = os.path.join(d, "emit")
    if not os.path.exists(os.path.join(em, "template.yaml")):
        sh(MDPORE, "permeability", image, "--axis", a.axis, "--emit-scenes", em, "--gradients", "0.001,0.002",
           "--rc-per-voxel", str(a.rc_per_voxel), "--wall-density", str(a.wall_density))
    scene = yaml.safe_load(open(os.path.join(em, "template.yaml")))
    scene["effects"]["body_force"] = {k: [0.0, 0.0, 0.0] for k in scene["effects"]["body_force"]}
    scene["run"] = {"dt": 0.01, "steps": a.steps, "seed": a.seed}
    scene["output"] = {"snapshot": {"every": max(1, a.steps // 10), "file": "snap"}, "summary": "summary.json",
                       "progress": False}
    rd = os.path.join(d, "run")
    os.makedirs(rd, exist_ok=True)
    text = yaml.safe_dump(scene, sort_keys=False)
    done = os.path.join(rd, "summary.json")
    if not (os.path.exists(done) and open(os.path.join(rd, "scene.yaml")).read() == text):
        for f in glob.glob(os.path.join(rd, "snap_*.h5")):
            os.remove(f)
        open(os.path.join(rd, "scene.yaml"), "w").write(text)
        launch = [MPIEXEC, "-n", str(a.np)] if a.np > 1 else []
        sh(*launch, MDPORE, "run", "scene.yaml", cwd=rd)
    geo = scene["geometry"]
    edge = float(geo["rc_per_voxel"])
    with h5py.File(geo["image"], "r") as f:
        labels = np.asarray(f["labels"])
    # HDF5 images are stored z, y, x (docs/images.md); the box is x, y, z
    solid = np.transpose(labels != 0, (2, 1, 0)).copy()
    dist = solid_distance(solid, edge, a.max_distance)
    counts = np.zeros(solid.shape)
    K = 0
    for path in sorted(glob.glob(os.path.join(rd, "snap_*.h5"))):
        with h5py.File(path, "r") as f:
            if int(f.attrs["step"]) < a.steps // 2:
                continue
            part = f["particles"]
            pos = part["position"][:][part["species"][:] == 0]  # species 0: the fluid (the template's first)
            lo = np.asarray(f.attrs["box_lo"])
        idx = np.floor((pos - lo) / edge).astype(int) % np.array(solid.shape)
        np.add.at(counts, (idx[:, 0], idx[:, 1], idx[:, 2]), 1.0)
        K += 1
    if K == 0:
        sys.exit(f"pore_density: {rd}: no snapshot after step {a.steps // 2}")
    vol = edge ** 3
    pore = ~solid
    shells = np.arange(0.0, a.max_distance + 1e-9, 0.5)
    rows = []
    for s0 in shells:
        m = pore & (dist >= s0) & (dist < s0 + 0.5) if s0 < a.max_distance else pore & (dist >= s0)
        if m.sum():
            rows.append(dict(image=name, d_lo=s0, d_hi=s0 + 0.5 if s0 < a.max_distance else float("inf"),
                             voxels=int(m.sum()), n=counts[m].sum() / (m.sum() * vol * K)))
    core = pore & (dist >= a.core)
    n_core = counts[core].sum() / (core.sum() * vol * K) if core.sum() else float("nan")
    n_pore = counts[pore].sum() / (pore.sum() * vol * K)
    in_solid = counts[solid].sum() / K
    return name, rows, dict(image=name, pore_voxels=int(pore.sum()), core_voxels=int(core.sum()),
                            core_fraction=core.sum() / pore.sum(), n_pore=n_pore, n_core=n_core,
                            fluid_in_solid=in_solid, snapshots=K)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("work")
    ap.add_argument("images", nargs="+")
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--axis", default="x", help="the campaign axis of the template (the image must percolate along it)")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--seed", type=int, default=4242)
    ap.add_argument("--rc-per-voxel", type=float, default=0.5)
    ap.add_argument("--wall-density", type=float, default=4.0)
    ap.add_argument("--max-distance", type=float, default=3.0, help="rc; shells beyond are merged")
    ap.add_argument("--core", type=float, default=1.5, help="rc from the solid: the core's inner edge")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    shells, summary = [], []
    for image in a.images:
        name, rows, s = measure(a.work, image, a)
        shells += rows
        summary.append(s)
        print(f"{name}: pore density {s['n_pore']:.4f}, core (>= {a.core:g} rc from the solid, "
              f"{100 * s['core_fraction']:.0f}% of the pore) {s['n_core']:.4f}; fluid in solid voxels "
              f"{s['fluid_in_solid']:.1f} per snapshot", flush=True)
        for r in rows:
            print(f"    d {r['d_lo']:.1f}-{r['d_hi']:.1f} rc: n = {r['n']:.4f} ({r['voxels']} voxels)")
    with open(os.path.join(a.work, "pore_density.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(shells[0]))
        w.writeheader()
        w.writerows(shells)
    lines = ["# Fluid density in the pores against the distance to the solid", "",
             f"`pore_density.py` ({a.steps} steps without flow, {a.np} ranks, snapshots of the second half; "
             f"wall density {a.wall_density:g}, {a.rc_per_voxel:g} rc per voxel, the campaign's template).", "",
             "| image | pore density | core density (>= %g rc) | core share of the pore | fluid in solid voxels |" % a.core,
             "|---|---|---|---|---|"]
    for s in summary:
        lines.append(f"| {s['image']} | {s['n_pore']:.4f} | {s['n_core']:.4f} | {s['core_fraction']:.2f} | "
                     f"{s['fluid_in_solid']:.1f} |")
    open(os.path.join(a.work, "pore_density.md"), "w").write("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
