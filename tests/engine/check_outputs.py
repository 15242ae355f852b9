#!/usr/bin/python3
"""Output files of a run are consistent: every XDMF entry points at an existing HDF5 dataset of the
stated shape; snapshots hold ids 1..N sorted, positions inside the box; the dump frame of a step carries
the same particles and positions as the snapshot of that step; the checkpoint holds the same N split
over the ranks; thermo and summary agree on N.
Usage: check_outputs.py DIR"""
import json
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

d = sys.argv[1]
ok = True


def check(cond, what):
    global ok
    print(("ok   " if cond else "FAIL ") + what)
    ok &= bool(cond)


summary = json.load(open(os.path.join(d, "summary.json")))
N = summary["particles"]
box = np.array(summary["box"])
grids = ET.parse(os.path.join(d, "snap.xdmf")).getroot().findall(".//Grid[@GridType='Uniform']")
check(len(grids) >= 2, f"XDMF lists {len(grids)} snapshots")
for g in grids:
    for item in g.iter("DataItem"):
        fname, dset = item.text.strip().split(":")
        dims = tuple(int(v) for v in item.get("Dimensions").split())
        with h5py.File(os.path.join(d, fname), "r") as f:
            check(dset in f and f[dset].shape == dims, f"{fname}:{dset} has shape {dims}")
last = grids[-1]
step = int(last.get("Name").split("_")[1])
with h5py.File(os.path.join(d, f"snap_{step:09d}.h5"), "r") as f:
    ids = f["/particles/id"][:]
    pos = f["/particles/position"][:]
    check(f.attrs["step"] == step, f"snapshot step attribute {f.attrs['step']}")
check(np.array_equal(ids, np.arange(1, N + 1)), f"snapshot ids are 1..{N} in order")
check(np.all(pos >= 0) and np.all(pos <= box), "snapshot positions inside the box")
# The dump frame of the same step.
lines = open(os.path.join(d, "dump.lammpstrj")).read().splitlines()
k = max(i for i, l in enumerate(lines) if l == "ITEM: TIMESTEP" and int(lines[i + 1]) == step)
n = int(lines[k + 3])
cols = lines[k + 8].split()[2:]
data = np.array([l.split() for l in lines[k + 9:k + 9 + n]], dtype=float)
check(cols[:11] == "id type x y z vx vy vz fx fy fz".split(), f"dump columns {' '.join(cols)}")
check(n == N and np.array_equal(data[:, 0], ids), "dump frame has the snapshot's particles")
check(np.allclose(data[:, 2:5], pos, rtol=0, atol=1e-8), "dump positions equal snapshot positions")
with h5py.File(os.path.join(d, "restart.h5"), "r") as f:
    check(f["rank_counts"][:].sum() == N and f["id"].shape == (N,), "checkpoint holds all particles")
    check(sorted(f["id"][:]) == list(range(1, N + 1)), "checkpoint ids are a permutation of 1..N")
rows = [l for l in open(os.path.join(d, "thermo.csv")) if not l.startswith("#")]
check(rows[0].strip().split(",") == "step,time,T,KE,Pxx,Pyy,Pzz,Pxy,Pxz,Pyz,p,N,px,py,pz".split(","), "thermo columns")
check(all(int(r.split(",")[11]) == N for r in rows[1:]), "thermo N constant")
sys.exit(0 if ok else 1)
