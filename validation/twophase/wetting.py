#!/usr/bin/python3
"""Two immiscible liquids on an image wall: the static contact angle of water against oil (measured
through the water) for several pairs of liquid-wall attractions, per solid phase (docs/twophase.md,
"Contact angles of two liquids").

Liquids: water and oil, A_ww = A_oo = -40, A_wo = -20, B = 25, rd = 0.75 for every pair (Warren's
no-go rule), gamma = 4.5 for every pair, kT = 1, dt = 0.01. Water and oil differ only by their
wall attractions, so the model is symmetric under water <-> oil.

Geometry, by the user's path: a voxel image (rc_per_voxel 0.5, written here as raw + sidecar) of
--length x (--pore-height + 2) x --depth rc whose two voxel layers at y = 0 are `inorganic`
(species quartz) and two at the top are `organic` (species kerogen); periodic, so the solid is one
slab 2 rc thick across the y boundary: its lower face (quartz, y = 1) and its upper face (kerogen,
y = Ly - 1) face the pore. `geometry:` builds the walls (patches at density 8) and fills the pore at
density 6.2 with oil; `geometry.fluid_species_regions` turns the fluid inside two cylinders along z
into water: one thread on the quartz face at x = L/4, one on the kerogen face at x = 3L/4, each of
radius --radius centred 0.3 radius off the face. Boundary: bounce_back.

Pairs per run: water-quartz A = A_w, oil-quartz A = A_o (--a-oil); on the kerogen the two are
swapped (water-kerogen A_o, oil-kerogen A_w). By the water <-> oil symmetry the water angle on the
kerogen is then 180 minus that on the quartz: every run gives two angles, a check of the model's
symmetry and of the per-phase, per-liquid pairs, and a second independent sample.

Analysis (per face; the kerogen face mirrored y -> Ly - y): HDF5 snapshots every --every steps from
--equil on; each snapshot is centred on that face's thread (circular mean of x of the water in
that half of the pore), water and oil binned in (x, y) at 0.25 rc over all z and summed; the order
parameter phi = (n_w - n_o) / (n_w + n_o) of the summed field; its phi = 0 contour in the face's
half of the pore, more than --skip (1 rc) above the wall surface, fitted with a circle (algebraic,
then geometric least squares); cos(theta) = (y_wall - y_c) / R, theta measured through the water.
Error: the standard error of the angles of 4 consecutive blocks of snapshots.

Young cross-check: cos theta_wo = (gamma_wv cos theta_w - gamma_ov cos theta_o) / gamma_wo (through
the water) from the single-liquid angles of validation/results/walls/contact_angle.csv (A_sl = -35,
-30, -20 against vapour), gamma_lv = 7.54 (physics.md section 2, A = -40) and the flat water-oil
tension 14.72 (docs/twophase.md section 4).

Checks (exit 1 when one fails): every fit good (rms < --rms-max rc over >= 20 points, 0 < theta
< 180); on the quartz the water angle grows as A_w weakens, on the kerogen it falls (more
attractive water-wall A than oil-wall A: smaller water angle). --quick (the ctest): one small run,
quartz A_w = -35, A_o = -25 and kerogen swapped: water angle < 90 on the quartz, > 90 on the
kerogen.

Full run (results in validation/results/twophase/wetting.{md,json,png}):
    nice -n 5 /usr/bin/python3 validation/twophase/wetting.py
"""
import argparse
import csv
import json
import math
import os
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "walls"))
from common import RC_PER_VOXEL, mdval, penetrations, run_or_reuse, write_raw_image  # noqa: E402

BIN = 0.25
WALL_VOX = 2  # voxel layers of each phase: the solid is 2 x 2 x 0.5 = 2 rc thick
GAMMA_LV = 7.54  # liquid-vapour tension of A = -40 (physics.md section 2)
GAMMA_WO = 14.72  # flat water-oil tension (docs/twophase.md section 4)
SPECIES = ["water", "oil", "quartz", "kerogen"]


def make_image(img_dir, nx, ny, nz):
    """Slab image: 2 voxel layers of inorganic (1) at y = 0, 2 of organic (2) at the top, pore between."""
    lab = np.zeros((nx, ny, nz), dtype=np.uint8)
    lab[:, :WALL_VOX, :] = 1
    lab[:, ny - WALL_VOX:, :] = 2
    path = os.path.join(img_dir, f"slab_{nx}x{ny}x{nz}.raw")
    return write_raw_image(path, lab, labelmap="pore=0;inorganic=1;organic=2")


def scene_of(name, box, image, patches, a_w, a_o, radius, steps, every, seed):
    y_wall = WALL_VOX * RC_PER_VOXEL
    lift = 0.3 * radius
    threads = [[box[0] / 4, y_wall + lift, 0.0], [3 * box[0] / 4, box[1] - y_wall - lift, 0.0]]
    pairs = {"default": {"A": -40.0, "B": 25.0, "gamma": 4.5, "rc": 1.0, "rd": 0.75},
             "water-oil": {"A": -20.0},
             "water-quartz": {"A": float(a_w)}, "oil-quartz": {"A": float(a_o)},
             "water-kerogen": {"A": float(a_o)}, "oil-kerogen": {"A": float(a_w)}}
    return {
        "name": name,
        "box": {"lo": [0.0, 0.0, 0.0], "hi": [float(v) for v in box], "periodic": [True, True, True]},
        "species": [{"name": "water", "mass": 1.0}, {"name": "oil", "mass": 1.0},
                    {"name": "quartz", "mass": 1.0, "frozen": True},
                    {"name": "kerogen", "mass": 1.0, "frozen": True}],
        "pairs": pairs,
        "density_kernel": "warren",
        "kT": 1.0,
        "effects": {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {}, "bounce_back": {}},
        "geometry": {"image": image, "rc_per_voxel": RC_PER_VOXEL, "flow_axis": "x",
                     "species": {"fluid": "oil", "inorganic": "quartz", "organic": "kerogen"},
                     "patches": {"file": patches, "seed": 1},
                     "fluid_species_regions": [
                         {"species": "water", "cylinder": {"axis": "z", "centre": c, "radius": float(radius)}}
                         for c in threads]},
        "initial": {"temperature": 1.0},
        "run": {"dt": 0.01, "steps": int(steps), "seed": int(seed)},
        "output": {"thermo": {"every": 100, "file": "thermo.csv"}, "summary": "summary.json",
                   "snapshot": {"every": int(every), "file": "snap"}, "progress": False},
    }


def face_fields(wd, start, box):
    """Per face (0 quartz, 1 kerogen mirrored), the list of (n_w, n_o) count fields of the snapshots
    from `start` on, each centred on that face's thread; and the number of water particles per face."""
    import glob
    import h5py
    Lx, Ly, _ = box
    nx, ny = int(round(Lx / BIN)), int(round(Ly / 2 / BIN))
    out = [[], []]
    counts = [[], []]
    for path in sorted(glob.glob(os.path.join(wd, "snap_*.h5"))):
        with h5py.File(path, "r") as f:
            if int(f.attrs["step"]) < start:
                continue
            p = f["particles"]
            sp, x = p["species"][:], p["position"][:]
        for face in (0, 1):
            y = x[:, 1] if face == 0 else Ly - x[:, 1]
            half = y < Ly / 2
            w, o = half & (sp == 0), half & (sp == 1)
            ang = 2 * math.pi * x[w, 0] / Lx
            xc = (math.atan2(np.sin(ang).mean(), np.cos(ang).mean()) / (2 * math.pi) * Lx) % Lx
            xs = (x[:, 0] - xc + Lx / 2) % Lx
            rng = [[0, Lx], [0, Ly / 2]]
            hw, _, _ = np.histogram2d(xs[w], y[w], bins=[nx, ny], range=rng)
            ho, _, _ = np.histogram2d(xs[o], y[o], bins=[nx, ny], range=rng)
            out[face].append((hw, ho))
            counts[face].append(int(w.sum()))
    return out, counts


def bulk_density(fields, box, y_wall):
    """Mean fluid density (water + oil) of the bins far from the thread (|x - L/2| > 0.35 L) and more
    than 2 rc from the wall, in that face's half of the pore: the oil's bulk."""
    tot = sum(f[0] + f[1] for f in fields)
    xc = (np.arange(tot.shape[0]) + 0.5) * BIN
    yc = (np.arange(tot.shape[1]) + 0.5) * BIN
    sel = (np.abs(xc - box[0] / 2) > 0.35 * box[0])[:, None] & (yc > y_wall + 2)[None, :]
    return float(tot[sel].mean() / (BIN * BIN * box[2] * len(fields)))


def fit_circle(px, py):
    """Circle through the points: algebraic (Kasa) start, then geometric least squares."""
    from scipy.optimize import least_squares
    A = np.stack([px, py, np.ones_like(px)], axis=1)
    c, *_ = np.linalg.lstsq(A, px ** 2 + py ** 2, rcond=None)
    x0, y0 = c[0] / 2, c[1] / 2
    r0 = math.sqrt(max(c[2] + x0 ** 2 + y0 ** 2, 1e-12))
    res = least_squares(lambda p: np.hypot(px - p[0], py - p[1]) - p[2], [x0, y0, r0])
    xc, yc, R = res.x
    return float(xc), float(yc), float(abs(R)), float(np.sqrt(np.mean(res.fun ** 2)))


def angle_of(fields, y_wall, skip):
    """(theta, circle (xc, yc, R), fitted points, rms, phi) of the summed fields of some snapshots."""
    import contourpy
    nw = sum(f[0] for f in fields)
    no = sum(f[1] for f in fields)
    tot = nw + no
    phi = np.where(tot > 0, (nw - no) / np.maximum(tot, 1), np.nan)
    xc = (np.arange(phi.shape[0]) + 0.5) * BIN
    yc = (np.arange(phi.shape[1]) + 0.5) * BIN
    keep = yc > y_wall + 0.25  # the wall's own bins (no fluid) are left out of the contour
    z = np.where(np.isfinite(phi), phi, -1.0)[:, keep]
    lines = contourpy.contour_generator(xc, yc[keep], z.T).lines(0.0)
    line = max(lines, key=len) if lines else np.zeros((0, 2))
    pts = line[line[:, 1] > y_wall + skip] if len(line) else line
    if len(pts) < 5:
        return float("nan"), (float("nan"),) * 3, pts, float("inf"), phi
    xcirc, ycirc, R, rms = fit_circle(pts[:, 0], pts[:, 1])
    c = (y_wall - ycirc) / R
    return math.degrees(math.acos(max(-1.0, min(1.0, c)))), (xcirc, ycirc, R), pts, rms, phi


def single_liquid_angles():
    """{A_sl: (theta, err)} of one liquid against its vapour (validation/walls/contact_angle.py)."""
    path = os.path.join(mdval.ROOT, "validation", "results", "walls", "contact_angle.csv")
    out = {}
    try:
        with open(path) as f:
            for row in csv.DictReader(f):
                out[float(row["A"])] = (float(row["theta"]), float(row["d_theta"]))
    except (OSError, KeyError, ValueError):
        pass
    return out


def young(a_w, a_o, single):
    """Young's water-oil angle (through the water) from the single-liquid angles, or None."""
    if a_w not in single or a_o not in single:
        return None
    tw, dw = single[a_w]
    to, do = single[a_o]
    c = GAMMA_LV * (math.cos(math.radians(tw)) - math.cos(math.radians(to))) / GAMMA_WO
    dc = GAMMA_LV / GAMMA_WO * math.hypot(math.sin(math.radians(tw)) * math.radians(dw),
                                          math.sin(math.radians(to)) * math.radians(do))
    th = math.degrees(math.acos(max(-1.0, min(1.0, c))))
    dth = math.degrees(dc / max(math.sqrt(max(1 - c * c, 0.0)), 1e-9))
    return th, dth, c


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="the ctest: one small run, A_w -35 / A_o -25 and swapped")
    ap.add_argument("--a-water", type=float, nargs="+", help="water-quartz A values, most attractive first "
                    "(default -35 -30 -20; --quick -35)")
    ap.add_argument("--a-oil", type=float, help="oil-quartz A (default -30; --quick -25)")
    ap.add_argument("--length", type=float, help="box length along x, rc (default 24; --quick 16)")
    ap.add_argument("--pore-height", type=float, help="pore height, rc (default 14; --quick 10)")
    ap.add_argument("--depth", type=float, default=3.0, help="box depth along z (the threads' axis), rc")
    ap.add_argument("--radius", type=float, help="threads' initial radius, rc (default 3.5; --quick 2.5)")
    ap.add_argument("--steps", type=int, help="steps in all (default 15000; --quick 3000)")
    ap.add_argument("--equil", type=int, help="steps before the averaging (default 3000; --quick 1500)")
    ap.add_argument("--every", type=int, help="snapshot interval (default 200; --quick 100)")
    ap.add_argument("--skip", type=float, default=1.0, help="contour points this far above the wall are fitted (rc)")
    ap.add_argument("--rms-max", type=float, default=0.15, help="largest rms of a good circle fit (rc)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--tag", help="name of the outputs (default wetting, --quick wetting_quick)")
    ap.add_argument("--outdir")
    ap.add_argument("--workdir")
    args = ap.parse_args()

    q = args.quick
    a_water = args.a_water or ([-35.0] if q else [-35.0, -30.0, -20.0])
    a_oil = args.a_oil if args.a_oil is not None else (-25.0 if q else -30.0)
    Lx = args.length or (16.0 if q else 24.0)
    hp = args.pore_height or (10.0 if q else 14.0)
    radius = args.radius or (2.5 if q else 3.5)
    steps = args.steps or (3000 if q else 15000)
    equil = args.equil if args.equil is not None else (1500 if q else 3000)
    every = args.every or (100 if q else 200)
    y_wall = WALL_VOX * RC_PER_VOXEL
    box = [Lx, hp + 2 * y_wall, args.depth]
    tag = args.tag or ("wetting" + ("_quick" if q else ""))
    outdir = args.outdir or mdval.out_dir("twophase")
    os.makedirs(outdir, exist_ok=True)
    base = os.environ.get("MDPORE_VALIDATION_OUT") or tempfile.gettempdir()
    workdir = os.path.abspath(args.workdir or os.path.join(base, tag + "_runs"))
    img_dir = os.path.join(workdir, "images")
    os.makedirs(img_dir, exist_ok=True)
    n = [int(round(v / RC_PER_VOXEL)) for v in box]
    if any(abs(v / RC_PER_VOXEL - k) > 1e-9 for v, k in zip(box, n)):
        sys.exit(f"wetting: the box {box} is not a whole number of {RC_PER_VOXEL} rc voxels")
    image = make_image(img_dir, *n)
    patches = os.path.join(workdir, f"patches-e{RC_PER_VOXEL:g}-d8-s1.h5")
    single = single_liquid_angles()
    print(f"box {box}, wall surfaces y = {y_wall} (quartz) and {box[1] - y_wall} (kerogen); runs in {workdir}",
          flush=True)
    results, t_all = [], time.time()
    for a_w in a_water:
        name = f"wet_Aw{a_w:g}_Ao{a_oil:g}"
        wd = os.path.join(workdir, name)
        scene = scene_of(name, box, image, patches, a_w, a_oil, radius, steps, every, args.seed)
        print(f"A_w = {a_w:g}, A_o = {a_oil:g}: {steps} steps, averaged from {equil} every {every} ...", flush=True)
        wall_s = run_or_reuse(scene, wd, args.np, args.reuse)
        fields, counts = face_fields(wd, equil, box)
        with open(os.path.join(wd, "summary.json")) as f:
            summ = json.load(f)
        pen, pen_max, pen_samples = penetrations(summ)
        for face, phase in enumerate(("quartz", "kerogen")):
            aw, ao = (a_w, a_oil) if face == 0 else (a_oil, a_w)
            theta, circ, pts, rms, phi = angle_of(fields[face], y_wall, args.skip)
            blocks = [angle_of(b, y_wall, args.skip)[0] for b in np.array_split(np.array(fields[face]), 4)]
            d_theta = float(np.std(blocks, ddof=1) / math.sqrt(len(blocks)))
            sens = [angle_of(fields[face], y_wall, s)[0] for s in (0.5, 1.5)]
            yg = young(aw, ao, single)
            n_bulk = bulk_density(fields[face], box, y_wall)
            r = dict(run=name, phase=phase, A_water=aw, A_oil=ao, theta=theta, d_theta=d_theta, blocks=blocks,
                     sens=sens, circle=circ, rms=rms, npts=len(pts), pts=pts, phi=phi,
                     n_water=[min(counts[face]), max(counts[face])], snapshots=len(fields[face]),
                     young=yg, n_bulk=n_bulk, pen=pen, pen_max=pen_max, pen_samples=pen_samples,
                     T=summ["thermo"]["T"]["mean"], wall_s=wall_s, particles=summ["particles"])
            r["fit_ok"] = bool(rms < args.rms_max and len(pts) >= 20 and 0 < theta < 180)
            results.append(r)
            print(f"  {phase}: A water/oil {aw:g}/{ao:g}: theta_w = {theta:.1f} +- {d_theta:.1f} deg (blocks "
                  f"{', '.join(f'{b:.1f}' for b in blocks)}; skip 0.5 / 1.5: {sens[0]:.1f} / {sens[1]:.1f}); "
                  f"R = {circ[2]:.2f}, centre - wall = {circ[1] - y_wall:+.2f}, rms {rms:.3f} over {len(pts)}; "
                  f"water in that half {r['n_water'][0]}..{r['n_water'][1]}"
                  + (f"; Young {yg[0]:.1f} +- {yg[1]:.1f}" if yg else ""), flush=True)
        print(f"  penetrations {pen} ({pen_samples} samples); T = {summ['thermo']['T']['mean']:.3f}; "
              f"run {wall_s:.0f} s", flush=True)

    quartz = [r for r in results if r["phase"] == "quartz"]
    kerogen = [r for r in results if r["phase"] == "kerogen"]
    checks = {f"circle fits good (rms < {args.rms_max:g} rc, >= 20 points, 0 < theta < 180)":
              all(r["fit_ok"] for r in results),
              "penetrations = 0": all(r["pen"] == 0 and r["pen_max"] == 0 and r["pen_samples"] > 0 for r in results)}
    if q:
        checks["water-wall A more attractive than oil-wall A: theta_w < 90 (quartz)"] = quartz[0]["theta"] < 90
        checks["swapped: theta_w > 90 (kerogen)"] = kerogen[0]["theta"] > 90
    else:
        checks["quartz: theta_w grows as A_water-quartz weakens"] = all(
            quartz[k + 1]["theta"] > quartz[k]["theta"] for k in range(len(quartz) - 1))
        checks["kerogen: theta_w falls as A_oil-kerogen weakens"] = all(
            kerogen[k + 1]["theta"] < kerogen[k]["theta"] for k in range(len(kerogen) - 1))
    for k, v in checks.items():
        print(f"{'ok  ' if v else 'FAIL'} {k}")
    write_outputs(outdir, tag, results, checks, args, box, y_wall, radius, steps, equil, every, a_oil)
    plot(outdir, tag, results, box, y_wall, args)
    ok = all(checks.values())
    print(f"wetting: {'pass' if ok else 'FAIL'} ({time.time() - t_all:.1f} s)")
    sys.exit(0 if ok else 1)


def write_outputs(outdir, tag, results, checks, args, box, y_wall, radius, steps, equil, every, a_oil):
    keep = ("run", "phase", "A_water", "A_oil", "theta", "d_theta", "blocks", "sens", "circle", "rms", "npts",
            "n_water", "snapshots", "young", "n_bulk", "pen", "pen_samples", "T", "wall_s", "particles", "fit_ok")
    data = {"box": box, "y_wall": y_wall, "radius": radius, "steps": steps, "equil": equil, "every": every,
            "gamma_lv": GAMMA_LV, "gamma_wo": GAMMA_WO, "checks": checks,
            "results": [{k: r[k] for k in keep} for r in results]}
    mdval.write_json(os.path.join(outdir, tag + ".json"), data)
    L = [f"# Contact angle of water against oil on a flat image wall ({'--quick' if args.quick else 'full run'})\n",
         f"Box {box[0]:g} x {box[1]:g} x {box[2]:g} rc, periodic; solid slab 2 rc thick across the y boundary, its "
         f"lower face quartz (inorganic voxels, y = {y_wall:g}), its upper face kerogen (organic, y = "
         f"{box[1] - y_wall:g}); walls from patches at density 8, bounce_back. Pore filled with oil at 6.2, two "
         f"water threads along z (radius {radius:g}, one per face, `geometry.fluid_species_regions`). "
         "A_ww = A_oo = -40, A_wo = -20, B = 25, rd = 0.75, gamma = 4.5 for all pairs. "
         f"{steps} steps, snapshots every {every} from step {equil}; phi = 0 contour of the summed fields more "
         f"than {args.skip:g} rc above the wall, circle fit; theta through the water. Error: 4 blocks. Young: "
         f"cos theta = {GAMMA_LV} (cos theta_w - cos theta_o) / {GAMMA_WO} from the single-liquid angles "
         "(validation/results/walls/contact_angle.csv).\n",
         "| solid | A water-wall | A oil-wall | theta_w (deg) | blocks | skip 0.5 / 1.5 rc | R (rc) | centre above wall "
         "| fit rms, points | Young (deg) | water (min..max) | run (s) |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        yg = r["young"]
        L.append(f"| {r['phase']} | {r['A_water']:g} | {r['A_oil']:g} | {r['theta']:.1f} ± {r['d_theta']:.1f} "
                 f"| {', '.join(f'{b:.0f}' for b in r['blocks'])} | {r['sens'][0]:.1f} / {r['sens'][1]:.1f} "
                 f"| {r['circle'][2]:.2f} | {r['circle'][1] - y_wall:+.2f} | {r['rms']:.3f}, {r['npts']} "
                 f"| {f'{yg[0]:.1f} ± {yg[1]:.1f}' if yg else '-'} | {r['n_water'][0]}..{r['n_water'][1]} "
                 f"| {r['wall_s']:.0f} |")
    pairs = {}
    for r in results:
        pairs.setdefault(r["run"], []).append(r)
    L.append("\nSymmetry (water <-> oil: the kerogen angle should be 180 minus the quartz angle): " + "; ".join(
        f"{v[0]['A_water']:g}/{v[0]['A_oil']:g}: {v[0]['theta']:.1f} + {v[1]['theta']:.1f} = "
        f"{v[0]['theta'] + v[1]['theta']:.1f} ± {math.hypot(v[0]['d_theta'], v[1]['d_theta']):.1f}"
        for v in pairs.values() if len(v) == 2))
    r0 = results[0]
    L.append(f"\nOil bulk density (far from the thread, > 2 rc from the wall): "
             f"{', '.join('%.2f' % r['n_bulk'] for r in results)} (in the order of the table).")
    L.append(f"\nParticles {r0['particles']}; T = {', '.join('%.3f' % r['T'] for r in results[::2])}; "
             f"penetrations {sum(r['pen'] for r in results[::2])}.")
    L.append("\nChecks: " + "; ".join(f"{k}: {'ok' if v else 'FAIL'}" for k, v in checks.items()))
    argv, skip_next = [], False
    for a in sys.argv[1:]:  # the command as run, less where its files went
        if skip_next or a == "--reuse":
            skip_next = False
            continue
        if a in ("--workdir", "--outdir"):
            skip_next = True
            continue
        argv.append(a)
    cmd = "/usr/bin/python3 " + " ".join(["validation/twophase/wetting.py"] + argv)
    L.append(f"\nRun time {sum(r['wall_s'] for r in results[::2]):.0f} s ({args.np} rank, shared 2-core machine). "
             f"Command: `{cmd}`\n")
    text = "\n".join(L)
    with open(os.path.join(outdir, tag + ".md"), "w") as f:
        f.write(text)
    print(text)


def plot(outdir, tag, results, box, y_wall, args):
    plt = mdval.pyplot()
    n = len(results)
    cols = 2
    rows = (n + 1) // 2
    fig, axs = plt.subplots(rows, cols, figsize=(5.6 * cols, 2.9 * rows), squeeze=False)
    for k, r in enumerate(results):
        ax = axs[k // cols][k % cols]
        im = ax.imshow(r["phi"].T, origin="lower", extent=[0, box[0], 0, box[1] / 2], cmap="coolwarm_r",
                       vmin=-1, vmax=1, aspect="equal")
        if len(r["pts"]):
            ax.plot(r["pts"][:, 0], r["pts"][:, 1], ".", ms=2, color="k", label="phi = 0, fitted")
        xc, yc, R = r["circle"]
        if np.isfinite(R):
            t = np.linspace(0, 2 * math.pi, 400)
            cx, cy = xc + R * np.cos(t), yc + R * np.sin(t)
            m = cy >= y_wall
            ax.plot(np.where(m, cx, np.nan), np.where(m, cy, np.nan), "g-", lw=1, label="fitted circle")
        ax.axhline(y_wall, color="orange", lw=0.8, label="wall surface")
        ax.set_title(f"{r['phase']}: A water {r['A_water']:g} / oil {r['A_oil']:g}: theta_w = {r['theta']:.1f} ± "
                     f"{r['d_theta']:.1f}", fontsize=8)
        ax.set_xlabel("x - x_thread + L/2 (rc)", fontsize=7)
        ax.set_ylabel("height (rc)", fontsize=7)
        ax.legend(fontsize=5, loc="upper right")
        fig.colorbar(im, ax=ax, shrink=0.8, label="phi (water +1)")
    for k in range(n, rows * cols):
        axs[k // cols][k % cols].axis("off")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, tag + ".png"), dpi=110)


if __name__ == "__main__":
    main()
