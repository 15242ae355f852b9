#!/usr/bin/python3
"""Walls from an image: plane Couette flow between a wall at rest and a moving wall.

A slit of h rc along y (rc_per_voxel 0.5) between two solid walls of --wall-voxels voxels, written
from numpy (raw + sidecar) with two solid labels: the lower wall organic (label 2, species `bottom`,
at rest), the upper wall inorganic (label 1, species `top`, `velocity: [U, 0, 0]`), both frozen, the
same fluid-wall A (-40) as the fluid's. Periodic in x, y, z (so the two walls are one solid slab
across the periodic y face; the builder keeps 3 voxel layers per face and drops the middle ones, so
the two species are 1 rc apart). Fluid mDPD A = -40, B = 25, rd = 0.75, gamma = 4.5, kT = 1,
dt = 0.01, fluid density 6.2; boundary --boundary (bounce_back, or wall_boundary+bounce_back); the
top wall's particles translate at U every step, carry v = U in the thermostat's pairs, and the
bounce-back reflects relative to the wall a particle hit (v' = 2u - v). `mdpore run` on --np ranks
writes a y profile (4 bins per rc) after a transient of max(2000, 6 tau) steps, tau = h^2 n / (pi^2
mu) the slowest mode of the start-up flow.

Analysis of the profile (bins of the fluid, between the voxel faces y_lo, y_hi):
  linear fit u = a + s (y - y_mid) over the core bins (more than --core-skip = 0.5 rc from the
  faces; weighted by the block errors): slope s, intercept a, chi^2 per degree of freedom;
  slip lengths: b_lo = y_lo - y0 with u(y0) = 0 (the wall at rest) and b_hi = y1 - y_hi with
  u(y1) = U (the moving wall): > 0 the linear profile reaches the wall's velocity inside the wall
  (slip), < 0 inside the fluid. Errors propagated from the fit's covariance;
  the same fit over all fluid bins (the contact layers included) is reported too;
  the shear stress the slope implies, mu_eff = sigma / s, is not measured (no stress column): the
  apparent viscosity is not reported;
  T: the thermo T of the mobile particles minus the flow's kinetic energy per degree of freedom.
Checks (exit 1 when one fails): the core profile is linear within its error bars (chi^2 per dof
of the linear fit below 1 + 3 sqrt(2 / dof), the 3-sigma bound of a chi^2 with that many dof);
penetrations = 0 in every thermo sample; |T_thermal - 1| <= 2%; the slope positive and within a
factor 2 of U / h (a sign or scale error would fail).
--quick: the ctest variant (h = 6, box 4 x 10 x 4, 1000 + 10000 steps, bounce_back, CPU). Its block
errors come from 1000 samples in at most 20 blocks and are underestimated (chi^2/dof 1.4 and 2.3 in
two runs of the same linear profile), so its chi^2 bound is 1 + 6 sqrt(2 / dof); R^2 of the linear
fit > 0.98 (--quick: 0.95) is checked too.

Full run (results in validation/results/walls/ as couette.{md,csv,png}):
    /usr/bin/python3 validation/walls/couette.py --widths 6 10 --boundary bounce_back wall_boundary+bounce_back
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

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import (BOUNDARIES, RC_PER_VOXEL, image_scene, mdval, pm, propagate, run_or_reuse,  # noqa: E402
                    wls, write_raw_image)

LABELS = "pore=0;inorganic=1;organic=2"


def make_image(workdir, width_vox, wall_vox, length_vox, depth_vox):
    """Organic (2) below, pore, inorganic (1) above, along y; uniform along x and z."""
    ny = width_vox + 2 * wall_vox
    lab = np.zeros((length_vox, ny, depth_vox), dtype=np.uint8)
    lab[:, :wall_vox, :] = 2
    lab[:, wall_vox + width_vox:, :] = 1
    path = os.path.join(workdir, f"couette_w{width_vox}_l{length_vox}_d{depth_vox}.raw")
    return write_raw_image(path, lab, LABELS)


def scene_for(name, box, image, patches, U, steps, start, every, bins, seed, patch_seed, boundary):
    s = image_scene(name, box, image, patches, steps=steps, seed=seed, patch_seed=patch_seed, boundary=boundary,
                    profile={"axis": "y", "bins": int(bins), "every": int(every), "start": int(start)})
    s["species"] = [{"name": "liquid", "mass": 1.0},
                    {"name": "bottom", "mass": 1.0, "frozen": True},
                    {"name": "top", "mass": 1.0, "frozen": True, "velocity": [float(U), 0.0, 0.0]}]
    s["pairs"] = {"default": {"A": -40.0, "B": 25.0, "gamma": 4.5, "rc": 1.0, "rd": 0.75}}
    s["geometry"]["species"] = {"fluid": "liquid", "organic": "bottom", "inorganic": "top"}
    s["geometry"]["labels"] = LABELS.replace(";", ",")
    return s


def linear_fit(y, u, du):
    p, cov, chi2, model = wls(np.stack([np.ones_like(y), y], axis=1), u, du)
    return p, cov, chi2, len(y) - 2


def analyse(wd, h, y_lo, y_hi, U, box, core_skip, sigmas=3.0):
    prof = mdval.read_table(os.path.join(wd, "profile.csv"))
    summ = json.load(open(os.path.join(wd, "summary.json")))
    y = prof["y"]
    width = y[1] - y[0]
    fluid = (y > y_lo) & (y < y_hi)
    ym = 0.5 * (y_lo + y_hi)
    xi = y[fluid] - ym
    u, du = prof["vx"][fluid], prof["vx_err"][fluid]
    n_b = prof["density_liquid"][fluid]
    d_wall = np.minimum(y[fluid] - y_lo, y_hi - y[fluid])
    core = d_wall > core_skip
    a = h / 2
    r = {"n_centre": float(n_b[np.abs(xi) <= h / 6 + 1e-9].mean())}
    for tag, sel in (("core", core), ("all", np.ones_like(core))):
        p, cov, chi2, dof = linear_fit(xi[sel], u[sel], du[sel])
        # slip: u(y0) = 0 at the lower wall, u(y1) = U at the upper wall (xi = y - y_mid)
        (b_lo, b_hi), (db_lo, db_hi) = propagate(lambda q: [-a + q[0] / q[1], (U - q[0]) / q[1] - a], p, cov)
        model = p[0] + p[1] * xi[sel]
        r[f"R2_{tag}"] = float(1 - np.sum((u[sel] - model) ** 2) / np.sum((u[sel] - u[sel].mean()) ** 2))
        r.update({f"a_{tag}": float(p[0]), f"a_{tag}_err": float(math.sqrt(cov[0, 0])),
                  f"s_{tag}": float(p[1]), f"s_{tag}_err": float(math.sqrt(cov[1, 1])),
                  f"chi2_{tag}": chi2, f"dof_{tag}": dof, f"b_lo_{tag}": float(b_lo), f"b_lo_{tag}_err": float(db_lo),
                  f"b_hi_{tag}": float(b_hi), f"b_hi_{tag}_err": float(db_hi), f"p_{tag}": p})
    r["chi2_bound"] = 1 + sigmas * math.sqrt(2 / max(1, r["dof_core"]))
    r["s_ideal"] = U / h
    T, dT = summ["thermo"]["T"]["mean"], summ["thermo"]["T"]["err"]
    Nb = n_b * box[0] * box[2] * width
    ke_flow = 0.5 * np.sum(Nb * (prof["vx"][fluid] ** 2 + prof["vy"][fluid] ** 2 + prof["vz"][fluid] ** 2))
    r.update(T=T, T_err=dT, T_thermal=T - 2 * ke_flow / (3 * (float(np.sum(Nb)) - 1)))
    pen = summ.get("penetrations", {})
    r["penetrations"] = int(pen.get("samples_with_penetration", -1))
    r["pen_max"] = int(pen.get("max_particles", -1))
    r["pen_samples"] = int(pen.get("samples", 0))
    r["particles"] = summ["particles"]
    r["profile"] = dict(xi=xi, u=u, du=du, core=core, xi_all=y - ym, n_all=prof["density_liquid"])
    return r


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="CI variant: h = 6, short run, bounce_back only")
    ap.add_argument("--widths", type=float, nargs="+", help="slit widths h in rc (multiples of 0.5; default 6 10)")
    ap.add_argument("--boundary", nargs="+", choices=BOUNDARIES, help="boundaries to run (default bounce_back "
                    "and wall_boundary+bounce_back; --quick bounce_back)")
    ap.add_argument("--U", type=float, default=0.5, help="velocity of the upper wall along x (default 0.5)")
    ap.add_argument("--steps", type=int, help="steps averaged into the profile (default 50000; --quick 10000)")
    ap.add_argument("--equil", type=int, help="transient steps (default max(2000, 6 tau); --quick 1000)")
    ap.add_argument("--length", type=float, default=6.0, help="box length along x, rc (default 6; --quick 4)")
    ap.add_argument("--depth", type=float, default=4.0, help="box depth along z, rc (default 4)")
    ap.add_argument("--wall-voxels", type=int, default=4, help="solid voxels of each wall (default 4 = 2 rc)")
    ap.add_argument("--bins-per-rc", type=int, default=4)
    ap.add_argument("--every", type=int, default=10)
    ap.add_argument("--core-skip", type=float, default=0.5, help="the linear fit leaves out bins this close to a face")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--patch-seed", type=int, default=1)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--reuse", action="store_true", help="analyse existing runs of the same scenes again")
    ap.add_argument("--outdir", help="table + PNG (default $MDPORE_VALIDATION_OUT/walls or validation/results/walls)")
    ap.add_argument("--workdir", help="run folders (default <$MDPORE_VALIDATION_OUT or $TMPDIR>/couette_runs)")
    args = ap.parse_args()
    q = args.quick
    widths = args.widths or ([6.0] if q else [6.0, 10.0])
    boundaries = args.boundary or (["bounce_back"] if q else ["bounce_back", "wall_boundary+bounce_back"])
    steps = args.steps or (10000 if q else 50000)
    length = 4.0 if (q and args.length == 6.0) else args.length
    tag = "couette" + ("_quick" if q else "")
    outdir = args.outdir or mdval.out_dir("walls")
    os.makedirs(outdir, exist_ok=True)
    base = os.environ.get("MDPORE_VALIDATION_OUT") or tempfile.gettempdir()
    workdir = os.path.abspath(args.workdir or os.path.join(base, tag + "_runs"))
    os.makedirs(workdir, exist_ok=True)
    print(f"runs in {workdir}", flush=True)

    def voxels(v, what):
        k = v / RC_PER_VOXEL
        if abs(k - round(k)) > 1e-9 or k < 1:
            sys.exit(f"couette: {what} {v} rc is not a whole number of {RC_PER_VOXEL} rc voxels")
        return int(round(k))

    lv, dv = voxels(length, "--length"), voxels(args.depth, "--depth")
    patches = os.path.join(workdir, f"patches-e{RC_PER_VOXEL:g}-d8-s{args.patch_seed}.h5")
    results, t_all = [], time.time()
    for boundary in boundaries:
        for h in widths:
            wv, wall = voxels(h, "width"), args.wall_voxels
            tau = h * h * 6.2 / (math.pi ** 2 * 5.41)
            equil = args.equil if args.equil is not None else (
                1000 if q else max(2000, int(math.ceil(6 * tau / 0.01 / 1000)) * 1000))
            name = f"couette_h{h:g}_{boundary.replace('+', '_')}"
            wd = os.path.join(workdir, name)
            image = make_image(workdir, wv, wall, lv, dv)
            box = [length, (wv + 2 * wall) * RC_PER_VOXEL, args.depth]
            y_lo, y_hi = wall * RC_PER_VOXEL, (wall + wv) * RC_PER_VOXEL
            scene = scene_for(name, box, image, patches, args.U, equil + steps, equil, args.every,
                              int(round(box[1] * args.bins_per_rc)), args.seed, args.patch_seed, boundary)
            print(f"h = {h:g}, {boundary}: box {box}, U = {args.U}, {equil} + {steps} steps ...", flush=True)
            wall_s = run_or_reuse(scene, wd, args.np, args.reuse)
            r = analyse(wd, h, y_lo, y_hi, args.U, box, args.core_skip, 6.0 if q else 3.0)
            r.update(h=h, boundary=boundary, U=args.U, equil=equil, steps=steps, wall_s=wall_s, box=box)
            r["checks"] = {
                f"linear within error bars (core chi2/dof < 1 + {6 if q else 3} sqrt(2/dof))":
                    r["chi2_core"] < r["chi2_bound"],
                f"linear fit explains > {0.95 if q else 0.98:g} of the core variance (R^2)":
                    r["R2_core"] > (0.95 if q else 0.98),
                "penetrations = 0": r["penetrations"] == 0 and r["pen_max"] == 0 and r["pen_samples"] > 0,
                "|T_thermal - 1| <= 2%": abs(r["T_thermal"] - 1.0) <= 0.02,
                "slope within 0.5-2 x U / h": 0.5 <= r["s_core"] / r["s_ideal"] <= 2.0,
            }
            results.append(r)
            for k, v in r["checks"].items():
                print(f"  {'ok  ' if v else 'FAIL'} {k}", flush=True)
            print(f"  slope {pm(r['s_core'], r['s_core_err'], 5)} (U / h = {r['s_ideal']:.5f}), chi2/dof "
                  f"{r['chi2_core']:.2f} (bound {r['chi2_bound']:.2f}); slip lo / hi "
                  f"{pm(r['b_lo_core'], r['b_lo_core_err'])} / {pm(r['b_hi_core'], r['b_hi_core_err'])} rc; "
                  f"T {r['T']:.4f} (thermal {r['T_thermal']:.4f}); penetrations {r['penetrations']}; "
                  f"run {wall_s:.1f} s", flush=True)
    write_tables(outdir, tag, results, args, widths, boundaries, steps)
    plot(outdir, tag, results)
    ok = all(all(r["checks"].values()) for r in results)
    print(f"couette: {'pass' if ok else 'FAIL'} ({time.time() - t_all:.1f} s)")
    sys.exit(0 if ok else 1)


def verdict_of(r):
    bad = [k for k, v in r["checks"].items() if not v]
    return "pass" if not bad else "FAIL: " + "; ".join(bad)


def write_tables(outdir, tag, results, args, widths, boundaries, steps):
    cols = ["boundary", "h", "U", "equil", "steps", "particles", "n_centre", "s_core", "s_core_err", "s_ideal",
            "a_core", "a_core_err", "chi2_core", "dof_core", "chi2_bound", "R2_core", "b_lo_core", "b_lo_core_err", "b_hi_core",
            "b_hi_core_err", "s_all", "s_all_err", "chi2_all", "b_lo_all", "b_lo_all_err", "b_hi_all",
            "b_hi_all_err", "T", "T_err", "T_thermal", "penetrations", "pen_samples", "wall_s", "verdict"]
    with open(os.path.join(outdir, tag + ".csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in results:
            vals = dict(r, verdict=verdict_of(r))
            w.writerow([f"{vals.get(c):.6g}" if isinstance(vals.get(c), float) else vals.get(c, "") for c in cols])
    L = [f"# Plane Couette flow in an image slit, one wall moving ({'--quick' if args.quick else 'full run'})\n",
         f"Slit of h rc between walls of {args.wall_voxels} voxels at rc_per_voxel {RC_PER_VOXEL} (lower: organic, "
         f"species `bottom`, at rest; upper: inorganic, species `top`, velocity [{args.U:g}, 0, 0]; both frozen, "
         f"fluid-wall A = -40 as fluid-fluid), box {results[0]['box'][0]:g} x (h + {2 * args.wall_voxels * RC_PER_VOXEL:g}) "
         f"x {args.depth:g} rc, periodic. mDPD A = -40, B = 25, rd = 0.75, gamma = 4.5, kT = 1, dt = 0.01, fluid "
         f"6.2 per rc^3 of pore; {args.np} ranks. Profile along y, {args.bins_per_rc} bins per rc, every "
         f"{args.every} steps after the transient.\n",
         f"Linear fit u = a + s (y - y_mid), weighted by the block errors, over the core bins (more than "
         f"{args.core_skip:g} rc from the voxel faces) and over all fluid bins. Slip length b: how far beyond the "
         "wall face the linear profile reaches that wall's velocity (> 0: inside the wall, slip; < 0: inside the "
         "fluid). chi2 = chi^2 per degree of freedom; linear within its error bars when chi2 < 1 + 3 sqrt(2 / dof). "
         "T thermal = thermo T minus the flow's kinetic energy.\n",
         "| boundary | h (rc) | steps | slope s (core) | U / h | s h / U | chi2 core (bound) | R^2 core | slip b lo (rest) | "
         "slip b hi (moving) | s, all bins | chi2 all | b lo / hi, all bins | T / T thermal | penetrations (samples) "
         "| run (s) | verdict |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        L.append(f"| {r['boundary']} | {r['h']:g} | {r['equil']} + {r['steps']} | {pm(r['s_core'], r['s_core_err'], 5)} "
                 f"| {r['s_ideal']:.5f} | {r['s_core'] / r['s_ideal']:.3f} | {r['chi2_core']:.2f} ({r['chi2_bound']:.2f}) "
                 f"| {r['R2_core']:.4f} "
                 f"| {pm(r['b_lo_core'], r['b_lo_core_err'])} | {pm(r['b_hi_core'], r['b_hi_core_err'])} "
                 f"| {pm(r['s_all'], r['s_all_err'], 5)} | {r['chi2_all']:.2f} "
                 f"| {r['b_lo_all']:+.3f} ± {r['b_lo_all_err']:.3f} / {r['b_hi_all']:+.3f} ± {r['b_hi_all_err']:.3f} "
                 f"| {r['T']:.4f} / {r['T_thermal']:.4f} | {r['penetrations']} ({r['pen_samples']}) | {r['wall_s']:.0f} "
                 f"| {verdict_of(r)} |")
    L.append(f"\nCommand: `/usr/bin/python3 validation/walls/couette.py{' --quick' if args.quick else ''} --widths "
             f"{' '.join(f'{h:g}' for h in widths)} --boundary {' '.join(boundaries)} --steps {steps}`\n")
    text = "\n".join(L)
    with open(os.path.join(outdir, tag + ".md"), "w") as f:
        f.write(text)
    print(text)


def plot(outdir, tag, results):
    plt = mdval.pyplot()
    fig, axs = plt.subplots(1, len(results), figsize=(5 * len(results), 4.2), squeeze=False)
    for k, r in enumerate(results):
        ax, p, a = axs[0][k], r["profile"], r["h"] / 2
        core = p["core"]
        ax.errorbar(p["xi"][core], p["u"][core], yerr=p["du"][core], fmt=".", color="k", label="core bins")
        ax.errorbar(p["xi"][~core], p["u"][~core], yerr=p["du"][~core], fmt="x", color="r", label="contact bins")
        x = np.linspace(-a - 0.3, a + 0.3, 50)
        pc = r["p_core"]
        ax.plot(x, pc[0] + pc[1] * x, "-", lw=1, label=f"fit: b = {r['b_lo_core']:+.2f} / {r['b_hi_core']:+.2f} rc")
        ax.plot(x, r["U"] * (x + a) / (2 * a), "--", color="grey", lw=0.8, label="no slip at the faces")
        for s in (-a, a):
            ax.axvline(s, color="grey", lw=0.8)
        ax.set_title(f"h = {r['h']:g} rc, {r['boundary']}", fontsize=9)
        ax.set_xlabel("y - y_mid (rc); faces at the grey lines")
        ax.set_ylabel("u_x")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, tag + ".png"), dpi=120)


if __name__ == "__main__":
    main()
