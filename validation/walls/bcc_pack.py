#!/usr/bin/env python3
"""The POREMAPS BCC sphere pack (../shared/data/external/poremaps_benchmarks,
100^3 voxels, porosity 0.30) built by the path a user takes (a scene with `geometry:`, walls from the
patch database, boundary bounce_back), run for many steps at moderate forcing; checks: zero
penetrations at every thermo sample, the particle count kept, the temperature near kT, and the fluid
density away from the walls (pore voxels farther than 1 rc from any solid voxel) within 2% of the
target. Writes a table (markdown) to --out. Exit 1 when a check fails.

usage: bcc_pack.py --mdpore BUILD/bin/mdpore --bcc BCC.raw [--rc-per-voxel 0.6] [--steps 20000]
                   [--force 0.01] [--backend cuda] [--np 1] [--work DIR] [--out FILE]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np


def run(cmd, **kw):
    print("+", " ".join(cmd), flush=True)
    return subprocess.run(cmd, check=True, **kw)


def read_last_dump(path):
    """Positions and types of the last frame of a LAMMPS-style dump."""
    with open(path) as f:
        lines = f.readlines()
    starts = [i for i, l in enumerate(lines) if l.startswith("ITEM: TIMESTEP")]
    i = starts[-1]
    n = int(lines[i + 3])
    cols = lines[i + 8].split()[2:]
    data = np.loadtxt(lines[i + 9:i + 9 + n])
    return {c: data[:, k] for k, c in enumerate(cols)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--mdpore", required=True)
    ap.add_argument("--bcc", required=True)
    ap.add_argument("--rc-per-voxel", type=float, default=0.6)
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--force", type=float, default=0.01)
    ap.add_argument("--backend", default="cuda")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--work", default="bcc-pack-run")
    ap.add_argument("--out", default="bcc_pack.md")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    os.environ.setdefault("MDPORE_CACHE_DIR", os.path.join(os.path.abspath(a.work), "cache"))
    image = os.path.join(a.work, "bcc.h5")
    run([a.mdpore, "image", "convert", a.bcc, "--dims", "100x100x100", "--labels",
         "pore=0,inorganic=1", "-o", image], stdout=subprocess.DEVNULL)
    h = a.rc_per_voxel
    L = 100 * h
    every = max(1, a.steps // 40)
    scene = f"""name: bcc_pack
box: {{lo: [0, 0, 0], hi: [{L}, {L}, {L}], periodic: true}}
species:
  - {{name: liquid}}
  - {{name: wall, frozen: true}}
pairs:
  default: {{A: -40, B: 25, gamma: 4.5, rc: 1.0, rd: 0.75}}
effects:
  mdpd_attraction: {{}}
  mdpd_repulsion: {{}}
  dpd_thermostat: {{}}
  body_force: {{liquid: [{a.force}, 0, 0]}}
  bounce_back: {{}}
geometry:
  image: bcc.h5
  labels: "pore=0,inorganic=1"
  rc_per_voxel: {h}
  flow_axis: x
  species: {{fluid: liquid, inorganic: wall}}
run: {{dt: 0.01, steps: {a.steps}, seed: 11}}
output:
  thermo: {{every: {every}, file: thermo.csv}}
  dump: {{every: {a.steps}, file: last.dump}}
  summary: summary.json
  progress: false
"""
    with open(os.path.join(a.work, "bcc.yaml"), "w") as f:
        f.write(scene)
    t0 = time.time()
    cmd = [a.mdpore, "run", "--backend", a.backend, "--output-dir", "out", "bcc.yaml"]
    if a.np > 1:
        cmd = ["mpiexec", "-n", str(a.np)] + cmd
    log = subprocess.run(cmd, cwd=a.work, capture_output=True, text=True)
    wall = time.time() - t0
    print(log.stdout[-3000:], log.stderr[-3000:], flush=True)
    if log.returncode:
        print("bcc_pack: the run failed", file=sys.stderr)
        return 1
    out = os.path.join(a.work, "out")
    summ = json.load(open(os.path.join(out, "summary.json")))
    th = np.genfromtxt(os.path.join(out, "thermo.csv"), delimiter=",", names=True, skip_header=1)
    n_particles = th["N"]
    pen = th["penetrations"]
    T = th["T"]
    half = T[len(T) // 2:]
    # density away from the walls: pore voxels farther than 1 rc from every solid voxel
    raw = np.fromfile(a.bcc, dtype=np.uint8).reshape(100, 100, 100)  # [z][y][x], x fastest
    solid = raw != 0
    near = solid.copy()
    k = math.ceil(1.0 / h)
    for _ in range(k):  # 26-connected dilation, periodic: chessboard distance <= k voxels
        grown = near.copy()
        for ax in range(3):
            for sh in (-1, 1):
                grown |= np.roll(near, sh, axis=ax)
        grown2 = grown.copy()
        for ax in range(3):
            for sh in (-1, 1):
                grown2 |= np.roll(grown, sh, axis=(ax + 1) % 3)
        near = grown2
    far = ~near
    d = read_last_dump(os.path.join(out, "last.dump"))
    fluid = d["type"] == 1
    ix = np.floor(d["x"][fluid] / h).astype(int) % 100
    iy = np.floor(d["y"][fluid] / h).astype(int) % 100
    iz = np.floor(d["z"][fluid] / h).astype(int) % 100
    in_far = far[iz, iy, ix]
    n_far_vox = int(far.sum())
    rho_far = in_far.sum() / (n_far_vox * h ** 3)
    in_solid = solid[iz, iy, ix].sum()
    mps = summ["timing"]["particle_steps_per_second"] / 1e6
    checks = [
        ("penetrations at every thermo sample", int(pen.max()) == 0, f"max {int(pen.max())} over {len(pen)} samples"),
        ("fluid particles in solid voxels at the end", int(in_solid) == 0, f"{int(in_solid)}"),
        ("particle count kept", n_particles.min() == n_particles.max(), f"{int(n_particles[0])}"),
        ("T (second half) within 3% of 1", abs(half.mean() - 1) < 0.03, f"{half.mean():.4f} (sd {half.std():.4f})"),
        ("fluid density > 1 rc from walls within 2% of 6.2", abs(rho_far / 6.2 - 1) < 0.02,
         f"{rho_far:.4f} in {n_far_vox} voxels ({(rho_far / 6.2 - 1) * 100:+.2f}%)"),
    ]
    ok = all(c[1] for c in checks)
    lines = [f"# BCC pack, walls from the image, bounce_back ({a.steps} steps)", "",
             f"`validation/walls/bcc_pack.py --rc-per-voxel {h} --steps {a.steps} --force {a.force} "
             f"--backend {a.backend} --np {a.np}`; box {L:g}^3 rc, {int(n_particles[0])} particles, "
             f"{mps:.1f} M particle-steps/s, wall time {wall:.0f} s", "",
             "| check | result | pass |", "| --- | --- | --- |"]
    lines += [f"| {c[0]} | {c[2]} | {'yes' if c[1] else 'NO'} |" for c in checks]
    text = "\n".join(lines) + "\n"
    print(text)
    with open(a.out, "w") as f:
        f.write(text)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
