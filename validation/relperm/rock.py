#!/usr/bin/env python3
"""Relative permeability of a rock crop at two wettabilities, fitted, exported and run through the
continuum (docs/relperm.md section 6.4).

The sample: the Fontainebleau sandstone crop 48^3 at voxel (68, 16, 16) of
../shared/data/external/rocks/fontainebleau_200 (5.7 um voxels), 1 rc per voxel, flow along x,
mirror faces (what `mdpore relperm` chooses for it). Six `mdpore relperm` campaigns, each with its
two single-phase references, body force g = 0.05 on both liquids, 40000 steps at most, target
error 3%, phase images without trapping:

  water, oil              M = 1, morphological drainage, water-wet / oil-wet
  water_M2, oil_M2        M = 2 (the oil twice as viscous), drainage
  water_M2_imb, oil_M2_imb  M = 2, imbibition

Checks (exit 1 when one fails):
  symmetry   at M = 1 the two liquids differ only in their names, so the oil-wet campaign is the
             water-wet one relabelled: krw_oilwet(1 - Sw) = kro_waterwet(Sw) and the converse
             (the runs are bitwise the same dynamics: agreement to 1e-9)
  monotone   in every campaign krw does not fall and kro does not rise as Sw grows, beyond twice
             their combined errors
  crossover  the saturation where krw = kro (linear between rows) lies above Sw = 0.5 in the
             water-wet campaigns and below it in the oil-wet ones (Craig's rule of thumb), for
             every M = 2 pair
  ordering   at the same Sw (the oil-wet curve interpolated) krw of the water-wet sample is lower
             than that of the oil-wet sample by more than two errors
  continuum  each M = 2 imbibition table fitted (`mdpore fit relperm`), exported as SWOF (the
             water-wet one with the morphological imbibition Pc), and run through `mdpore darcy`'s
             two-phase solve at M = the measured viscosity ratio, water injected: the water front
             within 2% of the Buckley-Leverett solution of the exported table at 200 and 400 blocks

usage: rock.py emit WORK [--rock RAW] [--mdpore BIN]     crop + the six campaigns' scenes
       sh validation/relperm/run_gpu.sh 32 400 WORK/water ... (on the GPU; see run_gpu.sh)
       rock.py collect WORK [--mdpore BIN] [--outdir DIR]  collect, check, table, PNG
WORK is relative to the repository root for the GPU step (the emitted scenes carry no paths of
this machine)."""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "validation", "upscale"))
import relperm_swof_bl as bl  # noqa: E402  (the SWOF reader, Welge tangent and darcy front)

ROCK = os.path.join(ROOT, "..", "shared", "data", "external", "rocks", "fontainebleau_200",
                    "fontainebleau_200.raw")
CROP = "68:116,16:64,16:64"
COMMON = ["--axis", "x", "--rc-per-voxel", "1", "--no-trapping", "--force", "0.05", "--steps",
          "40000", "--target-error", "0.03"]
SATS_M1 = "0.15,0.35,0.45,0.9"
SATS_M2 = "0.15,0.25,0.35,0.45,0.6,0.75,0.9"
# folder, wetting liquid, viscosity ratio, morphology
CAMPAIGNS = [("water", "water", 1, "drainage"), ("oil", "oil", 1, "drainage"),
             ("water_M2", "water", 2, "drainage"), ("oil_M2", "oil", 2, "drainage"),
             ("water_M2_imb", "water", 2, "imbibition"), ("oil_M2_imb", "oil", 2, "imbibition")]
PAIRS = [("water_M2", "oil_M2"), ("water_M2_imb", "oil_M2_imb")]
FRONT_TOL = 0.02


def sh(cmd, log=None):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if log:
        with open(log, "w") as f:
            f.write(r.stdout + r.stderr)
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: exit {r.returncode}\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
    return r.stdout


def emit(a):
    os.makedirs(a.work, exist_ok=True)
    img = os.path.join(a.work, "fb48.raw")
    sh([a.mdpore, "image", "convert", a.rock, "--crop", CROP, "-o", img])
    for name, wet, m, mode in CAMPAIGNS:
        sats = SATS_M1 if m == 1 else SATS_M2
        sh([a.mdpore, "relperm", img, *COMMON, "--wetting", wet, "--viscosity-ratio", str(m),
            "--mode", mode, "--saturations", sats, "--emit-scenes", os.path.join(a.work, name)],
           log=os.path.join(a.work, name + ".emit.log"))
        print(f"emitted {name}")
    print(f"then on the GPU: sh validation/relperm/run_gpu.sh 32 400 " +
          " ".join(os.path.join(a.work, c[0]) for c in CAMPAIGNS))


def rows_of(work, name):
    j = json.load(open(os.path.join(work, name, "relperm.json")))
    rows = sorted(j["rows"], key=lambda r: r["Sw"])
    return j, rows


def crossover(rows):
    """Sw where krw - kro changes sign, linear between rows (None when it does not)."""
    for r0, r1 in zip(rows, rows[1:]):
        d0, d1 = r0["krw"] - r0["kro"], r1["krw"] - r1["kro"]
        if d0 < 0 <= d1:
            return r0["Sw"] + (r1["Sw"] - r0["Sw"]) * (-d0) / (d1 - d0)
    return None


def check_monotone(name, rows, fails):
    for r0, r1 in zip(rows, rows[1:]):
        for k, sign in (("krw", 1), ("kro", -1)):
            drop = sign * (r0[k] - r1[k])  # > 0: the wrong direction
            err = math.hypot(r0[k + "_err"], r1[k + "_err"])
            if drop > 2 * err:
                fails.append(f"{name}: {k} goes the wrong way between Sw {r0['Sw']:.3f} and "
                             f"{r1['Sw']:.3f} ({r0[k]:.4f} -> {r1[k]:.4f}, error {err:.4f})")


def continuum(a, work, name, outdir, fails):
    """An imbibition table: fit, SWOF (water-wet: Pcow from the morphological imbibition Pc; oil-wet:
    Pcow = 0, the morphology's Pc being p_water - p_oil there), darcy vs Buckley-Leverett."""
    j = json.load(open(os.path.join(work, name, "relperm.json")))
    src = os.path.join(work, name, "relperm.csv")
    runs = os.path.join(outdir, "continuum")
    os.makedirs(runs, exist_ok=True)
    swof = os.path.join(runs, name + ".swof")
    fit_json = os.path.join(outdir, name + ".fit.json")
    pc = []
    if j["wetting"] == "water":
        pc_dir = os.path.join(outdir, "pc_imbibition")
        sh([a.mdpore, "image", "drainage", os.path.join(work, "fb48.raw"), "--axis", "x",
            "--imbibition", "--no-trapping", "--rc-per-voxel", "1", "-o", pc_dir])
        pc = ["--pc-morph", os.path.join(pc_dir, "pc_morph.csv")]
    sh([a.mdpore, "fit", "relperm", src, "--swof", swof, *pc, "--json", fit_json, "--quiet"])
    fit = json.load(open(fit_json))
    tab = bl.read_swof(swof)
    m = j["M"]
    s_i = tab[0, 0]
    f = bl.fw_table(tab, m)
    s_f, slope = bl.welge(f, s_i, tab[-1, 0])
    out = []
    for n in bl.BLOCKS:
        x_f, x_num, t_end, x, s = bl.darcy_front(a.mdpore, runs, name, swof, m, n, s_i, s_f, slope)
        err = x_num / x_f - 1
        out.append({"blocks": n, "x_f": x_f, "x_num": x_num, "err": err, "x": x.tolist(),
                    "s": s.tolist()})
        if abs(err) > FRONT_TOL:
            fails.append(f"continuum {name}: front at {n} blocks {x_num:.4f} m against {x_f:.4f} m "
                         f"({100 * err:+.2f}%, limit {100 * FRONT_TOL:.0f}%)")
    return {"name": name, "wetting": j["wetting"], "M": m, "s_i": s_i, "s_f": s_f, "slope": slope, "fronts": out,
            "law": fit.get("choice", {}).get("law"), "swof": os.path.relpath(swof, outdir)}


def collect(a):
    work, outdir = a.work, a.outdir
    os.makedirs(outdir, exist_ok=True)
    fails, res = [], {}
    for name, wet, m, mode in CAMPAIGNS:
        sh([a.mdpore, "relperm", "--collect", os.path.join(work, name)],
           log=os.path.join(outdir, name + ".collect.txt"))
        j, rows = rows_of(work, name)
        res[name] = {"wetting": wet, "M": j["M"], "M_err": j["M_err"], "mode": mode, "rows": rows,
                     "left_out": j["left_out"], "q_water_single": j["q_water_single"],
                     "q_oil_single": j["q_oil_single"], "crossover": crossover(rows)}
        if j["left_out"]:
            fails.append(f"{name}: runs left out: {j['left_out']}")
        check_monotone(name, rows, fails)
    # symmetry at M = 1: oil-wet = water-wet relabelled
    ww = res["water"]["rows"]
    for r in res["oil"]["rows"]:
        match = [w for w in ww if abs(w["Sw"] - (1 - r["Sw"])) < 1e-9]
        if not match or abs(r["krw"] - match[0]["kro"]) > 1e-9 or abs(r["kro"] - match[0]["krw"]) > 1e-9:
            fails.append(f"symmetry: oil-wet row Sw {r['Sw']:.4f} is not the water-wet row at "
                         f"Sw {1 - r['Sw']:.4f} relabelled")
    # crossover and ordering for the M = 2 pairs
    for wn, on in PAIRS:
        cw, co = res[wn]["crossover"], res[on]["crossover"]
        if cw is None or cw <= 0.5:
            fails.append(f"crossover: {wn} (water-wet) at {cw}: expected above Sw = 0.5")
        if co is None or co >= 0.5:
            fails.append(f"crossover: {on} (oil-wet) at {co}: expected below Sw = 0.5")
        orows = res[on]["rows"]
        osw = np.array([r["Sw"] for r in orows])
        for r in res[wn]["rows"]:
            if not osw[0] <= r["Sw"] <= osw[-1]:
                continue
            k = int(np.searchsorted(osw, r["Sw"]))
            k = min(max(k, 1), len(orows) - 1)
            r0, r1 = orows[k - 1], orows[k]
            t = (r["Sw"] - r0["Sw"]) / (r1["Sw"] - r0["Sw"])
            kr_o = r0["krw"] + t * (r1["krw"] - r0["krw"])
            e_o = max(r0["krw_err"], r1["krw_err"])
            if not kr_o - r["krw"] > 2 * math.hypot(e_o, r["krw_err"]):
                fails.append(f"ordering: at Sw {r['Sw']:.3f} krw water-wet {r['krw']:.4f} is not "
                             f"below oil-wet {kr_o:.4f} by two errors")
    cont = [continuum(a, work, name, outdir, fails) for name in ("water_M2_imb", "oil_M2_imb")]
    report(res, cont, fails, outdir)
    plot(res, cont, outdir)
    print("\n".join(fails) if fails else "all checks pass")
    sys.exit(1 if fails else 0)


def report(res, cont, fails, outdir):
    lines = ["# Relative permeability of a Fontainebleau crop (48^3, 1 rc per voxel, x, mirror faces)", "",
             "kr_i = q_i / q_i^(1) (each liquid against itself alone, same image and body force g = 0.05);"
             " Sw from particle counts; phase images by morphology without trapping; errors 1 sigma.", "",
             "| campaign | wetting | M | phases | Sw | krw | kro | Ca | Snw connected / disconnected |",
             "|---|---|---|---|---|---|---|---|---|"]
    for name, *_ in CAMPAIGNS:
        c = res[name]
        for r in c["rows"]:
            lines.append(f"| {name} | {c['wetting']} | {c['M']:.3g} | {c['mode']} | {r['Sw']:.3f} | "
                         f"{r['krw']:.4f} +- {r['krw_err']:.4f} | {r['kro']:.4f} +- {r['kro_err']:.4f} | "
                         f"{r['Ca']:.3f} | {r['Snw_connected']:.3f} / {r['Snw_disconnected']:.3f} |")
    lines += ["", "| campaign | crossover Sw (krw = kro) | q_water^(1) | q_oil^(1) |", "|---|---|---|---|"]
    for name, *_ in CAMPAIGNS:
        c = res[name]
        x = "-" if c["crossover"] is None else f"{c['crossover']:.3f}"
        lines.append(f"| {name} | {x} | {c['q_water_single']:.5g} | {c['q_oil_single']:.5g} |")
    for c in cont:
        how = (f"fitted ({c['law']})" if c["law"] else
               "no law supported by the data (mdpore fit relperm): its measured points")
        lines += ["", f"Continuum: {c['name']} {how}, exported to SWOF "
                  f"({'Pcow from the morphological imbibition Pc' if c['wetting'] == 'water' else 'Pcow 0'}), "
                  f"`mdpore darcy` two-phase at M = {c['M']:.3g}: Welge shock S_f = {c['s_f']:.4f} from "
                  f"S_i = {c['s_i']:.4f}"]
        for fr in c["fronts"]:
            lines.append(f"- {fr['blocks']} blocks: front {fr['x_num']:.4f} m against {fr['x_f']:.4f} m "
                         f"({100 * fr['err']:+.2f}%)")
    lines += ["", "Checks: " + ("all pass" if not fails else f"{len(fails)} failed")] + \
        [f"- {f}" for f in fails]
    open(os.path.join(outdir, "rock.md"), "w").write("\n".join(lines) + "\n")
    json.dump({"campaigns": res, "continuum": cont, "failures": fails},
              open(os.path.join(outdir, "rock.json"), "w"), indent=1)
    print("\n".join(lines))


def plot(res, cont, outdir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axs = plt.subplots(1, 3, figsize=(15, 4.6))
    style = {"water": ("b", "o"), "oil": ("r", "s")}
    for ax, names, title in ((axs[0], ("water", "oil"), "M = 1, drainage"),
                             (axs[1], ("water_M2_imb", "oil_M2_imb", "water_M2", "oil_M2"),
                              "M = 2: imbibition (filled), drainage (open)")):
        for name in names:
            c = res[name]
            col = "tab:blue" if c["wetting"] == "water" else "tab:red"
            mfc = "none" if (c["mode"] == "drainage" and len(names) > 2) else col
            sw = [r["Sw"] for r in c["rows"]]
            ax.errorbar(sw, [r["krw"] for r in c["rows"]], [r["krw_err"] for r in c["rows"]], color=col,
                        marker="o", mfc=mfc, ls="-", label=f"krw, {c['wetting']}-wet ({c['mode']})")
            ax.errorbar(sw, [r["kro"] for r in c["rows"]], [r["kro_err"] for r in c["rows"]], color=col,
                        marker="s", mfc=mfc, ls="--", label=f"kro, {c['wetting']}-wet ({c['mode']})")
        ax.axvline(0.5, color="0.7", lw=0.8)
        ax.set_xlabel("Sw (particle counts)")
        ax.set_ylabel("kr = q_i / q_i^(1)")
        ax.set_title(title)
        ax.set_xlim(0, 1)
        ax.legend(fontsize=6)
    for c in cont:
        col = "tab:blue" if c["wetting"] == "water" else "tab:red"
        for fr, ls in zip(c["fronts"], ("-", "--")):
            axs[2].plot(fr["x"], fr["s"], color=col, ls=ls,
                        label=f"{c['wetting']}-wet table, mdpore darcy, {fr['blocks']} blocks")
        x_f = c["fronts"][0]["x_f"]
        axs[2].plot([x_f, x_f], [c["s_i"], c["s_f"]], "k:", lw=1)
    axs[2].plot([], [], "k:", label="Buckley-Leverett shock of each table")
    axs[2].set_xlabel("x (m)")
    axs[2].set_ylabel("Sw")
    axs[2].set_title(f"imbibition tables as SWOF, water injected, M = {cont[0]['M']:.3g}")
    axs[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "rock.png"), dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("stage", choices=["emit", "collect"])
    ap.add_argument("work")
    ap.add_argument("--rock", default=ROCK)
    ap.add_argument("--mdpore", default=os.environ.get("MDPORE", os.path.join(ROOT, "build", "bin", "mdpore")))
    ap.add_argument("--outdir", default=os.path.join(ROOT, "validation", "results", "relperm", "rock"))
    a = ap.parse_args()
    emit(a) if a.stage == "emit" else collect(a)


if __name__ == "__main__":
    main()
