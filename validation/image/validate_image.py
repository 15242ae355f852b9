"""Image module validation on external geometries: porosity and connectivity of the POREMAPS BCC/FCC
packs (built at porosity 0.30) and of the voxelised DRP sphere pack (Andra et al. 2013) at two voxel
sizes against exact bounds from the sphere centres; random overlapping spheres stopping at their
target porosity. Writes results.md and results.csv into validation/results/image (or
--outdir / $MDPORE_VALIDATION_OUT). Exit 1 when a result is off, 77 when the data are missing.

usage: /usr/bin/python3 validate_image.py [--mdpore PATH] [--outdir DIR] [--data DIR]"""
import argparse
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
ap = argparse.ArgumentParser()
ap.add_argument("--mdpore", default=os.environ.get("MDPORE", os.path.join(here, "..", "..", "build", "bin", "mdpore")))
ap.add_argument("--outdir", default=os.environ.get("MDPORE_VALIDATION_OUT", os.path.join(here, "..", "results", "image")))
ap.add_argument("--data", default=os.environ.get("MDPORE_EXTERNAL_DATA", "/work/shared/data/external"))
args = ap.parse_args()
if not os.path.isdir(args.data):
    print("skipped: external data not found")
    sys.exit(77)
os.makedirs(args.outdir, exist_ok=True)
rows, bad = [], 0


def image(*a):
    p = subprocess.run([args.mdpore, "image", *a], capture_output=True, text=True, check=True)
    return json.loads(p.stdout)


def add(case, value, ref, ok, note=""):
    global bad
    bad += not ok
    rows.append((case, value, ref, "pass" if ok else "FAIL", note))


for f in sorted(glob.glob(os.path.join(args.data, "poremaps_benchmarks", "*.raw"))):
    info = image("info", f, "--dims", "100x100x100", "--labels", "pore=0,inorganic=1", "--voxel-size", "10um", "--json")
    name = os.path.basename(f).split("_")[1]
    add(f"POREMAPS {name} porosity", info["porosity"], "0.30 (by construction)", abs(info["porosity"] - 0.3) < 0.005,
        f"connected x {info['connected_porosity']['x']:.6f}, isolated clusters {info['isolated']['clusters']}")

pack = os.path.join(args.data, "drp_spherepack")
centres = [tuple(map(float, l.split()[:3])) for l in open(os.path.join(pack, "final_loc_cn1.dat")) if l.strip()]
box = [float(t.split(":")[1]) for t in open(os.path.join(pack, "Box_DIM.dat")).read().split("Relaxed State:")[1].split()]
R = 3.5
vs, vbox, lens = 4 / 3 * math.pi * R**3, box[0] * box[1] * box[2], 0.0
for a in range(len(centres)):
    for b in range(a + 1, len(centres)):
        d = math.sqrt(sum(((centres[a][x] - centres[b][x]) - box[x] * round((centres[a][x] - centres[b][x]) / box[x])) ** 2
                          for x in range(3)))
        if d < 2 * R:
            lens += math.pi * (4 * R + d) * (2 * R - d) ** 2 / 12
lo = 1 - len(centres) * vs / vbox
hi = lo + lens / vbox
with tempfile.TemporaryDirectory() as tmp:
    for dx in (0.35, 0.175):
        out = os.path.join(tmp, "pack.h5")
        made = image("make", "sphere-file", "--centres", os.path.join(pack, "final_loc_cn1.dat"), "--box-file",
                     os.path.join(pack, "Box_DIM.dat"), "--radius", str(R), "--dx", str(dx), "-o", out)
        phi = made["porosity"]
        add(f"DRP sphere pack porosity, dx = {dx} ({made['dims'][0]}^3)", phi, f"[{lo:.6f}, {hi:.6f}] exact bounds",
            lo - 1e-3 <= phi <= hi + 1e-3, "data README: 0.3447 +- 0.0008 (Monte-Carlo)")
    # Boolean model: spheres are added until the porosity first reaches the target, so it ends at
    # most one sphere volume below it
    n, r, target = 96, 5.0, 0.6
    out = os.path.join(tmp, "rs.h5")
    made = image("make", "random-spheres", "--size", str(n), "--radius", str(r), "--porosity", str(target),
                 "--seed", "7", "-o", out)
    info = image("info", out, "--json")
    one = 4 / 3 * math.pi * r**3 / n**3
    add("random spheres porosity (target 0.6)", info["porosity"], "<= 0.6, within one sphere",
        target - 1.5 * one <= info["porosity"] <= target,
        f"connected x {info['connected_porosity']['x']:.4f}, clusters {info['clusters']}")

with open(os.path.join(args.outdir, "results.md"), "w") as f:
    f.write("| case | value | reference | verdict | note |\n|---|---|---|---|---|\n")
    for r in rows:
        f.write(f"| {r[0]} | {r[1]:.6f} | {r[2]} | {r[3]} | {r[4]} |\n")
with open(os.path.join(args.outdir, "results.csv"), "w") as f:
    f.write("case,value,reference,verdict,note\n")
    for r in rows:
        f.write(f"\"{r[0]}\",{r[1]:.8f},\"{r[2]}\",{r[3]},\"{r[4]}\"\n")
print(open(os.path.join(args.outdir, "results.md")).read())
sys.exit(1 if bad else 0)
