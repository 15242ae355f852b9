#!/usr/bin/env python3
"""What the walls of a campaign's template adsorb: Gamma, the fluid particles per rc^2 of pore-solid
voxel face beyond the pore core's density, the constant of the campaign's fill (docs/permeability.md,
"Fill"; campaign/campaign.h CAMP_DEFAULT_WALL_ADSORPTION).

A slit image (`mdpore image make slit --width W --wall 4`, flat walls normal to y) at each
--rc-per-voxel: the campaign's own template (`mdpore permeability --emit-scenes --wall-adsorption 0`:
the same liquid and walls, filled uniformly at n = 6.2) run without a body force for --steps steps.
With N = n V fluid particles in the pore volume V, a core density n_core (pore voxels >= 1.5 rc from
the solid, the run's own census) and the wall area S (voxel faces between pore and solid, both
walls):

    Gamma = (N - n_core V) / S,   error = err(n_core) V / S

    /usr/bin/python3 validation/permeability/wall_adsorption.py WORK [--rc-per-voxel 1 0.5]
        [--width 16] [--steps 3000] [--wall-density 4]

Prints one line per voxel edge and the weighted mean; WORK/wall_adsorption.md. Measured (width 16
voxels, 3000 steps): 0.236 +- 0.028 at 1 rc per voxel, 0.239 +- 0.049 at 0.5, weighted 0.237 +- 0.024
(other seeds and a 10000-step run: 0.22-0.28; docs/permeability.md, "Fill").
"""
import argparse
import json
import os
import re
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MDPORE = os.environ.get("MDPORE") or os.path.join(ROOT, "build", "bin", "mdpore")


def sh(*args, cwd=None):
    p = subprocess.run([MDPORE, *args], cwd=cwd, capture_output=True, text=True)
    if p.returncode:
        sys.exit(f"wall_adsorption: mdpore {' '.join(args)}: exit {p.returncode}\n{p.stderr[-2000:]}")
    return p.stdout + p.stderr


def measure(a, edge):
    d = os.path.join(a.work, f"rc{edge:g}")
    os.makedirs(d, exist_ok=True)
    img = os.path.join(d, "slit.raw")
    made = json.loads(sh("image", "make", "slit", "--width", str(a.width), "--wall", "4", "--length", "12",
                         "--depth", "12", "-o", img))
    nx, ny, nz = made["dims"]
    em = os.path.join(d, "emitted")
    if not os.path.exists(os.path.join(em, "campaign.txt")):
        sh("permeability", img, "--axis", "x", "--boundary", "periodic", "--rc-per-voxel", f"{edge:g}", "--force",
           "--wall-adsorption", "0", "--wall-density", f"{a.wall_density:g}", "--gradients", "0.001,0.002",
           "--emit-scenes", em)
    run = sorted(os.listdir(os.path.join(em, "runs")))[0]
    text = open(os.path.join(em, "runs", run, "scene.yaml")).read()
    text = re.sub(r"body_force: \{[^}]*\}, ", "", text)  # at rest
    text = re.sub(r"steps: \d+", f"steps: {a.steps}", text)
    text = re.sub(r", target_error: [0-9.eE+-]+", "", text)
    rest = os.path.join(d, "rest")
    os.makedirs(rest, exist_ok=True)
    open(os.path.join(rest, "scene.yaml"), "w").write(text)
    if not os.path.exists(os.path.join(rest, "summary.json")):
        sh("run", "scene.yaml", cwd=rest)
    j = json.load(open(os.path.join(rest, "summary.json")))
    core, core_err = j["pore_core_density"]["mean"], j["pore_core_density"]["err"]
    fill = float(re.search(r"fluid_density: ([0-9.eE+-]+)", text).group(1))
    pore_voxels = nx * a.width * nz  # the slit's pore layers (normal to y)
    volume = pore_voxels * edge ** 3
    area = 2 * nx * nz * edge ** 2  # both walls
    n_fluid = round(fill * volume)
    gamma = (n_fluid - core * volume) / area
    err = core_err * volume / area
    return {"rc_per_voxel": edge, "fill": fill, "core": core, "core_err": core_err, "gamma": gamma, "err": err}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("work")
    ap.add_argument("--rc-per-voxel", type=float, nargs="+", default=[1.0, 0.5])
    ap.add_argument("--width", type=int, default=16, help="slit width in voxels")
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--wall-density", type=float, default=4.0)
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    rows = [measure(a, e) for e in a.rc_per_voxel]
    lines = ["| rc per voxel | fill | core density | Gamma (per rc^2) |", "|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['rc_per_voxel']:g} | {r['fill']:g} | {r['core']:.4f} +- {r['core_err']:.4f} | "
                     f"{r['gamma']:.3f} +- {r['err']:.3f} |")
    w = [1 / r["err"] ** 2 for r in rows if r["err"] > 0]
    if len(w) == len(rows):
        mean = sum(r["gamma"] * wi for r, wi in zip(rows, w)) / sum(w)
        lines.append(f"\nweighted mean Gamma = {mean:.3f} +- {sum(w) ** -0.5:.3f} per rc^2 "
                     f"(wall density {a.wall_density:g}, slit {a.width} voxels wide, {a.steps} steps at rest)")
    out = "\n".join(lines) + "\n"
    open(os.path.join(a.work, "wall_adsorption.md"), "w").write(out)
    print(out)


if __name__ == "__main__":
    main()
