"""Per-phase flux (output.flux.phases) in a layered two-liquid slit co-flow (docs/relperm.md, section 6).

An image slit (walls of 2 voxels normal to y, pore width --h voxels at 1 rc per voxel, image walls at
density 4 with bounce_back, as `mdpore permeability` builds them), filled with water; a box region
(geometry.fluid_species_regions) turns the middle of the pore into oil, so water films of thickness
a = Sw h / 2 line both walls. The same body force g along x acts on both liquids. A water-only run
in the same slit is the single-phase reference q_w^(1).

Checks (non-zero exit when one fails):
  1. identity: q = q_water + q_oil in every row of flux.csv and for the summary's means (within
     1e-8 of |q|): by the definitions q = (1/V) sum_s (1/n_s) sum_{i in s} v_x,i over the counted
     species and q_s is the same sum over species s alone; the means are over the same window;
  2. krw = q_water / q_w^(1) and krn = M q_oil / q_w^(1) (M = 1: both liquids have the same
     parameters) within --tol + 2 sigma of the layered formulas krw = Sw^2 (3 - Sw) / 2,
     krn = (1 - Sw)^3 + (3/2) M Sw (2 - Sw) (1 - Sw) (docs/twophase.md section 5) at the run's Sw
     from particle counts (flux.phases.water.saturation). The loose tolerance covers the wetting
     films' resolution deficit (krw 0.79-0.93 of exact at h = 6-12, docs/twophase.md section 5).
Water-oil A = -30 (the weaker contrast that removes the interfacial slip of A_wo = -20, section 5).

    /usr/bin/python3 validation/relperm/phase_flux.py [--quick]
"""
import argparse
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "engine"))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "walls"))
import mdval  # noqa: E402
from common import write_raw_image  # noqa: E402


def kr_layered(sw, M=1.0):
    return sw ** 2 * (3 - sw) / 2, (1 - sw) ** 3 + 1.5 * M * sw * (2 - sw) * (1 - sw)


def scene(name, image, box, h, wall, *, sw, g, steps, a_wo, seed):
    fill = 6.2 + 2 * 0.26 / h  # the campaign's fill: the core at 6.2 plus what the walls adsorb
    geo = {"image": image, "rc_per_voxel": 1.0, "flow_axis": "x", "fluid_density": round(fill, 6),
           "wall_density": 4, "species": {"fluid": "water", "inorganic": "quartz"}}
    phases = ["water"]
    if sw < 1:
        a = sw * h / 2
        geo["fluid_species_regions"] = [{"species": "oil", "lo": [0.0, wall + a, 0.0],
                                         "hi": [box[0], wall + h - a, box[2]]}]
        phases = ["water", "oil"]
    return {
        "name": name,
        "box": {"lo": [0.0, 0.0, 0.0], "hi": [float(v) for v in box], "periodic": [True, True, True]},
        "species": [{"name": "water", "mass": 1.0}, {"name": "oil", "mass": 1.0},
                    {"name": "quartz", "mass": 1.0, "frozen": True}],
        "pairs": {"default": {"A": -40.0, "B": 25.0, "gamma": 4.5, "rc": 1.0, "rd": 0.75},
                  "water-oil": {"A": float(a_wo)}, "water-quartz": {"A": -40.0}, "oil-quartz": {"A": -20.0}},
        "density_kernel": "warren",
        "kT": 1.0,
        "effects": {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {},
                    "body_force": {"water": [g, 0.0, 0.0], "oil": [g, 0.0, 0.0]}, "bounce_back": {}},
        "geometry": geo,
        "initial": {"temperature": 1.0},
        "run": {"dt": 0.01, "steps": int(steps), "seed": int(seed)},
        "output": {"flux": {"every": 10, "file": "flux.csv", "species": phases, "phases": phases},
                   "summary": "summary.json", "progress": False},
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="CI size: 6000 steps")
    ap.add_argument("--h", type=int, default=10, help="pore width, voxels = rc (default 10)")
    ap.add_argument("--sw", type=float, default=0.5, help="nominal water saturation of the layers")
    ap.add_argument("--g", type=float, default=0.02)
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--a-wo", type=float, default=-30.0)
    ap.add_argument("--tol", type=float, default=0.15)
    args = ap.parse_args()
    steps = 6000 if args.quick else args.steps
    out = mdval.out_dir("relperm")
    wall, L, D = 2, 6, 4
    lab = np.ones((L, args.h + 2 * wall, D), dtype=np.uint8)
    lab[:, wall:wall + args.h, :] = 0
    image = write_raw_image(os.path.join(out, f"phase_flux_slit_h{args.h}.raw"), lab)
    box = (L, args.h + 2 * wall, D)
    res, fails = {}, []
    for tag, sw in (("single", 1.0), ("layered", args.sw)):
        wd = os.path.join(out, f"phase_flux_{tag}")
        s = scene(f"phase_flux_{tag}", image, box, args.h, wall, sw=sw, g=args.g, steps=steps, a_wo=args.a_wo,
                  seed=5)
        wall_s = mdval.run(s, wd, 1)
        summ = json.load(open(os.path.join(wd, "summary.json")))
        res[tag] = {"flux": summ["flux"], "seconds": wall_s}
        if tag == "layered":
            t = mdval.read_table(os.path.join(wd, "flux.csv"))
            dev = np.max(np.abs(t["q_water"] + t["q_oil"] - t["q"]))
            scale = max(np.max(np.abs(t["q"])), 1e-300)
            res[tag]["row_identity_max_rel"] = float(dev / scale)
            if not dev <= 1e-8 * scale:
                fails.append(f"q_water + q_oil differs from q by {dev:.3g} in a row (|q| up to {scale:.3g})")
    f1, f2 = res["single"]["flux"], res["layered"]["flux"]
    ph = f2["phases"]
    qsum = ph["water"]["q"] + ph["oil"]["q"]
    if not abs(qsum - f2["q"]) <= 1e-8 * abs(f2["q"]):
        fails.append(f"summary: q_water + q_oil = {qsum:.10g} against q = {f2['q']:.10g}")
    q1, q1e = f1["phases"]["water"]["q"], f1["phases"]["water"]["q_err"]
    sw = ph["water"]["saturation"]
    krw = ph["water"]["q"] / q1
    krw_e = abs(krw) * math.hypot(ph["water"]["q_err"] / ph["water"]["q"], q1e / q1)
    krn = ph["oil"]["q"] / q1
    krn_e = abs(krn) * math.hypot(ph["oil"]["q_err"] / ph["oil"]["q"], q1e / q1)
    ew, en = kr_layered(sw)
    for name, v, e, ex in (("krw", krw, krw_e, ew), ("krn", krn, krn_e, en)):
        ok = abs(v - ex) <= args.tol + 2 * e
        print(f"{name} = {v:.4f} +- {e:.4f} at Sw = {sw:.4f} (particle counts); layered formula {ex:.4f}: "
              f"{'pass' if ok else 'FAIL'}")
        if not ok:
            fails.append(f"{name} {v:.3f} +- {e:.3f} against the layered {ex:.3f} at Sw {sw:.3f} (tol {args.tol})")
    print(f"q = {f2['q']:.6g}, q_water + q_oil = {qsum:.6g}; largest row deviation "
          f"{res['layered']['row_identity_max_rel']:.2g} of |q|; q_w^(1) = {q1:.6g} +- {q1e:.2g}")
    res.update(Sw=sw, krw=krw, krw_err=krw_e, krn=krn, krn_err=krn_e, krw_layered=ew, krn_layered=en, fails=fails)
    mdval.write_json(os.path.join(out, "phase_flux.json"), res)
    if fails:
        print("phase_flux: FAIL: " + "; ".join(fails))
        return 1
    print("phase_flux: pass")
    return 0


if __name__ == "__main__":
    sys.exit(main())
