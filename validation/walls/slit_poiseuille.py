#!/usr/bin/python3
"""Walls from an image: body-force Poiseuille flow in a slit, through the
user's path: `mdpore image make slit` writes the image, a scene with `geometry:` builds frozen wall
particles (patch database) and the fluid from it, the boundary of --boundary (bounce_back by default;
wall_boundary: Li et al.'s phi-based reflection and near-wall dissipation, physics.md section 3; or
both) keeps the fluid out of the solid, and `mdpore run` (2 ranks) writes a y profile.

Geometry: slit of h rc (h / 0.5 pore voxels at rc_per_voxel 0.5) between walls of --wall-voxels (4 =
2 rc) voxels, periodic in y, so the box holds one slit and one 4 rc thick solid made of the two walls;
box --length x (h + 4) x --depth rc. Walls: default thickness of the builder (rc + rd = 1.75 rc ->
3 voxel layers kept per face), patches at density 8. Fluid: mDPD A = -40, B = 25, rd = 0.75,
gamma = 4.5, kT = 1, dt = 0.01, fluid density 6.2 of the pore volume; fluid-wall A = --a-wall (-40).
Body force g along x on the fluid. By default g = min(0.05, g*) with g* the force that would give a
no-slip centre velocity of 0.25: well above the noise of the bin means, a wall shear rate <= 0.12, so the
flow is laminar (Re = u h / nu < 4) and viscous heating small (T is checked).

Analysis of the profile CSV (meso/analysis/profile.c: density per species, mean velocity of the mobile
particles per bin, block errors), bins of 1/4 rc aligned with the voxel faces y_lo, y_hi:
  n        fluid density averaged over the central third of the channel;
  mu_ref   the mDPD viscosity measured by validation/engine/viscosity.py (reverse Poiseuille, A = -40,
           density 6.07, box 10 x 20 x 10), read from validation/results/engine/viscosity/viscosity.csv
           (5.41 +- 0.007; that value when the file is missing);
  mu_bulk  (full runs; --no-bulk skips it) the same reverse-Poiseuille measurement at the slit's centre
           density n in a periodic box of the slit's length and depth (L x 12 x D, g = 0.05), and once
           at 6.07 to compare with mu_ref: the fluid in the slit is denser than 6.07 and mu grows with
           density, so mu_ref alone would read a density effect as a wall effect;
  fit A    mu fixed: u = (n g / 2 mu) (y - y0)(y1 - y), zeros y0, y1 free (weighted linear least
           squares in y0 + y1 and y0 y1): slip lengths b_lo = y_lo - y0, b_hi = y1 - y_hi (> 0: the
           velocity vanishes inside the wall, i.e. slip; < 0: inside the fluid). With mu_ref (A) and
           with mu_bulk (A');
  fit B    zeros fixed at the faces, mu free: the viscosity the profile implies for a no-slip wall;
  fit C    free parabola (3 parameters) over all fluid bins: zeros and curvature from the profile alone
           (independent of mu and n); effective mu = n g / (2 |curvature|); R^2 = share of the variance
           of the bin means it explains;
  fit D    free parabola over the core, the bins more than --core-skip (0.5) rc from the faces: the
           contact layer moves faster than the core's parabola extrapolates (chi^2 of C), D is the
           slip length and viscosity of the core flow;
  u_c      centre velocity (vertex of fit C) against the no-slip prediction n g h^2 / (8 mu);
  density  contact layer (0-0.5 rc from a face) and near-wall layer (0.5-1.5 rc) per wall against n,
           largest single-bin deviation beyond 0.5 rc (layering);
  T        the profile has no temperature column: thermo T of the mobile particles (which includes the
           flow's kinetic energy) and T_thermal = T - 2 KE_flow / (3 (N - 1)), KE_flow from the mean
           velocities and densities of the bins;
  penetrations from the summary (samples with mobile particles inside solid voxels).
Checks (exit 1 when one fails): penetrations = 0; |T_thermal - 1| <= 2%; near-wall layer (0.5-1.5 rc)
density within 10% of n at both walls; fit C explains > 0.99 of the variance (> 0.9 with --quick);
u_c within 0.5-1.5 x the no-slip prediction with mu_ref; with --quick also a contact layer above half
of n. The slip lengths are reported and compared with the target |b| < 0.1 rc (set for Li's
boundary) without failing unless --slip-tol is given (then on fit D).
--quick: h = 4, box 6 x 8 x 4, 1000 + 20000 steps, no bulk run, looser bounds (the ctest variant).
--reuse: a run folder whose scene.yaml equals the new scene and holds a summary is analysed again
without running.

Full run (results in validation/results/walls/):
    /usr/bin/python3 validation/walls/slit_poiseuille.py --widths 4 8 12 --steps 100000
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import (BOUNDARIES, RC_PER_VOXEL, image_scene, bulk_viscosity, mdval, mu_reference, pm, propagate,  # noqa: E402
                    run_or_reuse, wls)


def make_image(workdir, width_vox, wall_vox, length_vox, depth_vox):
    path = os.path.join(workdir, f"slit_w{width_vox}_l{length_vox}_d{depth_vox}.h5")
    cmd = [mdval.mdpore_binary(), "image", "make", "slit", "--width", str(width_vox), "--wall", str(wall_vox),
           "--length", str(length_vox), "--depth", str(depth_vox), "-o", path]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {p.stderr}")
    return path, json.loads(p.stdout)


def scene_for(name, box, image, patches, g, a_wall, steps, start, every, bins, seed, patch_seed,
              boundary="bounce_back", gamma_wall=None, wall_density=None):
    """The slit scene: common.image_scene with the body force along x and a y profile."""
    return image_scene(name, box, image, patches, steps=steps, seed=seed, patch_seed=patch_seed,
                       a_wall=a_wall, gamma_wall=gamma_wall, wall_density=wall_density, g=[g, 0.0, 0.0], boundary=boundary,
                       profile={"axis": "y", "bins": int(bins), "every": int(every), "start": int(start)})


def roots_sp(p):
    """Zeros of x^2 - s x + q (p = (s, q)), ascending."""
    s, q = p
    d = math.sqrt(max(s * s - 4 * q, 0.0))
    return np.array([(s - d) / 2, (s + d) / 2])


def roots_poly(p):
    """Zeros of k0 + k1 x + k2 x^2, ascending."""
    k0, k1, k2 = p
    d = math.sqrt(max(k1 * k1 - 4 * k2 * k0, 0.0))
    r = np.array([(-k1 - d) / (2 * k2), (-k1 + d) / (2 * k2)])
    return np.sort(r)


def fit_mu_fixed(xi, u, du, c0):
    """Fit A: u = c0 (xi - z0)(z1 - xi) with c0 = n g / (2 mu) known; zeros, their errors, chi2, curve."""
    p, cov, chi2, _ = wls(np.stack([c0 * xi, -c0 * np.ones_like(xi)], axis=1), u + c0 * xi ** 2, du)
    z, dz = propagate(roots_sp, p, cov)
    return z, dz, chi2, (lambda x: c0 * (x - z[0]) * (z[1] - x))


def fit_free(xi, u, du):
    """Free parabola k0 + k1 xi + k2 xi^2: params, covariance, zeros, their errors, chi2, R^2, curve."""
    p, cov, chi2, model = wls(np.stack([np.ones_like(xi), xi, xi ** 2], axis=1), u, du)
    z, dz = propagate(roots_poly, p, cov)
    r2 = float(1 - np.sum((u - model) ** 2) / np.sum((u - u.mean()) ** 2))
    return p, cov, z, dz, chi2, r2, (lambda x: p[0] + p[1] * x + p[2] * x ** 2)


def analyse(wd, h, y_lo, y_hi, g, mu, mu_err, box, core_skip, mu_bulk=None):
    prof = mdval.read_table(os.path.join(wd, "profile.csv"))
    summ = json.load(open(os.path.join(wd, "summary.json")))
    y = prof["y"]
    width = y[1] - y[0]
    fluid = (y > y_lo) & (y < y_hi)
    yf, xi = y[fluid], y[fluid] - 0.5 * (y_lo + y_hi)
    u, du = prof["vx"][fluid], prof["vx_err"][fluid]
    n_b, dn_b = prof["density_liquid"][fluid], prof["density_liquid_err"][fluid]
    d_wall = np.minimum(yf - y_lo, y_hi - yf)
    centre = np.abs(xi) <= h / 6 + 1e-9
    n = float(n_b[centre].mean())
    n_err = float(np.sqrt(np.sum(dn_b[centre] ** 2)) / centre.sum())
    a = h / 2
    r = {"n_centre": n, "n_centre_err": n_err, "n_channel": float(n_b.mean()), "curves": {}}

    def slip(tag, z, dz):
        r.update({f"b_lo_{tag}": -a - z[0], f"b_hi_{tag}": z[1] - a, f"b_lo_{tag}_err": dz[0], f"b_hi_{tag}_err": dz[1]})

    # Fit A (mu_ref) and A' (mu_bulk at n): mu fixed, zeros free, all fluid bins.
    z, dz, r["chi2_A"], r["curves"]["A"] = fit_mu_fixed(xi, u, du, n * g / (2 * mu))
    slip("A", z, dz)
    if mu_bulk:
        z, dz, r["chi2_A2"], r["curves"]["A2"] = fit_mu_fixed(xi, u, du, n * g / (2 * mu_bulk[0]))
        slip("A2", z, dz)
    # Fit B: zeros at the faces, mu free.
    shape = a * a - xi ** 2
    pB, covB, chiB, _ = wls(shape[:, None], u, du)
    cB, dcB = float(pB[0]), float(math.sqrt(covB[0, 0]))
    muB = n * g / (2 * cB)
    r.update(mu_B=muB, mu_B_err=muB * math.hypot(dcB / cB, n_err / n), chi2_B=chiB)
    r["curves"]["B"] = lambda x: cB * (a * a - x ** 2)
    # Fit C: free parabola, all fluid bins.
    pC, covC, z, dz, r["chi2_C"], r["R2"], r["curves"]["C"] = fit_free(xi, u, du)
    slip("C", z, dz)
    (uc,), (duc,) = propagate(lambda p: [p[0] - p[1] ** 2 / (4 * p[2])], pC, covC)
    r.update(u_c=float(uc), u_c_err=float(duc), mu_C=n * g / (2 * abs(pC[2])))
    r["mu_C_err"] = r["mu_C"] * math.hypot(math.sqrt(covC[2, 2]) / abs(pC[2]), n_err / n)
    # Fit D: free parabola over the core.
    core = d_wall > core_skip
    pD, covD, z, dz, r["chi2_D"], r["R2_D"], r["curves"]["D"] = fit_free(xi[core], u[core], du[core])
    slip("D", z, dz)
    r["mu_D"] = n * g / (2 * abs(pD[2]))
    r["mu_D_err"] = r["mu_D"] * math.hypot(math.sqrt(covD[2, 2]) / abs(pD[2]), n_err / n)
    # No-slip predictions of the centre velocity.
    r["u_pred"] = n * g * h * h / (8 * mu)
    r["u_pred_err"] = r["u_pred"] * math.hypot(n_err / n, mu_err / mu)
    if mu_bulk:
        r["u_pred_bulk"] = n * g * h * h / (8 * mu_bulk[0])
        r["u_pred_bulk_err"] = r["u_pred_bulk"] * math.hypot(n_err / n, mu_bulk[1] / mu_bulk[0])
        r["curves"]["noslip_bulk"] = lambda x: n * g / (2 * mu_bulk[0]) * (a * a - x ** 2)

    # Density next to each wall.
    lo_side = xi < 0
    for side, sel in (("lo", lo_side), ("hi", ~lo_side)):
        r[f"n_contact_{side}"] = float(n_b[sel & (d_wall < 0.5)].mean())
        r[f"n_near_{side}"] = float(n_b[sel & (d_wall >= 0.5) & (d_wall < 1.5)].mean())
    r["n_bin_maxdev"] = float(np.max(np.abs(n_b[d_wall >= 0.5] / n - 1)))

    # Temperature: thermo T minus the flow's kinetic energy (the profile has no T column).
    T, dT = summ["thermo"]["T"]["mean"], summ["thermo"]["T"]["err"]
    Nb = n_b * box[0] * box[2] * width
    ke_flow = 0.5 * np.sum(Nb * (prof["vx"][fluid] ** 2 + prof["vy"][fluid] ** 2 + prof["vz"][fluid] ** 2))
    r.update(T=T, T_err=dT, T_thermal=T - 2 * ke_flow / (3 * (float(np.sum(Nb)) - 1)))
    pen = summ.get("penetrations", {})
    r["penetrations"] = int(pen.get("samples_with_penetration", -1))
    r["pen_max"] = int(pen.get("max_particles", -1))
    r["pen_samples"] = int(pen.get("samples", 0))
    r["loop_s"] = summ["timing"]["loop_seconds"]
    r["particles"] = summ["particles"]
    r["profile"] = dict(xi_all=y - 0.5 * (y_lo + y_hi), xi=xi, u=u, du=du, core=core,
                        n_all=prof["density_liquid"], w_all=prof["density_wall"])
    return r


def default_g(h, n=6.2, mu=5.41, u_target=0.25):
    return min(0.05, round(u_target * 8 * mu / (n * h * h), 4))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="CI variant: h = 4, short run, no bulk run, loose bounds")
    ap.add_argument("--widths", type=float, nargs="+", help="slit widths h in rc (multiples of 0.5; default 4 8 12)")
    ap.add_argument("--steps", type=int, help="steps averaged into the profile, after the transient "
                                               "(default 100000; --quick 20000)")
    ap.add_argument("--equil", type=int, help="transient steps before the profile starts (default max(2000, "
                                               "6 tau), tau = (h/pi)^2 n / mu the flow's slowest mode; --quick 1000)")
    ap.add_argument("--g", type=float, help="body force (default min(0.05, force for a no-slip centre velocity 0.25))")
    ap.add_argument("--length", type=float, default=6.0, help="box length along the flow, rc (default 6)")
    ap.add_argument("--depth", type=float, default=4.0, help="box depth along z, rc (default 4)")
    ap.add_argument("--wall-voxels", type=int, default=4, help="solid voxels of each wall (default 4 = 2 rc)")
    ap.add_argument("--a-wall", type=float, default=-40.0, help="fluid-wall A (default -40, as fluid-fluid)")
    ap.add_argument("--gamma-wall", type=float, help="fluid-wall gamma (default: gamma 4.5, as fluid-fluid)")
    ap.add_argument("--wall-density", type=float, default=8.0, help="wall patch density (geometry.wall_density, default 8)")
    ap.add_argument("--bins-per-rc", type=int, default=4)
    ap.add_argument("--every", type=int, default=10, help="profile sampling interval (steps)")
    ap.add_argument("--core-skip", type=float, default=0.5, help="fit D leaves out the bins this close to a face (rc)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--patch-seed", type=int, default=1)
    ap.add_argument("--no-bulk", action="store_true", help="skip the bulk viscosity runs at the slits' densities")
    ap.add_argument("--bulk-steps", type=int, default=50000, help="averaged steps of each bulk run (default 50000)")
    ap.add_argument("--slip-tol", type=float, help="fail when a slip length of fit D exceeds this (rc); default: report only")
    ap.add_argument("--reuse", action="store_true", help="analyse existing runs of the same scenes again")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--boundary", choices=BOUNDARIES, default="bounce_back",
                    help="wall boundary effect(s): bounce_back (default), wall_boundary (Li et al.), or both")
    ap.add_argument("--outdir", help="table + PNG (default $MDPORE_VALIDATION_OUT/walls or validation/results/walls)")
    ap.add_argument("--workdir", help="run folders (default <$MDPORE_VALIDATION_OUT or $TMPDIR>/slit_poiseuille_runs)")
    args = ap.parse_args()

    q = args.quick
    widths = args.widths or ([4.0] if q else [4.0, 8.0, 12.0])
    steps = args.steps or (20000 if q else 100000)
    bulk = not (q or args.no_bulk)
    r2_min = 0.9 if q else 0.99
    tag = "slit_poiseuille" + ("_quick" if q else "") + \
        ("" if args.boundary == "bounce_back" else "_" + args.boundary.replace("+", "_")) + \
        ("" if args.gamma_wall is None else f"_gw{args.gamma_wall:g}") + \
        ("" if args.wall_density == 8.0 else f"_wd{args.wall_density:g}")
    outdir = args.outdir or mdval.out_dir("walls")
    os.makedirs(outdir, exist_ok=True)
    base = os.environ.get("MDPORE_VALIDATION_OUT") or tempfile.gettempdir()
    workdir = os.path.abspath(args.workdir or os.path.join(base, tag + "_runs"))
    os.makedirs(workdir, exist_ok=True)
    mu, mu_err, mu_src = mu_reference()
    print(f"mu_ref = {mu} +- {mu_err} ({mu_src}); runs in {workdir}", flush=True)

    def voxels(v, what):
        k = v / RC_PER_VOXEL
        if abs(k - round(k)) > 1e-9 or k < 1:
            sys.exit(f"slit_poiseuille: {what} {v} rc is not a whole number of {RC_PER_VOXEL} rc voxels")
        return int(round(k))

    length_vox, depth_vox = voxels(args.length, "--length"), voxels(args.depth, "--depth")
    patches = os.path.join(workdir, f"patches-e{RC_PER_VOXEL:g}-d{args.wall_density:g}-s{args.patch_seed}.h5")
    img_dir = os.path.join(workdir, "images")
    os.makedirs(img_dir, exist_ok=True)
    results, bulk_rows, t_all = [], [], time.time()
    if bulk:
        mu0 = bulk_viscosity(workdir, 6.07, args.length, args.depth, args.bulk_steps, args.np, args.reuse, args.seed)
        bulk_rows.append((6.07, *mu0))
        print(f"bulk mu at 6.07 in a {args.length:g} x 12 x {args.depth:g} box: {mu0[0]:.3f} +- {mu0[1]:.3f} "
              f"(mu_ref {mu:g})", flush=True)
    for h in widths:
        width_vox = voxels(h, "width")
        wall = args.wall_voxels
        g = args.g if args.g is not None else default_g(h)
        tau = (h / math.pi) ** 2 * 6.2 / mu
        equil = args.equil if args.equil is not None else (
            1000 if q else max(2000, int(math.ceil(6 * tau / 0.01 / 1000)) * 1000))
        name = f"slit_h{h:g}"
        wd = os.path.join(workdir, name)
        image, info = make_image(img_dir, width_vox, wall, length_vox, depth_vox)
        box = [args.length, (width_vox + 2 * wall) * RC_PER_VOXEL, args.depth]
        y_lo, y_hi = wall * RC_PER_VOXEL, (wall + width_vox) * RC_PER_VOXEL
        bins = int(round(box[1] * args.bins_per_rc))
        scene = scene_for(name, box, image, patches, g, args.a_wall, equil + steps, equil, args.every, bins,
                          args.seed, args.patch_seed, boundary=args.boundary, gamma_wall=args.gamma_wall,
                          wall_density=None if args.wall_density == 8.0 else args.wall_density)
        print(f"h = {h:g}: image {info['dims']}, box {box}, g = {g}, {equil} + {steps} steps ...", flush=True)
        wall_s = run_or_reuse(scene, wd, args.np, args.reuse)
        mu_bulk = None
        if bulk:
            n_c = analyse(wd, h, y_lo, y_hi, g, mu, mu_err, box, args.core_skip)["n_centre"]
            rho = round(n_c, 2)
            mb = bulk_viscosity(workdir, rho, args.length, args.depth, args.bulk_steps, args.np, args.reuse, args.seed)
            bulk_rows.append((rho, *mb))
            mu_bulk = (mb[0], mb[1], rho)
            print(f"  bulk mu at the centre density {rho:g}: {mb[0]:.3f} +- {mb[1]:.3f}", flush=True)
        r = analyse(wd, h, y_lo, y_hi, g, mu, mu_err, box, args.core_skip, mu_bulk)
        r.update(h=h, g=g, equil=equil, steps=steps, wall_s=wall_s, box=box, mu_bulk=mu_bulk)
        chk = {
            "penetrations = 0": r["penetrations"] == 0 and r["pen_max"] == 0 and r["pen_samples"] > 0,
            "|T_thermal - 1| <= 2%": abs(r["T_thermal"] - 1.0) <= 0.02,
            "near-wall density within 10%": all(abs(r[f"n_near_{s}"] / r["n_centre"] - 1) <= 0.10 for s in ("lo", "hi")),
            f"parabola (fit C) R^2 > {r2_min:g}": r["R2"] > r2_min,
            "u_c / no-slip prediction in [0.5, 1.5]": 0.5 <= r["u_c"] / r["u_pred"] <= 1.5,
        }
        if q:
            chk["contact layer > 0.5 n"] = all(r[f"n_contact_{s}"] > 0.5 * r["n_centre"] for s in ("lo", "hi"))
        if args.slip_tol is not None:
            chk[f"|b| (fit D) <= {args.slip_tol:g} rc"] = max(abs(r["b_lo_D"]), abs(r["b_hi_D"])) <= args.slip_tol
        r["checks"] = chk
        results.append(r)
        for k, v in chk.items():
            print(f"  {'ok  ' if v else 'FAIL'} {k}", flush=True)
        print(f"  u_c = {r['u_c']:.4f} +- {r['u_c_err']:.4f} (no-slip prediction {r['u_pred']:.4f} with mu_ref); "
              f"slip lo / hi: fit A {r['b_lo_A']:+.3f} / {r['b_hi_A']:+.3f}, fit D {r['b_lo_D']:+.3f} / "
              f"{r['b_hi_D']:+.3f} rc; mu_B = {r['mu_B']:.3f}; T = {r['T']:.4f} (thermal {r['T_thermal']:.4f}); "
              f"run {wall_s:.1f} s", flush=True)

    write_tables(outdir, tag, results, bulk_rows, mu, mu_err, mu_src, args)
    plot(outdir, tag, results, args.boundary)
    ok = all(all(r["checks"].values()) for r in results)
    print(f"slit_poiseuille: {'pass' if ok else 'FAIL'} ({time.time() - t_all:.1f} s)")
    sys.exit(0 if ok else 1)


def verdict_of(r):
    bad = [k for k, v in r["checks"].items() if not v]
    return "pass" if not bad else "FAIL: " + "; ".join(bad)


def write_tables(outdir, tag, results, bulk_rows, mu, mu_err, mu_src, args):
    cols = ["h", "box", "particles", "g", "equil", "steps", "n_centre", "n_centre_err", "mu_ref", "mu_bulk",
            "mu_bulk_err", "u_c", "u_c_err", "u_pred", "u_pred_err", "u_pred_bulk", "u_pred_bulk_err",
            "b_lo_A", "b_lo_A_err", "b_hi_A", "b_hi_A_err", "chi2_A", "b_lo_A2", "b_lo_A2_err", "b_hi_A2",
            "b_hi_A2_err", "chi2_A2", "mu_B", "mu_B_err", "chi2_B", "b_lo_C", "b_lo_C_err", "b_hi_C", "b_hi_C_err",
            "mu_C", "mu_C_err", "chi2_C", "R2", "b_lo_D", "b_lo_D_err", "b_hi_D", "b_hi_D_err", "mu_D", "mu_D_err",
            "chi2_D", "n_contact_lo", "n_contact_hi", "n_near_lo", "n_near_hi", "n_bin_maxdev", "T", "T_err",
            "T_thermal", "penetrations", "pen_samples", "wall_s", "loop_s", "verdict"]
    with open(os.path.join(outdir, tag + ".csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in results:
            vals = dict(r, verdict=verdict_of(r), box="x".join(f"{b:g}" for b in r["box"]), mu_ref=mu,
                        mu_bulk=r["mu_bulk"][0] if r["mu_bulk"] else "", mu_bulk_err=r["mu_bulk"][1] if r["mu_bulk"] else "")
            w.writerow([f"{vals.get(c, ''):.6g}" if isinstance(vals.get(c), float) else vals.get(c, "") for c in cols])
    L = [f"# Body-force Poiseuille flow in an image slit, boundary `{args.boundary}` "
         f"({'--quick' if args.quick else 'full run'})\n",
         f"Slit from `mdpore image make slit` at rc_per_voxel {RC_PER_VOXEL}, walls of {args.wall_voxels} voxels "
         f"(the builder's default thickness keeps 3 voxel layers of patches at density 8 per face), box {args.length:g} x "
         f"(h + {2 * args.wall_voxels * RC_PER_VOXEL:g}) x {args.depth:g} rc, periodic. mDPD A = -40, B = 25, rd = 0.75, "
         f"gamma = 4.5, kT = 1, dt = 0.01; fluid-wall A = {args.a_wall:g}, gamma = {4.5 if args.gamma_wall is None else args.gamma_wall:g}; fluid 6.2 per rc^3 of pore; body force g "
         f"along x; effects mdpd_attraction, mdpd_repulsion, dpd_thermostat, body_force, {args.boundary.replace('+', ', ')}; "
         f"{args.np} ranks. Profile along y, {args.bins_per_rc} bins per rc, every {args.every} steps after the "
         f"transient.\n",
         f"mu_ref = {mu:g} ± {mu_err:g} from {mu_src} (reverse Poiseuille, density 6.07, box 10 x 20 x 10). "
         "mu_bulk = the same measurement at the slit's centre density n (rounded to 0.01) in an L x 12 x D periodic "
         "box of the slit's length and depth.\n",
         "Slip length b: how far beyond the wall face (voxel face) the parabola reaches zero (> 0: inside the "
         "wall, slip; < 0: inside the fluid, a layer that moves less than a no-slip flow). Fits (weighted by the "
         "block errors; chi2 = chi^2 per degree of freedom): A mu = mu_ref fixed, zeros free; A' mu = mu_bulk "
         "fixed, zeros free; B zeros at the faces, mu free; C free parabola, all fluid bins (effective mu = "
         f"n g / (2 |curvature|), R^2); D free parabola over the core (bins more than {args.core_skip:g} rc from "
         "the faces). u_c = vertex of fit C; no-slip prediction n g h^2 / (8 mu).\n"]
    if bulk_rows:
        L += ["## Bulk viscosity (reverse Poiseuille, same length and depth)\n",
              "| density | mu | chi2 | run (s) |", "|---|---|---|---|"]
        L += [f"| {rho:g} | {pm(m, e)} | {c:.2f} | {wall:.0f} |" for rho, m, e, c, wall in bulk_rows]
        L.append("")
    L += ["## Centre velocity and viscosity\n",
          "| h (rc) | g | steps (transient + averaged) | n centre | u_c | no-slip u_c (mu_ref) | ratio | mu_bulk(n) "
          "| no-slip u_c (mu_bulk) | ratio | mu, fit B (no slip) | chi2 B | mu eff, fit C | chi2 C | R^2 C | mu, fit D (core) | chi2 D |",
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        mb = r["mu_bulk"]
        bulk_cols = (f"{pm(mb[0], mb[1], 2)} | {pm(r['u_pred_bulk'], r['u_pred_bulk_err'], 4)} | "
                     f"{r['u_c'] / r['u_pred_bulk']:.3f}") if mb else "– | – | –"
        L.append(f"| {r['h']:g} | {r['g']:g} | {r['equil']} + {r['steps']} | {pm(r['n_centre'], r['n_centre_err'])} "
                 f"| {pm(r['u_c'], r['u_c_err'], 4)} | {pm(r['u_pred'], r['u_pred_err'], 4)} | {r['u_c'] / r['u_pred']:.3f} "
                 f"| {bulk_cols} | {pm(r['mu_B'], r['mu_B_err'], 2)} | {r['chi2_B']:.2f} "
                 f"| {pm(r['mu_C'], r['mu_C_err'], 2)} | {r['chi2_C']:.2f} | {r['R2']:.4f} "
                 f"| {pm(r['mu_D'], r['mu_D_err'], 2)} | {r['chi2_D']:.2f} |")

    def b(r, t):
        if f"b_lo_{t}" not in r:
            return "–"
        return f"{r[f'b_lo_{t}']:+.3f} ± {r[f'b_lo_{t}_err']:.3f} / {r[f'b_hi_{t}']:+.3f} ± {r[f'b_hi_{t}_err']:.3f}"

    L += ["\n## Slip lengths b (rc), lower / upper wall\n",
          "| h (rc) | fit A (mu_ref) | chi2 A | fit A' (mu_bulk) | chi2 A' | fit C (free, all bins) | fit D (free, core) "
          "| abs(b) < 0.1 rc (target for Li's boundary), fit D |",
          "|---|---|---|---|---|---|---|---|"]
    for r in results:
        tgt = max(abs(r["b_lo_D"]), abs(r["b_hi_D"])) < 0.1
        L.append(f"| {r['h']:g} | {b(r, 'A')} | {r['chi2_A']:.2f} | {b(r, 'A2')} | "
                 f"{(format(r['chi2_A2'], '.2f') if 'chi2_A2' in r else '–')} | {b(r, 'C')} | {b(r, 'D')} | {'yes' if tgt else 'no'} |")
    L += ["\n## Structure, temperature, boundary, cost\n",
          "| h (rc) | particles | contact layer 0-0.5 rc lo / hi (/ n) | near-wall 0.5-1.5 rc lo / hi (/ n) "
          "| max bin deviation beyond 0.5 rc | T (thermo) | T thermal | penetrations (samples) | run (s) | verdict |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        n = r["n_centre"]
        L.append(f"| {r['h']:g} | {r['particles']} | {r['n_contact_lo'] / n:.3f} / {r['n_contact_hi'] / n:.3f} "
                 f"| {r['n_near_lo'] / n:.3f} / {r['n_near_hi'] / n:.3f} | {100 * r['n_bin_maxdev']:.1f}% "
                 f"| {pm(r['T'], r['T_err'], 4)} | {r['T_thermal']:.4f} | {r['penetrations']} ({r['pen_samples']}) "
                 f"| {r['wall_s']:.0f} | {verdict_of(r)} |")
    widths = " ".join(f"{r['h']:g}" for r in results)
    runs_s = sum(r["wall_s"] for r in results) + sum(row[4] for row in bulk_rows)
    L.append(f"\nRun time (2-core machine, {args.np} ranks): slit runs {sum(r['wall_s'] for r in results):.0f} s, "
             f"bulk runs {sum(row[4] for row in bulk_rows):.0f} s, total {runs_s:.0f} s. Command: `/usr/bin/python3 "
             f"validation/walls/slit_poiseuille.py{' --quick' if args.quick else ''} --widths {widths} "
             f"--steps {results[0]['steps']}`\n")
    text = "\n".join(L)
    with open(os.path.join(outdir, tag + ".md"), "w") as f:
        f.write(text)
    print(text)


def plot(outdir, tag, results, boundary):
    plt = mdval.pyplot()
    fig, axs = plt.subplots(2, len(results), figsize=(5.5 * len(results), 8), squeeze=False)
    for k, r in enumerate(results):
        p, a, cv = r["profile"], r["h"] / 2, r["curves"]
        ax = axs[0][k]
        core = p["core"]
        ax.errorbar(p["xi"][core], p["u"][core], yerr=p["du"][core], fmt=".", color="k", label="mdpore, core bins")
        ax.errorbar(p["xi"][~core], p["u"][~core], yerr=p["du"][~core], fmt="x", color="r", label="mdpore, contact bins")
        x = np.linspace(-a - 0.4, a + 0.4, 200)
        ax.plot(x, cv["A"](x), "-", lw=1, label=f"A mu_ref: b = {r['b_lo_A']:+.2f} / {r['b_hi_A']:+.2f}")
        ax.plot(x, cv["B"](x), "--", lw=1, label=f"B no slip: mu = {r['mu_B']:.2f}")
        ax.plot(x, cv["C"](x), ":", lw=1.5, label=f"C free: b = {r['b_lo_C']:+.2f} / {r['b_hi_C']:+.2f}")
        ax.plot(x, cv["D"](x), "-.", lw=1.2, label=f"D core: b = {r['b_lo_D']:+.2f} / {r['b_hi_D']:+.2f}, "
                                                   f"mu = {r['mu_D']:.2f}")
        if "noslip_bulk" in cv:
            ax.plot(x, cv["noslip_bulk"](x), "-", color="grey", lw=0.8,
                    label=f"no slip, mu_bulk = {r['mu_bulk'][0]:.2f}")
        for s in (-a, a):
            ax.axvline(s, color="grey", lw=0.8)
        ax.axhline(0, color="grey", lw=0.5)
        ax.set_ylim(min(-0.02, float(np.min(p["u"])) - 0.02), 1.25 * float(np.max(p["u"])))
        ax.set_title(f"h = {r['h']:g} rc, g = {r['g']:g}, {boundary}")
        ax.set_xlabel("y - y_mid (rc); walls at the grey lines")
        ax.set_ylabel("u_x")
        ax.legend(fontsize=6.5, loc="lower center")
        ax = axs[1][k]
        ax.plot(p["xi_all"], p["n_all"], "-o", ms=2, label="fluid")
        ax.plot(p["xi_all"], p["w_all"], "-", color="grey", lw=0.8, label="wall particles")
        n = r["n_centre"]
        ax.axhspan(0.9 * n, 1.1 * n, color="C2", alpha=0.15, label="n centre ± 10%")
        for s in (-a, a):
            ax.axvline(s, color="grey", lw=0.8)
        ax.set_xlabel("y - y_mid (rc)")
        ax.set_ylabel("number density")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, tag + ".png"), dpi=120)


if __name__ == "__main__":
    main()
