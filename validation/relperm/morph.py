#!/usr/bin/python3
"""Morphological drainage and imbibition (`mdpore image drainage`, docs/relperm.md sections 2 and 6)
on a sphere pack and on a real rock crop: the Pc(Sw) and Leverett J curves, drainage and imbibition,
with and without trapping, and the residual saturations that trapping leaves.

Samples:
  pack  the drp-benchmarks random pack of 621 equal spheres (../shared/data/external/drp_spherepack),
        voxelised with `mdpore image make sphere-file --radius 3.5 --dx 0.5`: sphere radius Rs = 7
        voxels, 110 x 111 x 111 voxels, porosity 0.343, periodic (distances measured across the y and
        z faces, --periodic); axis x. k = 0.02363 rc^2 at 0.5 rc per voxel (the mDPD campaign of
        docs/permeability.md, "The drp sphere pack").
  rock  the Fontainebleau crop 48^3 at (68, 16, 16) (../shared/data/external/rocks/fontainebleau_200,
        5.7 um voxels), axis x, faces open, 0.58 rc per voxel; k = 0.1869 voxel^2 along x (its mDPD
        campaign, docs/permeability.md), porosity 0.158.
Per sample: four curves (drainage / imbibition x trapping on / off) and `mdpore image info --sizes` for
the critical throat d_c (the breakthrough diameter of mercury intrusion, a separate bisection).

Reported: the entry radius (first invasion from the inlet), the breakthrough radius (the non-wetting
phase first spans the axis) and its Pc* = Pc Rs / (gamma cos theta) = 2 Rs / R (pack), the irreducible
wetting saturation of drainage with trapping, the residual non-wetting saturation of imbibition with
trapping, J at Sw = 0.5.
Checks (exit 1 when one fails): each curve monotone (drainage Snw never falls as R falls, imbibition
Snw never rises as R grows); trapping leaves a residual (> 0) and none without it (trapped = 0); the
no-trapping drainage ends at least as drained as the trapping one; the breakthrough radius within one
voxel of d_c / 2 (both are the largest ball that crosses the sample, found by different codes; the
ball radius of the digital balls differs by up to a voxel between them); the CSV's J equals
2 sqrt(k / phi) / r recomputed.

Usage: /usr/bin/python3 validation/relperm/morph.py [--work DIR] [--samples pack rock]
Results: validation/results/relperm/morph.{md,json,png} (MDPORE_VALIDATION_OUT overrides the folder).
MDPORE: the mdpore binary (default build/bin/mdpore)."""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MDPORE = os.environ.get("MDPORE") or os.path.join(ROOT, "build", "bin", "mdpore")
SHARED = os.path.join(ROOT, "..", "shared", "data", "external")
RESULTS = os.environ.get("MDPORE_VALIDATION_OUT") or os.path.join(ROOT, "validation", "results", "relperm")

SAMPLES = {
    "pack": {"title": "drp random sphere pack (Rs = 7 voxels)", "axis": "x", "periodic": True,
             "rc_per_voxel": 0.5, "k": "0.02363", "phi": 0.343, "rs_vox": 7.0},
    "rock": {"title": "Fontainebleau 48^3 at (68, 16, 16)", "axis": "x", "periodic": False,
             "rc_per_voxel": 0.58, "k": "0.1869vox2", "phi": 0.158, "rs_vox": None},
}
CURVES = [("drainage", True), ("drainage", False), ("imbibition", True), ("imbibition", False)]


def mdpore(*args):
    t = time.time()
    p = subprocess.run([MDPORE, *args], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"mdpore {' '.join(args)}: exit {p.returncode}\n{p.stderr[-3000:]}")
    return p.stdout, time.time() - t


def image_of(name, work):
    if name == "pack":
        path = os.path.join(work, "pack.h5")
        if not os.path.exists(path):
            d = os.path.join(SHARED, "drp_spherepack")
            mdpore("image", "make", "sphere-file", "--centres", os.path.join(d, "final_loc_cn1.dat"),
                   "--box-file", os.path.join(d, "Box_DIM.dat"), "--radius", "3.5", "--dx", "0.5",
                   "-o", path)
        return path, []
    raw = os.path.join(SHARED, "rocks", "fontainebleau_200", "fontainebleau_200.raw")
    return raw, ["--crop", "68:116,16:64,16:64"]


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    out = []
    for r in rows:
        out.append({k: (float(v) if v not in ("",) else float("nan")) for k, v in r.items()})
    return out


def run_sample(name, work, failures):
    s = SAMPLES[name]
    path, extra = image_of(name, work)
    info, _ = mdpore("image", "info", path, *extra, "--sizes", "--json",
                     *(["--periodic"] if s["periodic"] else []))
    info = json.loads(info)
    throat = info["sizes"]["critical_throat_voxels"][s["axis"]]
    res = {"title": s["title"], "dims": info["dims"], "porosity": info["porosity"],
           "critical_throat_voxels": throat, "curves": {}}
    for mode, trap in CURVES:
        key = f"{mode}_{'trap' if trap else 'notrap'}"
        out = os.path.join(work, name, key)
        args = ["image", "drainage", path, *extra, "--axis", s["axis"], "--rc-per-voxel",
                str(s["rc_per_voxel"]), "--k", s["k"], "--phi", str(s["phi"]), "-o", out, "--no-plot"]
        if mode == "imbibition":
            args.append("--imbibition")
        if not trap:
            args.append("--no-trapping")
        if s["periodic"]:
            args.append("--periodic")
        _, secs = mdpore(*args)
        rows = read_csv(os.path.join(out, "pc_morph.csv"))
        res["curves"][key] = {"rows": rows, "seconds": secs}
        snw = [r["Snw"] for r in rows]
        mono = all(b >= a - 1e-12 for a, b in zip(snw, snw[1:])) if mode == "drainage" else \
            all(b <= a + 1e-12 for a, b in zip(snw, snw[1:]))
        if not mono:
            failures.append(f"{name} {key}: Snw not monotone")
        last = rows[-1]
        if trap and not last["trapped"] > 0:
            failures.append(f"{name} {key}: trapping left no residual")
        if not trap and last["trapped"] != 0:
            failures.append(f"{name} {key}: {last['trapped']} trapped without trapping")
        h = s["rc_per_voxel"]
        kk = float(s["k"].replace("vox2", "")) * (h * h if s["k"].endswith("vox2") else 1.0)
        for r in rows:
            j = 2 * math.sqrt(kk / s["phi"]) / r["radius_rc"]
            if abs(r["J"] - j) > 1e-6 * j:
                failures.append(f"{name} {key}: J {r['J']} at r {r['radius_rc']}, expected {j}")
                break
    d = res["curves"]
    dt, dn = d["drainage_trap"]["rows"], d["drainage_notrap"]["rows"]
    it = d["imbibition_trap"]["rows"]
    entry = next((r for r in dt if r["Snw"] > 0), None)
    brk = next((r for r in dt if r["nw_spans"] == 1), None)
    res["entry_radius_vox"] = entry["radius_vox"] if entry else None
    res["breakthrough_radius_vox"] = brk["radius_vox"] if brk else None
    res["breakthrough_snw"] = brk["Snw"] if brk else None
    res["sw_irreducible_trap"] = dt[-1]["Sw"]
    res["sw_end_notrap"] = dn[-1]["Sw"]
    res["snw_residual_trap"] = it[-1]["Snw"]
    res["snw_end_imbibition_notrap"] = d["imbibition_notrap"]["rows"][-1]["Snw"]
    if dn[-1]["Snw"] < dt[-1]["Snw"] - 1e-12:
        failures.append(f"{name}: drainage ends less drained without trapping")
    if brk is None:
        failures.append(f"{name}: the non-wetting phase never spans the axis")
    elif abs(brk["radius_vox"] - 0.5 * throat) > 1.0:
        failures.append(f"{name}: breakthrough R {brk['radius_vox']:.3g} vs d_c / 2 = {0.5 * throat}")
    half = min(dt, key=lambda r: abs(r["Sw"] - 0.5))
    res["J_at_sw_half"] = {"Sw": half["Sw"], "J": half["J"], "pc": half["pc"],
                           "pc_Pa": half["pc_Pa"] if not math.isnan(half["pc_Pa"]) else None}
    if s["rs_vox"] and brk:
        res["breakthrough_pc_star"] = 2 * s["rs_vox"] / brk["radius_vox"]
    return res


def plot(results, png):
    fig, axes = plt.subplots(2, len(results), figsize=(6 * len(results), 9), squeeze=False)
    styles = {"drainage_trap": ("C0", "-"), "drainage_notrap": ("C0", ":"),
              "imbibition_trap": ("C3", "-"), "imbibition_notrap": ("C3", ":")}
    for col, (name, res) in enumerate(results.items()):
        for key, c in res["curves"].items():
            rows = c["rows"]
            sw = [r["Sw"] for r in rows]
            color, ls = styles[key]
            label = key.replace("_notrap", ", no trapping").replace("_trap", ", trapping")
            axes[0][col].step(sw, [r["pc"] for r in rows], where="post", color=color, ls=ls,
                              label=label)
            axes[1][col].step(sw, [r["J"] for r in rows], where="post", color=color, ls=ls,
                              label=label)
        axes[0][col].set_title(res["title"], fontsize=10)
        axes[0][col].set_ylabel("Pc = 2 gamma cos / r (kT/rc^3, gamma cos = 8.67)")
        axes[1][col].set_ylabel("Leverett J = Pc sqrt(k/phi) / (gamma cos)")
        for ax in (axes[0][col], axes[1][col]):
            ax.set_xlabel("wetting saturation Sw")
            ax.set_xlim(0, 1)
            ax.set_yscale("log")
            ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def table(results, failures):
    lines = ["# Morphological drainage and imbibition (validation/relperm/morph.py)", "",
             "Pc = 2 gamma cos / r with gamma cos = 8.67 kT/rc^2 (the standard water/oil pair set); "
             "r = R x rc per voxel; J = 2 sqrt(k / phi) / r.", "",
             "| sample | voxels | porosity | d_c (voxels) | entry R | breakthrough R (Snw) | "
             "Sw irreducible (trapping) | Sw end (no trapping) | Snw residual (imbibition, trapping) | "
             "Snw end (imbibition, no trapping) | J at Sw 0.5 | seconds (4 curves) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, r in results.items():
        secs = sum(c["seconds"] for c in r["curves"].values())
        lines.append(
            f"| {r['title']} | {'x'.join(map(str, r['dims']))} | {r['porosity']:.4f} | "
            f"{r['critical_throat_voxels']} | {r['entry_radius_vox']:.3g} | "
            f"{r['breakthrough_radius_vox']:.3g} ({r['breakthrough_snw']:.3f}) | "
            f"{r['sw_irreducible_trap']:.4f} | {r['sw_end_notrap']:.4f} | {r['snw_residual_trap']:.4f} | "
            f"{r['snw_end_imbibition_notrap']:.4f} | {r['J_at_sw_half']['J']:.3g} | {secs:.1f} |")
    for name, r in results.items():
        if "breakthrough_pc_star" in r:
            lines.append("")
            lines.append(f"{r['title']}: breakthrough Pc* = Pc Rs / (gamma cos) = 2 Rs / R = "
                         f"{r['breakthrough_pc_star']:.3g}.")
    lines.append("")
    lines.append("Checks: " + ("all passed" if not failures else "FAILED: " + "; ".join(failures)))
    return "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--work", default=os.path.join(ROOT, "out", "relperm_morph"))
    p.add_argument("--samples", nargs="+", default=["pack", "rock"], choices=list(SAMPLES))
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    os.makedirs(RESULTS, exist_ok=True)
    failures = []
    results = {n: run_sample(n, a.work, failures) for n in a.samples}
    plot(results, os.path.join(RESULTS, "morph.png"))
    md = table(results, failures)
    with open(os.path.join(RESULTS, "morph.md"), "w") as f:
        f.write(md)
    slim = {n: {k: v for k, v in r.items() if k != "curves"} for n, r in results.items()}
    for n, r in results.items():
        slim[n]["curves"] = {k: [{kk: (None if isinstance(vv, float) and math.isnan(vv) else vv)
                                  for kk, vv in row.items()} for row in c["rows"]]
                             for k, c in r["curves"].items()}
    with open(os.path.join(RESULTS, "morph.json"), "w") as f:
        json.dump({"results": slim, "failures": failures}, f, indent=1)
    print(md)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
