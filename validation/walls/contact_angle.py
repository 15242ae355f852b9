#!/usr/bin/python3
"""Walls from an image: the static contact angle of an mDPD droplet on a flat image
wall for several fluid-wall attractions A_sl (physics.md section 2: with A_ll = -40, A_sl = -35 wets,
-30 is about 90 degrees, -20 does not wet; the paper's slit, section 4.2).

Geometry, by the user's path: `mdpore image make slit --width 20 --wall 2` (rc_per_voxel 0.5; periodic,
so the two 1 rc walls make one flat solid 2 rc thick with pore space 10 rc high above it), a scene with
`geometry:` (walls from the patch database at density 8, the builder's default thickness) and
`geometry.fluid_region` putting the liquid only in a block on the wall: --block-width x --block-height
rc, the whole depth along z. z is periodic and short, so the droplet is a cylinder along z with a
straight contact line (no line tension), its cross-section a circular cap in the x-y plane. Fluid:
mDPD A = -40, B = 25, rd = 0.75, gamma = 4.5, kT = 1, dt = 0.01, liquid density 6.2 in the block;
fluid-wall A = A_sl, B = 25, rd = 0.75 (B and rd common to all pairs, Warren's no-go rule); boundary
effect --boundary (default bounce_back; wall_boundary once it exists); no body force.

Analysis: HDF5 snapshots every --every steps after --equil steps; each snapshot's liquid is shifted so
that its centre of mass along x (circular mean: x is periodic) sits mid-box, then binned in (x, y)
(bins of 0.25 rc, all of z) and averaged over the snapshots: the time-averaged density field.
n_l = liquid density in the droplet core (|x - x_c| < 1.5, 1-2 rc above the wall); the half-density
isoline rho = n_l / 2 (contourpy, the longest line) is cut to the points more than --skip (1 rc) above
the wall surface (the voxel face: the first layer is structured by the wall), and a circle is fitted
to them (algebraic fit, then geometric least squares). Contact angle through the liquid:
cos(theta) = (y_wall - y_centre) / R. Error: the fit repeated on 4 consecutive blocks of snapshots,
standard error of their angles. Also reported: theta with --skip 0.5 and 1.5 (sensitivity to the cut).
Checks (exit 1 when one fails): penetrations = 0; every fit good (rms distance of the isoline points to
the circle < 0.15 rc, at least 20 points, 0 < theta < 180); the angles ordered as the attractions
(more attraction, smaller angle, beyond their errors: theta_k+1 - theta_k > 0).
The solid is one slab across the periodic y boundary; a droplet that leaves its face (the block's
first steps are violent: random positions next to vacuum) may cross the pore and hang from the other
face: those snapshots are mirrored in y and counted (table: snapshots on the upper face, face changes).
--quick: shorter runs (a smoke test, 10 minutes on a busy 2-core machine: not registered in ctest, as
nothing under ~30 s is meaningful here).

Full run (results in validation/results/walls/):
    nice -n 10 /usr/bin/python3 validation/walls/contact_angle.py
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import (BOUNDARIES, RC_PER_VOXEL, image_scene, mdval, penetrations, read_snapshots,  # noqa: E402
                    run_or_reuse)

BIN = 0.25


def make_image(img_dir, length_vox, pore_vox, wall_vox, depth_vox):
    path = os.path.join(img_dir, f"flat_l{length_vox}_p{pore_vox}_w{wall_vox}_d{depth_vox}.h5")
    cmd = [mdval.mdpore_binary(), "image", "make", "slit", "--width", str(pore_vox), "--wall", str(wall_vox),
           "--length", str(length_vox), "--depth", str(depth_vox), "-o", path]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {p.stderr}")
    return path, json.loads(p.stdout)


def density_field(wd, start, box, y_wall):
    """Time-averaged fields of the snapshots from `start` on, and on which face of the solid the
    droplet sat in every snapshot of the run (0: the lower face, 1: the upper one, across the pore).
    The solid is one slab across the periodic y boundary, so a droplet that left its face during the
    violent first steps (a random block next to vacuum) and crossed the pore hangs from the upper
    face: such snapshots are mirrored (y -> Ly - y), which maps that face onto the lower one."""
    steps, snaps, _ = read_snapshots(wd, 0)
    Lx, Ly, Lz = box
    nx, ny = int(round(Lx / BIN)), int(round(Ly / BIN))
    fields, sides = [], []
    for step, (x, _v) in zip(steps, snaps):
        side = int(np.mean(x[:, 1]) > Ly / 2)
        sides.append(side)
        if step < start:
            continue
        if side:
            x = x.copy()
            x[:, 1] = Ly - x[:, 1]
        above = x[:, 1] >= y_wall
        ang = 2 * math.pi * x[above, 0] / Lx
        xc = (math.atan2(np.sin(ang).mean(), np.cos(ang).mean()) / (2 * math.pi) * Lx) % Lx
        xs = (x[:, 0] - xc + Lx / 2) % Lx
        H, _, _ = np.histogram2d(xs, x[:, 1], bins=[nx, ny], range=[[0, Lx], [0, Ly]])
        fields.append(H / (BIN * BIN * Lz))
    return np.array(sides), np.array(fields)


def fit_circle(px, py):
    """Circle through the points: algebraic (Kasa) start, then geometric least squares."""
    from scipy.optimize import least_squares
    A = np.stack([px, py, np.ones_like(px)], axis=1)
    c, *_ = np.linalg.lstsq(A, px ** 2 + py ** 2, rcond=None)
    x0, y0 = c[0] / 2, c[1] / 2
    r0 = math.sqrt(max(c[2] + x0 ** 2 + y0 ** 2, 1e-12))
    res = least_squares(lambda p: np.hypot(px - p[0], py - p[1]) - p[2], [x0, y0, r0])
    xc, yc, R = res.x
    rms = float(np.sqrt(np.mean(res.fun ** 2)))
    return float(xc), float(yc), float(abs(R)), rms


def isoline(rho, box, level):
    import contourpy
    xc = (np.arange(rho.shape[0]) + 0.5) * BIN
    yc = (np.arange(rho.shape[1]) + 0.5) * BIN
    gen = contourpy.contour_generator(xc, yc, rho.T)
    lines = gen.lines(level)
    if not lines:
        return np.zeros((0, 2))
    return max(lines, key=len)


def angle_of(rho, box, y_wall, skip):
    """(theta in degrees, circle, points used, rms, n_l) of one time-averaged density field."""
    Lx = box[0]
    xc = (np.arange(rho.shape[0]) + 0.5) * BIN
    yc = (np.arange(rho.shape[1]) + 0.5) * BIN
    core = (np.abs(xc - Lx / 2) < 1.5)[:, None] & ((yc > y_wall + 1) & (yc < y_wall + 2))[None, :]
    n_l = float(rho[core].mean())
    line = isoline(rho, box, 0.5 * n_l)
    pts = line[line[:, 1] > y_wall + skip] if len(line) else line
    if len(pts) < 5:
        return float("nan"), (float("nan"),) * 3, pts, float("inf"), n_l
    xcirc, ycirc, R, rms = fit_circle(pts[:, 0], pts[:, 1])
    c = (y_wall - ycirc) / R
    theta = math.degrees(math.acos(max(-1.0, min(1.0, c))))
    return theta, (xcirc, ycirc, R), pts, rms, n_l


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="CI variant: smaller droplet, shorter runs")
    ap.add_argument("--a-wall", type=float, nargs="+", default=[-35.0, -30.0, -20.0],
                    help="fluid-wall A values, most attractive first (default -35 -30 -20)")
    ap.add_argument("--boundary", choices=BOUNDARIES, default="bounce_back")
    ap.add_argument("--length", type=float, help="box length along x, rc (default 16)")
    ap.add_argument("--depth", type=float, default=4.0, help="box depth along z (the droplet's axis), rc")
    ap.add_argument("--pore-height", type=float, default=10.0, help="pore space above the wall, rc (default 10)")
    ap.add_argument("--block-width", type=float, help="initial liquid block along x, rc (default 6)")
    ap.add_argument("--block-height", type=float, help="initial liquid block height, rc (default 3)")
    ap.add_argument("--steps", type=int, help="steps in all (default 14000; --quick 6000)")
    ap.add_argument("--equil", type=int, help="steps before the averaging (default 4000; --quick 3000)")
    ap.add_argument("--every", type=int, help="snapshot interval (default 250)")
    ap.add_argument("--skip", type=float, default=1.0, help="isoline points this far above the wall are fitted (rc)")
    ap.add_argument("--rms-max", type=float, default=0.15, help="largest rms of a good circle fit (rc)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--patch-seed", type=int, default=1)
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--outdir")
    ap.add_argument("--workdir")
    args = ap.parse_args()

    q = args.quick
    Lx = args.length or 16.0
    bw = args.block_width or 6.0
    bh = args.block_height or 3.0
    steps = args.steps or (6000 if q else 14000)
    equil = args.equil if args.equil is not None else (3000 if q else 4000)
    every = args.every or 250
    tag = "contact_angle" + ("_quick" if q else "") + ("" if args.boundary == "bounce_back" else "_" + args.boundary)
    outdir = args.outdir or mdval.out_dir("walls")
    os.makedirs(outdir, exist_ok=True)
    base = os.environ.get("MDPORE_VALIDATION_OUT") or tempfile.gettempdir()
    workdir = os.path.abspath(args.workdir or os.path.join(base, tag + "_runs"))
    img_dir = os.path.join(workdir, "images")
    os.makedirs(img_dir, exist_ok=True)
    patches = os.path.join(workdir, f"patches-e{RC_PER_VOXEL:g}-d8-s{args.patch_seed}.h5")

    def vox(v, what):
        k = v / RC_PER_VOXEL
        if abs(k - round(k)) > 1e-9 or k < 1:
            sys.exit(f"contact_angle: {what} {v} rc is not a whole number of {RC_PER_VOXEL} rc voxels")
        return int(round(k))

    wall_vox = 2
    image, info = make_image(img_dir, vox(Lx, "--length"), vox(args.pore_height, "--pore-height"), wall_vox,
                             vox(args.depth, "--depth"))
    box = [Lx, args.pore_height + 2 * wall_vox * RC_PER_VOXEL, args.depth]
    y_wall = wall_vox * RC_PER_VOXEL
    region = ([Lx / 2 - bw / 2, y_wall, 0.0], [Lx / 2 + bw / 2, y_wall + bh, args.depth])
    print(f"image {info['dims']}, box {box}, wall surface y = {y_wall}, liquid block {region}; runs in {workdir}",
          flush=True)
    results, t_all = [], time.time()
    for a in args.a_wall:
        name = f"drop_A{a:g}"
        wd = os.path.join(workdir, name)
        scene = image_scene(name, box, image, patches, steps=steps, seed=args.seed, patch_seed=args.patch_seed,
                            a_wall=a, boundary=args.boundary, fluid_region=region, snapshot=every, thermo_every=100)
        print(f"A_sl = {a:g}: {steps} steps, averaged from {equil} every {every} ...", flush=True)
        wall_s = run_or_reuse(scene, wd, args.np, args.reuse)
        sides, fields = density_field(wd, equil, box, y_wall)
        rho = fields.mean(axis=0)
        theta, circ, pts, rms, n_l = angle_of(rho, box, y_wall, args.skip)
        blocks = [angle_of(f.mean(axis=0), box, y_wall, args.skip)[0] for f in np.array_split(fields, 4)]
        d_theta = float(np.std(blocks, ddof=1) / math.sqrt(len(blocks)))
        sens = [angle_of(rho, box, y_wall, s)[0] for s in (0.5, 1.5)]
        with open(os.path.join(wd, "summary.json")) as f:
            summ = json.load(f)
        pen, pen_max, pen_samples = penetrations(summ)
        h_drop = circ[1] + circ[2] - y_wall
        base_w = 2 * math.sqrt(max(circ[2] ** 2 - (y_wall - circ[1]) ** 2, 0.0))
        r = dict(A=a, sides=sides, hops=int(np.sum(sides[1:] != sides[:-1])), upper=int(sides[-len(fields):].sum()),
                 theta=theta, d_theta=d_theta, blocks=blocks, sens=sens, circle=circ, rms=rms, npts=len(pts),
                 n_l=n_l, rho=rho, pts=pts, h_drop=h_drop, base=base_w, snapshots=len(fields), pen=pen,
                 pen_max=pen_max, pen_samples=pen_samples, T=summ["thermo"]["T"]["mean"], wall_s=wall_s,
                 particles=summ["particles"])
        r["fit_ok"] = (rms < args.rms_max and len(pts) >= 20 and 0 < theta < 180)
        results.append(r)
        print(f"  theta = {theta:.1f} +- {d_theta:.1f} deg (blocks {', '.join(f'{b:.1f}' for b in blocks)}; skip 0.5 / "
              f"1.5: {sens[0]:.1f} / {sens[1]:.1f}); circle R = {circ[2]:.2f}, centre y - wall = {circ[1] - y_wall:+.2f}, "
              f"rms {rms:.3f} rc over {len(pts)} points; n_l = {n_l:.2f}; on the upper face {r['upper']} of "
              f"{len(fields)}, face changes {r['hops']}; penetrations {pen} ({pen_samples}); "
              f"T = {r['T']:.3f}; run {wall_s:.0f} s", flush=True)

    checks = {"penetrations = 0": all(r["pen"] == 0 and r["pen_max"] == 0 and r["pen_samples"] > 0 for r in results),
              f"circle fits good (rms < {args.rms_max:g} rc, >= 20 points, 0 < theta < 180)":
                  all(r["fit_ok"] for r in results),
              "angles ordered as the attractions (theta increases as A_sl weakens)":
                  all(results[k + 1]["theta"] > results[k]["theta"] for k in range(len(results) - 1))}
    if len(results) < 2:
        checks.pop("angles ordered as the attractions (theta increases as A_sl weakens)")
    for k, v in checks.items():
        print(f"{'ok  ' if v else 'FAIL'} {k}")
    write_table(outdir, tag, results, checks, args, box, region, y_wall, Lx, steps, equil, every)
    plot(outdir, tag, results, box, y_wall, args)
    ok = all(checks.values())
    print(f"contact_angle: {'pass' if ok else 'FAIL'} ({time.time() - t_all:.1f} s)")
    sys.exit(0 if ok else 1)


def write_table(outdir, tag, results, checks, args, box, region, y_wall, Lx, steps, equil, every):
    import csv
    cols = ["A", "theta", "d_theta", "theta_skip05", "theta_skip15", "R", "yc_minus_wall", "rms", "npts", "n_l",
            "h_drop", "base", "snapshots", "particles", "T", "pen", "pen_samples", "wall_s"]
    with open(os.path.join(outdir, tag + ".csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in results:
            w.writerow([r["A"], f"{r['theta']:.3f}", f"{r['d_theta']:.3f}", f"{r['sens'][0]:.3f}", f"{r['sens'][1]:.3f}",
                        f"{r['circle'][2]:.4f}", f"{r['circle'][1] - y_wall:.4f}", f"{r['rms']:.4f}", r["npts"],
                        f"{r['n_l']:.4f}", f"{r['h_drop']:.3f}", f"{r['base']:.3f}", r["snapshots"], r["particles"],
                        f"{r['T']:.4f}", r["pen"], r["pen_samples"], f"{r['wall_s']:.1f}"])
    L = [f"# Static contact angle of a cylindrical mDPD droplet on a flat image wall, boundary `{args.boundary}` "
         f"({'--quick' if args.quick else 'full run'})\n",
         f"Wall: `mdpore image make slit --wall 2` at rc_per_voxel {RC_PER_VOXEL} (periodic: one flat solid 2 rc thick, "
         f"surface at y = {y_wall:g}), patches at density 8, builder's default thickness. Box {box[0]:g} x {box[1]:g} x "
         f"{box[2]:g} rc, periodic; the droplet is a cylinder along z. Liquid: mDPD A_ll = -40, B = 25, rd = 0.75, "
         f"gamma = 4.5, kT = 1, dt = 0.01, started as a block `geometry.fluid_region` = {region[0]} .. {region[1]} at "
         f"density 6.2; fluid-wall A = A_sl (B, rd, gamma common). {steps} steps, snapshots every {every} from step "
         f"{equil} averaged (centred on the droplet's x centre of mass), bins 0.25 rc. Angle from a circle fitted "
         f"to the rho = n_l / 2 isoline more than {args.skip:g} rc above the wall; cos(theta) = (y_wall - y_c) / R. "
         "Error: standard error of the angles of 4 blocks of snapshots.\n",
         "| A_sl | theta (deg) | blocks | theta, skip 0.5 / 1.5 rc | circle R (rc) | centre above wall (rc) "
         "| fit rms (rc), points | n_l | height / base (rc) | snapshots averaged (on the upper face) | face changes "
         "| T | penetrations (samples) | run (s) |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        L.append(f"| {r['A']:g} | {r['theta']:.1f} ± {r['d_theta']:.1f} | {', '.join(f'{b:.0f}' for b in r['blocks'])} "
                 f"| {r['sens'][0]:.1f} / {r['sens'][1]:.1f} | {r['circle'][2]:.2f} | {r['circle'][1] - y_wall:+.2f} "
                 f"| {r['rms']:.3f}, {r['npts']} | {r['n_l']:.2f} | {r['h_drop']:.2f} / {r['base']:.2f} "
                 f"| {r['snapshots']} ({r['upper']}) | {r['hops']} | {r['T']:.3f} "
                 f"| {r['pen']} ({r['pen_samples']}) | {r['wall_s']:.0f} |")
    L.append("\nChecks: " + "; ".join(f"{k}: {'ok' if v else 'FAIL'}" for k, v in checks.items()))
    cmd = "/usr/bin/python3 validation/walls/contact_angle.py" + (" --quick" if args.quick else "")
    if args.a_wall != [-35.0, -30.0, -20.0]:
        cmd += " --a-wall " + " ".join(f"{a:g}" for a in args.a_wall)
    if args.boundary != "bounce_back":
        cmd += f" --boundary {args.boundary}"
    L.append(f"\nRun time {sum(r['wall_s'] for r in results):.0f} s ({args.np} ranks, shared 2-core machine). "
             f"Command: `{cmd}`\n")
    text = "\n".join(L)
    with open(os.path.join(outdir, tag + ".md"), "w") as f:
        f.write(text)
    print(text)


def plot(outdir, tag, results, box, y_wall, args):
    plt = mdval.pyplot()
    n = len(results)
    fig, axs = plt.subplots(1, n, figsize=(5.2 * n, 3.4), squeeze=False)
    for k, r in enumerate(results):
        ax = axs[0][k]
        im = ax.imshow(r["rho"].T, origin="lower", extent=[0, box[0], 0, box[1]], cmap="viridis",
                       vmin=0, vmax=max(8.0, float(r["rho"].max())), aspect="equal")
        if len(r["pts"]):
            ax.plot(r["pts"][:, 0], r["pts"][:, 1], ".", ms=2, color="w", label="rho = n_l/2, fitted")
        xc, yc, R = r["circle"]
        if np.isfinite(R):
            t = np.linspace(0, 2 * math.pi, 400)
            cx, cy = xc + R * np.cos(t), yc + R * np.sin(t)
            m = cy >= y_wall
            ax.plot(np.where(m, cx, np.nan), np.where(m, cy, np.nan), "r-", lw=1, label="fitted circle")
        ax.axhline(y_wall, color="orange", lw=0.8, label="wall surface")
        ax.axhline(y_wall + args.skip, color="orange", lw=0.5, ls=":")
        ax.set_ylim(0, min(box[1], y_wall + 9))
        ax.set_title(f"A_sl = {r['A']:g}: theta = {r['theta']:.1f} ± {r['d_theta']:.1f} deg", fontsize=9)
        ax.set_xlabel("x (rc)")
        ax.set_ylabel("y (rc)")
        ax.legend(fontsize=6, loc="upper right")
        fig.colorbar(im, ax=ax, shrink=0.8, label="density")
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, tag + ".png"), dpi=110)


if __name__ == "__main__":
    main()
