#!/usr/bin/python3
"""Walls from an image: body-force flow through a circular tube (Hagen-Poiseuille)
and a square duct (series solution, physics.md section 4), made as images and built by the user's
path: the image is written from numpy as raw + sidecar (docs/images.md; `mdpore image make` has no
tube or duct), a scene with `geometry:` builds the frozen wall particles (patch database) and the
fluid, the boundary effect named by --boundary (default bounce_back; wall_boundary once it exists)
keeps the fluid out of the solid, and `mdpore run` (2 ranks) writes HDF5 snapshots.

Geometry (rc_per_voxel 0.5, flow along x, periodic): cross-section (y, z) of side 2R (tube) or a (duct)
plus --wall-voxels (4 = 2 rc) of solid on each side, so periodic copies are 4 rc of solid apart; the
tube is the voxels whose centre lies within R of the axis (a staircase: its area-equivalent radius
R_A = sqrt(A_pore / pi) is used in the formulas, R is the nominal one), the duct a / 0.5 voxels square.
Walls: the builder's default thickness (rc + rd), patches at density 8. Fluid: mDPD A = -40, B = 25,
rd = 0.75, gamma = 4.5, kT = 1, dt = 0.01, fluid-wall A = -40, fluid density 6.2 per rc^3 of pore.
Body force g along x: by default the force that gives a no-slip centre velocity of --u-target (0.4)
with mu = 5.41, n = 6.2, at most 0.3.

Analysis of the snapshots after the transient (every --every steps), bins of 0.25 rc in (y, z):
  Q        volumetric flow rate sum_bins A_bin <S_bin> / <C_bin> (S: sum of v_x, C: count of the fluid
           particles of the bin, <> the time average), from the per-snapshot series
           Q_k = sum_bins A_bin S_bin,k / <C_bin> (error by block averaging, mdval.block_average);
  n        fluid density of the core (r < R / 2, or |y|, |z| < a / 4), G = n g (physics.md section 4);
  mu       the viscosity measured the same way as validation/walls/slit_poiseuille.py: reverse
           Poiseuille in a periodic bulk box at the core density. By default taken from the slit's
           bulk measurements (validation/results/walls/slit_poiseuille.md, 4 densities 6.07-6.36, a
           weighted straight line in the density); --bulk-runs measures it at round(n, 2) here
           (common.bulk_viscosity, L x 12 x 4, --bulk-steps);
  Q_ana    tube pi G R_A^4 / (8 mu), duct a^4 G / (12 mu) [1 - (192 / pi^5) sum_odd tanh(k pi / 2) / k^5];
  Q_slip   the same with the slip-corrected size R_A + b, a + 2 b, b the slit validation's slip length
           (fit D, mean of both walls and all widths, validation/results/walls/slit_poiseuille.csv;
           --slip overrides): bounce_back leaves a layer about 0.2 rc thick that moves less than a
           no-slip flow, i.e. b < 0.
Checks (exit 1 when one fails): penetrations = 0 at every sample; |Q / Q_ana - 1| <= --tol (3%)
with the nominal size (the target); --quick: Q / Q_ana in [0.5, 1.5] instead. The slip-corrected
comparison is reported (which one passes) but does not fail the run.
--quick: tube R = 2 and duct a = 4, box length 4, 1000 + 8000 steps (the ctest variant).
--reuse: a run folder whose scene.yaml equals the new scene is analysed again without running.

Full run (results in validation/results/walls/):
    nice -n 10 /usr/bin/python3 validation/walls/tube_duct.py --radii 2 3 --sides 4 6 --steps 40000
"""
import argparse
import math
import os
import re
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from voxel_flow import continuum_ratio, cross_section, q_duct, q_tube  # noqa: E402
from common import (BOUNDARIES, RC_PER_VOXEL, bulk_viscosity, image_scene, mdval, mu_reference,  # noqa: E402
                    penetrations, pm, read_snapshots, run_or_reuse, slit_slip_length, write_raw_image)

BIN = 0.25  # rc; divides the voxel edge, so every bin is wholly pore or wholly solid


# ---- analytic flow rates and profiles -----------------------------------------------------------------

def u_duct(G, mu, a, y, z, terms=100):
    """Velocity in the square duct |y|, |z| < a / 2 (Fourier series in y, exact in z)."""
    y, z = np.asarray(y, float), np.asarray(z, float)
    u = np.zeros(np.broadcast(y, z).shape)
    for k in range(1, 2 * terms, 2):
        u += ((-1) ** ((k - 1) // 2) / k ** 3 * (1 - np.cosh(k * math.pi * z / a) / np.cosh(k * math.pi / 2))
              * np.cos(k * math.pi * y / a))
    return 4 * G * a * a / (mu * math.pi ** 3) * u


def u_tube(G, mu, R, r):
    r = np.asarray(r, float)
    return np.where(r < R, G / (4 * mu) * (R * R - r * r), 0.0)


# ---- the viscosity ----------------------------------------------------------------------------------

def slit_bulk_table():
    """[(density, mu, err)] of the slit validation's bulk runs (its markdown table), or []."""
    path = os.path.join(mdval.ROOT, "validation", "results", "walls", "slit_poiseuille.md")
    rows, inside = [], False
    try:
        for line in open(path):
            if line.startswith("## Bulk viscosity"):
                inside = True
            elif line.startswith("## "):
                inside = False
            m = re.match(r"\| ([0-9.]+) \| ([0-9.]+) ± ([0-9.]+) \|", line) if inside else None
            if m:
                rows.append(tuple(float(v) for v in m.groups()))
    except OSError:
        pass
    return rows


def mu_line(rows):
    """Weighted straight line mu(rho) through the slit's bulk points: f(rho) -> (mu, err)."""
    rho, mu, err = (np.array(c) for c in zip(*rows))
    X = np.stack([np.ones_like(rho), rho - 6.2], axis=1)
    w = 1 / err ** 2
    cov = np.linalg.inv((X * w[:, None]).T @ X)
    p = cov @ (X * w[:, None]).T @ mu
    chi2 = float(np.sum(w * (mu - X @ p) ** 2) / max(1, len(rho) - 2))
    cov *= max(1.0, chi2)

    def f(r):
        x = np.array([1.0, r - 6.2])
        return float(x @ p), float(math.sqrt(x @ cov @ x))
    return f, p, chi2, (float(rho.min()), float(rho.max()))


# ---- geometry ----------------------------------------------------------------------------------------

def make_geometry(kind, size, wall_vox, length, img_dir, h=RC_PER_VOXEL):
    """The image (raw + sidecar) at h rc per voxel, the box, the pore mask of the cross-section and
    its area."""
    across = 2 * size if kind == "tube" else size
    m = across / h
    if abs(m - round(m)) > 1e-9:
        sys.exit(f"tube_duct: {kind} size {size} rc is not a whole number of {h} rc voxels across")
    nc = int(round(m)) + 2 * wall_vox
    nx = int(round(length / h))
    pore = np.pad(cross_section(kind, size, h), wall_vox)  # the pore, wall_vox solid voxels around
    labels = np.broadcast_to(np.where(pore, 0, 1).astype(np.uint8)[None, :, :], (nx, nc, nc))
    path = os.path.join(img_dir, f"{kind}_{size:g}_l{nx}_w{wall_vox}" + ("" if h == RC_PER_VOXEL else f"_v{h:g}") + ".raw")
    write_raw_image(path, labels)
    box = [nx * h, nc * h, nc * h]
    return path, box, pore, float(pore.sum()) * h * h


def default_g(kind, size, u_target, n=6.2, mu=5.41):
    # no-slip centre velocity: tube n g R^2 / (4 mu); square duct 0.07367 n g a^2 / mu
    k = 0.25 * size ** 2 if kind == "tube" else 0.0736713 * size ** 2
    return min(0.3, round(u_target * mu / (n * k), 4))


# ---- analysis ----------------------------------------------------------------------------------------

def analyse(wd, kind, size, box, equil, g):
    steps, snaps, _ = read_snapshots(wd, equil)
    if len(snaps) < 10:
        raise RuntimeError(f"{wd}: {len(snaps)} snapshots after step {equil}")
    L = box[0]
    nb = int(round(box[1] / BIN))
    yc, zc = box[1] / 2, box[2] / 2
    C = np.zeros(nb * nb)
    S = np.zeros((len(snaps), nb * nb))
    core_counts = np.zeros(len(snaps))
    for k, (x, v) in enumerate(snaps):
        iy = np.clip((x[:, 1] / BIN).astype(int), 0, nb - 1)
        iz = np.clip((x[:, 2] / BIN).astype(int), 0, nb - 1)
        idx = iy * nb + iz
        C += np.bincount(idx, minlength=nb * nb)
        S[k] = np.bincount(idx, weights=v[:, 0], minlength=nb * nb)
        dy, dz = x[:, 1] - yc, x[:, 2] - zc
        core = (dy ** 2 + dz ** 2 < (size / 2) ** 2) if kind == "tube" else (np.maximum(abs(dy), abs(dz)) < size / 4)
        core_counts[k] = core.sum()
    K = len(snaps)
    Cm = C / K
    filled = Cm > 0
    Qk = (S[:, filled] / Cm[filled]).sum(axis=1) * BIN * BIN
    Q, dQ = mdval.block_average(Qk)
    core_area = math.pi * size ** 2 / 4 if kind == "tube" else (size / 2) ** 2
    n, n_err = mdval.block_average(core_counts / (core_area * L))
    # profiles: radial (tube) or along y through the middle (duct), bins of BIN
    cy = (np.arange(nb) + 0.5) * BIN - yc
    CY, CZ = np.meshgrid(cy, cy, indexing="ij")
    Sm = S.mean(axis=0)
    if kind == "tube":
        coord = np.sqrt(CY ** 2 + CZ ** 2).ravel()
        sel = np.ones_like(coord, bool)
    else:
        coord = CY.ravel()
        sel = (np.abs(CZ) < 0.5).ravel()
    edges = np.arange(-box[1] / 2, box[1] / 2 + 1e-9, BIN) if kind == "duct" else np.arange(0, box[1] / 2 + 1e-9, BIN)
    which = np.digitize(coord, edges) - 1
    prof_x, prof_u, prof_n = [], [], []
    for b in range(len(edges) - 1):
        m = sel & (which == b)
        c = Cm[m].sum()
        if c > 0:
            prof_x.append(0.5 * (edges[b] + edges[b + 1]))
            prof_u.append(Sm[m].sum() / c)
            prof_n.append(c / (m.sum() * BIN * BIN * L))
    summ = mdval_json(os.path.join(wd, "summary.json"))
    pen, pen_max, pen_samples = penetrations(summ)
    T, dT = summ["thermo"]["T"]["mean"], summ["thermo"]["T"]["err"]
    return dict(Q=Q, dQ=dQ, n=n, n_err=n_err, snapshots=K, pen=pen, pen_max=pen_max, pen_samples=pen_samples,
                T=T, T_err=dT, particles=summ["particles"], loop_s=summ["timing"]["loop_seconds"],
                prof=(np.array(prof_x), np.array(prof_u), np.array(prof_n)),
                u_mean=float(np.sum(S) / np.sum(C)))


def mdval_json(path):
    import json
    with open(path) as f:
        return json.load(f)


# ---- main --------------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="CI variant: tube R = 2, duct a = 4, short runs, loose bounds")
    ap.add_argument("--radii", type=float, nargs="*", help="tube radii R in rc (multiples of 0.25; default 2 3 4)")
    ap.add_argument("--sides", type=float, nargs="*", help="square duct sides a in rc (multiples of 0.5; default 4 6 8)")
    ap.add_argument("--boundary", choices=BOUNDARIES, default="bounce_back",
                    help="the wall boundary effect (default bounce_back)")
    ap.add_argument("--steps", type=int, help="averaged steps after the transient (default 40000; --quick 8000)")
    ap.add_argument("--equil", type=int, help="transient steps (default max(2000, 6 tau); --quick 1000)")
    ap.add_argument("--g", type=float, help="body force (default: no-slip centre velocity --u-target, at most 0.3)")
    ap.add_argument("--u-target", type=float, default=0.4)
    ap.add_argument("--length", type=float, default=4.0, help="box length along the flow, rc (default 4)")
    ap.add_argument("--wall-voxels", type=int, help="solid voxels on each side (default: 2 rc of them)")
    ap.add_argument("--rc-per-voxel", type=float, default=RC_PER_VOXEL,
                    help=f"voxel edge in rc (default {RC_PER_VOXEL}; 0.25 halves the tube's staircase steps)")
    ap.add_argument("--every", type=int, default=100, help="snapshot interval (steps)")
    ap.add_argument("--tol", type=float, default=0.03, help="allowed |Q / Q_ana - 1| (default 0.03)")
    ap.add_argument("--slip", type=float, help="slip length b for the corrected size (default: the slit validation's)")
    ap.add_argument("--bulk-runs", action="store_true",
                    help="measure mu at each core density here (default: the slit validation's bulk runs)")
    ap.add_argument("--bulk-steps", type=int, default=50000)
    ap.add_argument("--wall-density", type=float, default=8.0,
                    help="wall patch density (geometry.wall_density; 4 is the campaigns', docs/walls.md section 16)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--patch-seed", type=int, default=1)
    ap.add_argument("--reuse", action="store_true", help="analyse existing runs of the same scenes again")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--outdir", help="table + PNG (default $MDPORE_VALIDATION_OUT/walls or validation/results/walls)")
    ap.add_argument("--workdir", help="run folders (default <$MDPORE_VALIDATION_OUT or $TMPDIR>/tube_duct_runs)")
    args = ap.parse_args()

    q = args.quick
    radii = args.radii if args.radii is not None else ([2.0] if q else [2.0, 3.0, 4.0])
    sides = args.sides if args.sides is not None else ([4.0] if q else [4.0, 6.0, 8.0])
    steps = args.steps or (8000 if q else 40000)
    tag = "tube_duct" + ("_quick" if q else "") + ("" if args.boundary == "bounce_back" else "_" + args.boundary) + \
        ("" if args.wall_density == 8.0 else f"_wd{args.wall_density:g}") + \
        ("" if args.length == 4.0 else f"_L{args.length:g}") + ("" if args.patch_seed == 1 else f"_ps{args.patch_seed}") + \
        ("" if args.rc_per_voxel == RC_PER_VOXEL else f"_v{args.rc_per_voxel:g}")
    if args.wall_voxels is None:
        args.wall_voxels = int(round(2.0 / args.rc_per_voxel))
    outdir = args.outdir or mdval.out_dir("walls")
    os.makedirs(outdir, exist_ok=True)
    base = os.environ.get("MDPORE_VALIDATION_OUT") or tempfile.gettempdir()
    workdir = os.path.abspath(args.workdir or os.path.join(base, tag + "_runs"))
    img_dir = os.path.join(workdir, "images")
    os.makedirs(img_dir, exist_ok=True)
    patches = os.path.join(workdir, f"patches-e{args.rc_per_voxel:g}-d{args.wall_density:g}-s{args.patch_seed}.h5")
    mu_ref, mu_ref_err, mu_src = mu_reference()
    if args.slip is not None:
        b, b_spread, b_src = args.slip, 0.0, "--slip"
    else:
        b, b_spread, b_src = slit_slip_length()
    bulk_rows = slit_bulk_table()
    if not (args.bulk_runs or bulk_rows or q):
        print("tube_duct: the slit validation's bulk viscosities were not found: measuring here (--bulk-runs)")
        args.bulk_runs = True
    line = mu_line(bulk_rows) if len(bulk_rows) >= 2 else None
    print(f"mu_ref = {mu_ref} +- {mu_ref_err} ({mu_src}); slip b = {b:+.3f} rc ({b_src}); runs in {workdir}",
          flush=True)

    cases = [("tube", r) for r in radii] + [("duct", a) for a in sides]
    results, t_all = [], time.time()
    for kind, size in cases:
        image, box, pore, area = make_geometry(kind, size, args.wall_voxels, args.length, img_dir,
                                               args.rc_per_voxel)
        g = args.g if args.g is not None else default_g(kind, size, args.u_target)
        half = size if kind == "tube" else size / 2
        tau = (half / 2.405) ** 2 * 6.2 / mu_ref
        equil = args.equil if args.equil is not None else (
            1000 if q else max(2000, int(math.ceil(6 * tau / 0.01 / 1000)) * 1000))
        name = f"{kind}_{size:g}"
        wd = os.path.join(workdir, name)
        scene = image_scene(name, box, image, patches, steps=equil + steps, seed=args.seed,
                            patch_seed=args.patch_seed, g=[g, 0.0, 0.0], boundary=args.boundary,
                            wall_density=None if args.wall_density == 8.0 else args.wall_density,
                            snapshot=args.every, thermo_every=100, rc_per_voxel=args.rc_per_voxel)
        print(f"{name}: box {box}, pore area {area:g} rc^2, g = {g}, {equil} + {steps} steps ...", flush=True)
        wall_s = run_or_reuse(scene, wd, args.np, args.reuse)
        r = analyse(wd, kind, size, box, equil, g)
        n = r["n"]
        if args.bulk_runs:
            rho = round(n, 2)
            mb = bulk_viscosity(workdir, rho, args.length, 4.0, args.bulk_steps, args.np, args.reuse, args.seed)
            mu, mu_err, mu_how = mb[0], mb[1], f"bulk run at {rho:g}"
        elif line and not q:
            mu, mu_err = line[0](n)
            lo, hi = line[3]
            mu_how = f"slit bulk line at {n:.3f}" + ("" if lo - 0.05 <= n <= hi + 0.05 else " (extrapolated)")
        else:
            mu, mu_err, mu_how = mu_ref, mu_ref_err, "mu_ref"
        G = n * g
        if kind == "tube":
            R_A = math.sqrt(area / math.pi)
            Qa, Qs = q_tube(G, mu, R_A), q_tube(G, mu, R_A + b)
            size_eff = R_A
        else:
            Qa, Qs = q_duct(G, mu, size), q_duct(G, mu, size + 2 * b)
            size_eff = size
        rel = math.hypot(r["n_err"] / n, mu_err / mu)
        r.update(kind=kind, size=size, size_eff=size_eff, area=area, g=g, G=G, mu=mu, mu_err=mu_err, mu_how=mu_how,
                 Q_ana=Qa, Q_slip=Qs, ratio=r["Q"] / Qa, ratio_err=r["Q"] / Qa * math.hypot(r["dQ"] / r["Q"], rel),
                 ratio_slip=r["Q"] / Qs, equil=equil, steps=steps, wall_s=wall_s, box=box,
                 ratio_ref=r["Q"] / (Qa * mu / mu_ref))
        r["ratio_slip_err"] = r["ratio_slip"] * r["ratio_err"] / r["ratio"]
        # the continuum on the same voxels (voxel_flow.py): the staircase's own flow rate
        c_vox, _ = continuum_ratio(kind, size, args.rc_per_voxel)
        r["ratio_vox"], r["ratio_vox_err"] = r["ratio"] / c_vox, r["ratio_err"] / c_vox
        if q:
            ok_q = 0.5 <= r["ratio"] <= 1.5
            qname = "Q / Q_ana in [0.5, 1.5]"
        else:
            ok_q = abs(r["ratio"] - 1) <= args.tol
            qname = f"|Q / Q_ana - 1| <= {100 * args.tol:g}%"
        r["checks"] = {"penetrations = 0": r["pen"] == 0 and r["pen_max"] == 0 and r["pen_samples"] > 0, qname: ok_q}
        r["slip_pass"] = abs(r["ratio_slip"] - 1) <= args.tol
        results.append(r)
        for k, v in r["checks"].items():
            print(f"  {'ok  ' if v else 'FAIL'} {k}", flush=True)
        print(f"  Q = {r['Q']:.4f} +- {r['dQ']:.4f}; n = {n:.3f}; mu = {mu:.3f} ({mu_how}); Q_ana = {Qa:.4f} "
              f"(ratio {r['ratio']:.3f} +- {r['ratio_err']:.3f}); slip-corrected {Qs:.4f} (ratio "
              f"{r['ratio_slip']:.3f}); against the continuum on the same voxels {r['ratio_vox']:.3f} +- "
              f"{r['ratio_vox_err']:.3f}; T = {r['T']:.4f}; run {wall_s:.0f} s", flush=True)

    write_table(outdir, tag, results, args, b, b_spread, b_src, mu_ref, mu_ref_err, mu_src, line, bulk_rows)
    plot(outdir, tag, results, b, args.boundary)
    ok = all(all(r["checks"].values()) for r in results)
    print(f"tube_duct: {'pass' if ok else 'FAIL'} ({time.time() - t_all:.1f} s)")
    sys.exit(0 if ok else 1)


def verdict_of(r):
    bad = [k for k, v in r["checks"].items() if not v]
    return "pass" if not bad else "FAIL: " + "; ".join(bad)


def write_table(outdir, tag, results, args, b, b_spread, b_src, mu_ref, mu_ref_err, mu_src, line, bulk_rows):
    import csv
    cols = ["kind", "size", "size_eff", "area", "box", "particles", "g", "equil", "steps", "snapshots", "n", "n_err",
            "mu", "mu_err", "mu_how", "Q", "dQ", "Q_ana", "ratio", "ratio_err", "Q_slip", "ratio_slip", "ratio_ref",
            "ratio_vox", "ratio_vox_err", "T", "T_err", "pen", "pen_samples", "wall_s", "verdict"]
    with open(os.path.join(outdir, tag + ".csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in results:
            vals = dict(r, verdict=verdict_of(r), box="x".join(f"{v:g}" for v in r["box"]))
            w.writerow([f"{vals[c]:.6g}" if isinstance(vals[c], float) else vals[c] for c in cols])
    L = [f"# Body-force flow in an image tube and square duct, boundary `{args.boundary}` "
         f"({'--quick' if args.quick else 'full run'})\n",
         f"Images written from numpy (raw + sidecar) at rc_per_voxel {args.rc_per_voxel:g}, flow along x, box length "
         f"{args.length:g} rc, {args.wall_voxels} solid voxels on each side; builder defaults (walls rc + rd thick, "
         "patches at density 8, fluid 6.2 per rc^3 of pore); mDPD A = -40 (fluid-fluid and fluid-wall), B = 25, "
         f"rd = 0.75, gamma = 4.5, kT = 1, dt = 0.01; effects mdpd_attraction, mdpd_repulsion, dpd_thermostat, "
         f"body_force, {args.boundary}; {args.np} ranks; snapshots every {args.every} steps after the transient.\n",
         "Q = volumetric flow rate from the snapshots (bins of 0.25 rc in the cross-section, sum of bin area x "
         "mean velocity), block-averaged error. n = fluid density of the core (r < R/2; |y|, |z| < a/4); G = n g. "
         "Tube: R_A = area-equivalent radius of the voxel staircase, Q_ana = pi G R_A^4 / (8 mu). Duct: "
         "Q_ana = a^4 G / (12 mu) [1 - (192/pi^5) sum_odd tanh(k pi/2)/k^5]. Slip-corrected: R_A + b, a + 2b "
         f"with b = {b:+.3f} rc (spread {b_spread:.3f}) from {b_src}.\n"]
    if line and not args.bulk_runs and not args.quick:
        f, p, chi2, (lo, hi) = line
        L.append(f"mu = reverse-Poiseuille bulk viscosity at the core density, from the slit validation's bulk runs "
                 f"({', '.join(f'{r:g}: {m:.3f}' for r, m, _ in bulk_rows)}; weighted line mu = {p[0]:.3f} + "
                 f"{p[1]:.3f} (rho - 6.2), chi2 {chi2:.2f}). mu_ref = {mu_ref:g} ± {mu_ref_err:g} ({mu_src}).\n")
    elif args.bulk_runs:
        L.append("mu = reverse-Poiseuille bulk viscosity measured here at round(n, 2) (L x 12 x 4 periodic box).\n")
    else:
        L.append(f"mu = mu_ref = {mu_ref:g} ± {mu_ref_err:g} ({mu_src}).\n")
    L += ["| shape | size (rc) | area-equiv. / side (rc) | g | steps | n core | mu | Q | Q_ana (no slip) | Q / Q_ana "
          "| within tol | Q_slip (size + b) | Q / Q_slip | within tol | Q / Q_ana with mu_ref | Q / Q_vox (continuum "
          "on the same voxels) | T | penetrations (samples) | run (s) | verdict |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        L.append(f"| {r['kind']} | {'R = ' if r['kind'] == 'tube' else 'a = '}{r['size']:g} | {r['size_eff']:.3f} "
                 f"| {r['g']:g} | {r['equil']} + {r['steps']} | {pm(r['n'], r['n_err'])} | {pm(r['mu'], r['mu_err'], 2)} "
                 f"| {pm(r['Q'], r['dQ'], 4)} | {r['Q_ana']:.4f} | {pm(r['ratio'], r['ratio_err'])} "
                 f"| {'yes' if abs(r['ratio'] - 1) <= args.tol else 'no'} | {r['Q_slip']:.4f} "
                 f"| {pm(r['ratio_slip'], r['ratio_slip_err'])} | {'yes' if r['slip_pass'] else 'no'} "
                 f"| {r['ratio_ref']:.3f} | {pm(r['ratio_vox'], r['ratio_vox_err'])} "
                 f"| {pm(r['T'], r['T_err'], 4)} | {r['pen']} ({r['pen_samples']}) "
                 f"| {r['wall_s']:.0f} | {verdict_of(r)} |")
    cmd = "/usr/bin/python3 validation/walls/tube_duct.py" + (" --quick" if args.quick else "")
    if not args.quick:
        cmd += (f" --radii {' '.join(f'{r:g}' for r in args.radii or [2, 3, 4])} --sides "
                f"{' '.join(f'{a:g}' for a in args.sides or [4, 6, 8])} --steps {results[0]['steps']}")
    if args.boundary != "bounce_back":
        cmd += f" --boundary {args.boundary}"
    for flag, val, default in (("--wall-density", args.wall_density, 8.0), ("--slip", args.slip, None),
                               ("--length", args.length, 4.0), ("--patch-seed", args.patch_seed, 1),
                               ("--rc-per-voxel", args.rc_per_voxel, RC_PER_VOXEL)):
        if val is not None and val != default:
            cmd += f" {flag} {val:g}"
    L.append(f"\nTolerance {100 * args.tol:g}%. Run time {sum(r['wall_s'] for r in results):.0f} s "
             f"({args.np} ranks, shared 2-core machine). Command: `{cmd}`\n")
    text = "\n".join(L)
    with open(os.path.join(outdir, tag + ".md"), "w") as f:
        f.write(text)
    print(text)


def plot(outdir, tag, results, b, boundary):
    plt = mdval.pyplot()
    n = len(results)
    fig, axs = plt.subplots(1, n + 1, figsize=(4.2 * (n + 1), 3.8), squeeze=False)
    for k, r in enumerate(results):
        ax = axs[0][k]
        x, u, _ = r["prof"]
        ax.plot(x, u, "o", ms=3, color="k", label="mdpore")
        s = r["size_eff"]
        if r["kind"] == "tube":
            xx = np.linspace(0, x.max() + 0.3, 200)
            ax.plot(xx, u_tube(r["G"], r["mu"], s, xx), "-", label=f"no slip, R_A = {s:.2f}")
            ax.plot(xx, u_tube(r["G"], r["mu"], s + b, xx), "--", label=f"R_A + b = {s + b:.2f}")
            ax.axvline(s, color="grey", lw=0.8)
            ax.set_xlabel("r (rc)")
            ax.set_title(f"tube R = {r['size']:g}: Q/Q_ana = {r['ratio']:.3f}", fontsize=9)
        else:
            xx = np.linspace(-s / 2, s / 2, 200)
            ax.plot(xx, u_duct(r["G"], r["mu"], s, xx, 0 * xx), "-", label=f"no slip, a = {s:g}")
            xs = np.linspace(-(s / 2 + b), s / 2 + b, 200)
            ax.plot(xs, u_duct(r["G"], r["mu"], s + 2 * b, xs, 0 * xs), "--", label=f"a + 2b = {s + 2 * b:.2f}")
            for e in (-s / 2, s / 2):
                ax.axvline(e, color="grey", lw=0.8)
            ax.set_xlabel("y - y_axis (rc), |z| < 0.5")
            ax.set_title(f"duct a = {r['size']:g}: Q/Q_ana = {r['ratio']:.3f}", fontsize=9)
        ax.set_ylabel("u_x")
        ax.legend(fontsize=7)
    ax = axs[0][n]
    for kind, mk in (("tube", "o"), ("duct", "s")):
        rs = [r for r in results if r["kind"] == kind]
        if not rs:
            continue
        sz = [r["size"] / (1 if kind == "tube" else 2) for r in rs]
        ax.errorbar(sz, [r["ratio"] for r in rs], yerr=[r["ratio_err"] for r in rs], fmt=mk + "-",
                    label=f"{kind}: Q / Q_ana")
        ax.errorbar(sz, [r["ratio_slip"] for r in rs], yerr=[r["ratio_slip_err"] for r in rs], fmt=mk + "--",
                    mfc="none", label=f"{kind}: Q / Q_ana(size + b)")
    ax.axhspan(0.97, 1.03, color="C2", alpha=0.15, label="±3%")
    ax.axhline(1, color="grey", lw=0.8)
    ax.set_xlabel("R or a/2 (rc)")
    ax.set_title(f"flow rate / analytic, {boundary}", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, tag + ".png"), dpi=110)


if __name__ == "__main__":
    main()
