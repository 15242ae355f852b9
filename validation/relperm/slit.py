"""`mdpore relperm` on a slit against the layered co-flow solution (docs/relperm.md section
6.2).

The image: a slit along x, walls of 2 voxels normal to y, pore width --h voxels at 1 rc per voxel
(periodic along x: --boundary periodic). The phase distributions are layered (a slit has one pore
size, so its morphological drainage is all or nothing): water films of a voxels on both walls, oil
(label 3) between them, a = 1 .. h/2 - 1, written as labelled images and given to the command with
--phase-images. M = 1 (--viscosity-ratio 1). The command runs the two-liquid runs and the two
single-phase references and writes relperm.csv / .json; this script compares krw and kro with the
exact layered solution at the run's Sw (particle counts):

    krw = Sw^2 (3 - Sw) / 2,    krn = (1 - Sw)^3 + (3/2) M Sw (2 - Sw) (1 - Sw)

(docs/twophase.md section 5). Tolerance: |kr - exact| <= --rel-tol exact + --abs-tol + 2 sigma,
default 0.25 exact + 0.04: the wetting films of 1-2 rc carry 15-20% less than the continuum solution
(krw 0.79-0.85 of exact at h = 6, 0.93 at h = 12, docs/twophase.md section 5: the films' resolution),
and Sw by particle counts includes the first layer at the wall that hardly moves. A film of one voxel
(1 rc) is that layer: it hardly flows and the oil core sees a slit narrower by 2 rc, so films below
--min-film (default 2 rc) are reported and not checked (except krw in --quick). The water-oil A is
-30 by default (--cross-attraction): at the standard -20 the one-particle-thin interface lets the oil
slip over the water and kro exceeds the layered solution (up to 2x at small Sw, docs/twophase.md
section 5); --a-wo -20 measures that. --quick (ctest): h = 8, box 4 x 12 x 3, films of 1 and 3
voxels (Sw 1/4 and 3/4), g = 0.02, 8000 steps: krw within the tolerance, krw increasing with Sw.
Then `mdpore fit relperm` on the campaign's relperm.csv (no simulation): its SWOF table must be
valid (4 columns, Sw increasing in [0, 1], krw non-decreasing from 0, krow non-increasing to 0) and
its krw at the measured Sw within the same tolerance of the layered krw (check_swof).

    nice -n 5 /usr/bin/python3 validation/relperm/slit.py [--quick] [--a-wo -30]
"""
import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "engine"))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "walls"))
import mdval  # noqa: E402
from common import write_raw_image  # noqa: E402


def kr_layered(sw, M=1.0):
    return sw ** 2 * (3 - sw) / 2, (1 - sw) ** 3 + 1.5 * M * sw * (2 - sw) * (1 - sw)


def read_swof(path):
    """The rows of a SWOF file (Sw krw krow Pcow) and its '--' header."""
    text = open(path).read()
    head, _, body = text.partition("\nSWOF\n")
    rows = []
    for line in body.splitlines():
        t = line.strip()
        if t == "/":
            break
        if t and not t.startswith("--"):
            rows.append([float(v) for v in t.split()])
    return head, rows


def check_swof(work, rows, M, args):
    """`mdpore fit relperm` on the campaign's relperm.csv (no simulation): the SWOF export is valid
    (4 columns, Sw strictly increasing in [0, 1], krw non-decreasing from 0, krow non-increasing to
    0, kr in [0, 1]) and at the measured Sw its krw (interpolated as a simulator does) is within
    the tolerance of the layered-slit krw = Sw^2 (3 - Sw) / 2 (docs/twophase.md section 5)."""
    fails = []
    src, swof = os.path.join(work, "relperm.csv"), os.path.join(work, "relperm.swof")
    p = subprocess.run([mdval.mdpore_binary(), "fit", "relperm", src, "--swof", swof, "--json",
                        os.path.join(work, "relperm.fit.json"), "--quiet"], env=mdval.mpi_env(),
                       capture_output=True, text=True)
    if p.returncode != 0 or not os.path.exists(swof):
        return [f"mdpore fit relperm {src}: exit {p.returncode}: {(p.stdout + p.stderr)[-600:]}"]
    head, t = read_swof(swof)
    sw, krw, krow = (np.array([r[k] for r in t]) for k in range(3))
    if not (t and all(len(r) == 4 for r in t) and np.all(np.diff(sw) > 0) and sw[0] >= 0
            and sw[-1] <= 1 and np.all(np.diff(krw) >= 0) and np.all(np.diff(krow) <= 0)
            and krw[0] == 0 and krow[-1] == 0 and np.all((krw >= 0) & (krw <= 1))
            and np.all((krow >= 0) & (krow <= 1))):
        fails.append(f"{swof}: not a valid SWOF table: {t}")
    measured = "THE MEASURED POINTS" in head
    for r in rows:
        if not 0 < r["Sw"] <= 1:
            fails.append(f"measured Sw {r['Sw']} outside (0, 1]")
        v = float(np.interp(r["Sw"], sw, krw))
        ex = kr_layered(r["Sw"], M)[0]
        ok = abs(v - ex) <= args.rel_tol * ex + args.abs_tol + 2 * r["krw_err"]
        print(f"SWOF ({'measured points' if measured else 'law'}): krw({r['Sw']:.3f}) = {v:.4f}, "
              f"layered {ex:.4f}: {'pass' if ok else 'FAIL'}")
        if not ok:
            fails.append(f"SWOF krw {v:.3f} at Sw {r['Sw']:.3f}: layered {ex:.3f}")
    return fails


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--h", type=int, default=12, help="pore width in voxels = rc (default 12)")
    ap.add_argument("--length", type=int, default=6)
    ap.add_argument("--depth", type=int, default=4)
    ap.add_argument("--films", default=None, help="film thicknesses a in voxels (default 1..h/2-1)")
    ap.add_argument("--g", type=float, default=0.01)
    ap.add_argument("--steps", type=int, default=20000)
    ap.add_argument("--target-error", type=float, default=0.02)
    ap.add_argument("--a-wo", type=float, default=-30.0)
    ap.add_argument("--rel-tol", type=float, default=0.25)
    ap.add_argument("--abs-tol", type=float, default=0.04)
    ap.add_argument("--min-film", type=int, default=2,
                    help="films thinner than this (voxels = rc) are reported, not checked (default 2)")
    ap.add_argument("--tag", default=None)
    args = ap.parse_args()
    if args.quick:
        args.h, args.length, args.depth, args.steps, args.g = 8, 4, 3, 8000, 0.02
        films = [1, 3]
    else:
        films = [int(v) for v in args.films.split(",")] if args.films else list(range(1, args.h // 2))
    tag = args.tag or ("slit_quick" if args.quick else f"slit_h{args.h}_awo{-args.a_wo:g}")
    out = mdval.out_dir("relperm")
    wall = 2
    ny = args.h + 2 * wall
    base = np.ones((args.length, ny, args.depth), dtype=np.uint8)
    base[:, wall:wall + args.h, :] = 0
    image = write_raw_image(os.path.join(out, f"{tag}.raw"), base)
    phase_images = []
    for a in films:
        lab = base.copy()
        lab[:, wall + a:wall + args.h - a, :] = 3
        phase_images.append(write_raw_image(os.path.join(out, f"{tag}_a{a}.raw"), lab,
                                            labelmap="pore=0,3;inorganic=1"))
    work = os.path.join(out, f"{tag}_work")
    cmd = [mdval.mdpore_binary(), "relperm", image, "--axis", "x", "--phase-images", ",".join(phase_images),
           "--nw-label", "3", "--viscosity-ratio", "1", "--cross-attraction", str(args.a_wo), "--force", str(args.g),
           "--rc-per-voxel", "1", "--boundary", "periodic", "--steps", str(args.steps), "--target-error",
           str(args.target_error), work]
    print(" ".join(cmd), flush=True)
    p = subprocess.run(cmd, env=mdval.mpi_env(), capture_output=True, text=True)
    open(os.path.join(out, f"{tag}.log"), "w").write(p.stdout + p.stderr)
    print(p.stdout[-4000:])
    if p.returncode not in (0, 1) or not os.path.exists(os.path.join(work, "relperm.json")):
        print(p.stderr[-3000:])
        print(f"slit: FAIL: mdpore relperm exit {p.returncode}")
        return 1
    d = json.load(open(os.path.join(work, "relperm.json")))
    rows, fails, table = d["rows"], [], []
    # a second collect of the finished folder reads what the first left (its outputs do not
    # replace its inputs) and writes the same table
    csv_first = open(os.path.join(work, "relperm.csv")).read()
    p2 = subprocess.run([mdval.mdpore_binary(), "relperm", "--collect", work], env=mdval.mpi_env(),
                        capture_output=True, text=True)
    if p2.returncode != p.returncode or open(os.path.join(work, "relperm.csv")).read() != csv_first:
        fails.append(f"a second --collect: exit {p2.returncode} (first {p.returncode}), table "
                     f"{'changed' if p2.returncode == 0 else 'not written'}: {p2.stderr[-300:]}")
    if len(rows) != len(films):
        fails.append(f"{len(rows)} rows of {len(films)} runs (left out: {d['left_out']})")
    for r in rows:
        ew, en = kr_layered(r["Sw"], d["M"])
        film = int(round((1 - r["Snw_image"]) * args.h / 2))
        ok = []
        for name, v, e, ex in (("krw", r["krw"], r["krw_err"], ew), ("kro", r["kro"], r["kro_err"], en)):
            if (args.quick and name == "kro") or (not args.quick and film < args.min_film):
                continue
            good = abs(v - ex) <= args.rel_tol * ex + args.abs_tol + 2 * e
            ok.append(good)
            if not good:
                fails.append(f"{name} {v:.3f} +- {e:.3f} at Sw {r['Sw']:.3f}: layered {ex:.3f}")
        table.append([film, r["Sw"], r["Snw_image"], r["krw"], r["krw_err"], ew, r["krw"] / ew, r["kro"], r["kro_err"], en,
                      r["kro"] / en, r["Ca"], ("pass" if all(ok) else "FAIL") if ok else "not checked"])
    krw = [r["krw"] for r in rows]
    if any(b <= a for a, b in zip(krw, krw[1:])):
        fails.append(f"krw does not increase with Sw: {krw}")
    fails += check_swof(work, rows, d["M"], args)
    mdval.write_report(out, tag, ["film (rc)", "Sw", "Snw image", "krw", "krw err", "layered", "ratio", "kro", "kro err",
                                  "layered", "ratio", "Ca", "check"], table,
                       notes=f"`{' '.join(','.join(os.path.basename(x) for x in c.split(',')) if '/' in c else c for c in cmd)}`\n\n"
                             f"slit h = {args.h}, box {args.length} x {ny} x {args.depth}, g = {args.g}, "
                             f"A_wo = {args.a_wo}, M = {d['M']}; q_w^(1) = {d['q_water_single']:.5g} +- "
                             f"{d['q_water_single_err']:.2g}, q_o^(1) = {d['q_oil_single']:.5g} +- "
                             f"{d['q_oil_single_err']:.2g}; tolerance {args.rel_tol} exact + {args.abs_tol} + 2 sigma"
                             f"{' (kro not checked in --quick)' if args.quick else f'; films below {args.min_film} rc not checked'}")
    plt = mdval.pyplot()
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    s = np.linspace(0, 1, 101)
    ax.plot(s, kr_layered(s, d["M"])[0], "b-", lw=1, label="layered krw")
    ax.plot(s, kr_layered(s, d["M"])[1], "r-", lw=1, label="layered krn")
    ax.errorbar([r["Sw"] for r in rows], krw, yerr=[r["krw_err"] for r in rows], fmt="bo", capsize=3,
                label="mdpore relperm krw")
    ax.errorbar([r["Sw"] for r in rows], [r["kro"] for r in rows], yerr=[r["kro_err"] for r in rows], fmt="rs",
                capsize=3, label="mdpore relperm kro")
    ax.set_xlabel("Sw (particle counts)")
    ax.set_ylabel("kr")
    ax.set_xlim(0, 1)
    ax.set_ylim(bottom=0)
    ax.set_title(f"slit h = {args.h}, M = {d['M']:g}, A_wo = {args.a_wo:g}", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, f"{tag}.png"), dpi=120)
    mdval.write_json(os.path.join(out, f"{tag}.json"), {"rows": rows, "table": table, "fails": fails,
                                                         "args": vars(args)})
    if fails:
        print("slit: FAIL: " + "; ".join(fails))
        return 1
    print("slit: pass")
    return 0


if __name__ == "__main__":
    sys.exit(main())
