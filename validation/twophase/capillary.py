#!/usr/bin/python3
"""Capillarity in a slit of image walls: Washburn imbibition of a wetting mDPD liquid into an empty slit,
and the capillary entry pressure of oil into a water-filled slit throat (docs/twophase.md, section
"Capillary rise: Washburn imbibition and entry pressure").

Walls: raw images written here (validation/walls/common.py), rc_per_voxel 0.5, patches at density 8
(geometry.wall_density default), bounce_back, 1 rank; liquids mDPD A = -40, B = 25, rd = 0.75,
gamma = 4.5, kT = 1, dt = 0.01, fluid density 6.2 (the contact-angle runs of docs/walls.md section 13,
whose angles are used: A_sl = -35: 68.6 +- 0.8 deg, A_sl = -20: 141.7 +- 2.4 deg).

Washburn (--parts washburn): one solid slab (wt = 2 rc thick, y in [0, wt)) over x in [x_m, Lx); y is
periodic, so the slit of width H lies between the slab and its periodic image. The liquid (liquid-wall
A = --a-wall, -35) starts as a reservoir slab x in [Lv, x_m) over the whole y and z
(geometry.fluid_region), a vapour gap x in [0, Lv) before it: the reservoir's free surface at x = Lv is
flat (pressure 0), and it feeds the slit mouth at x_m. Snapshots every --every steps: the liquid in the
slit (x > x_m, y in the pore) binned along x (0.5 rc); the front L(t) = the distance from the mouth to
the first bin, counted from the mouth, whose density is below half the filled part's (the bins 1-3 rc
behind the mouth). Fit L^2 = k (t - t0) over L in [H, 2 H] (--fit-window-h, in units of H; or --fit-window
in rc) by least squares; error of k: the spread of the two halves of the window and of the --seeds.
A slit long enough for L = 2 H at H = 10 needs a longer slit and reservoir (--slit-length, --reservoir,
one value per width) and, to save time, part of the slit filled at the start (--prefill rc: the fit
window must start beyond it).
Washburn with slip b at each wall: k_W = gamma_lv cos(theta) H (1 + 6 b / H) / (3 mu)
(Poiseuille flux in a slit with slip H^3 (1 + 6 b / H) / 12, driving pressure 2 gamma cos(theta) / H);
gamma_lv = 7.54 (physics.md section 2), b = -0.2 +- 0.05 rc (docs/walls.md section 16, wall density 8),
mu from the reverse-Poiseuille line mu = 5.636 + 1.572 (n - 6.2) (validation/results/engine/
viscosity_density) at the liquid density n measured in the slit's core behind the mouth. Also the local
slope over --segments parts of the L window, and the early regime: the exponent d ln L / d ln t for
L from 1 rc to the window, against the viscous time rho H^2 / (12 mu) of Bosanquet's equation (the
inertial regime lasts about that long).

Entry (--parts entry): a chamber x in [0, Lc) over the whole y and a throat x in [Lc, Lx) of width H
(solid y in [0, ws) there). Water (water-wall A = -35) fills the throat and the chamber's downstream
part, oil (oil-wall A = -20, water-oil A = -20) the chamber's upstream part x in [Lc - Lo, Lc)
(geometry.fluid_species_regions). The same body force f along x on both liquids: at rest the pressure rises by
n f per unit length along the loop, and the only jump is the meniscus at the throat's mouth, so
dp = f * int n dx over one period (the chamber's profile, the throat at its liquid density).
Young-Laplace entry pressure of a slit dp_c = 2 gamma_wo cos(theta_wo) / H_eff with gamma_wo cos(theta_wo)
= gamma_lv (cos theta_w - cos theta_o) (Young's equation for each liquid against its vapour: the
solid-vapour tension cancels; both liquids are the same A = -40 liquid with gamma_lv = 7.54), from the
flat-wall angles of docs/walls.md section 13; gamma_wo = 14.72 (docs/twophase.md) gives theta_wo.
A ladder of forces (--ratios of dp_c); the oil's depth in the throat is the oil particles in the
throat / (n H Lz). A rung "advanced" when the depth in the last quarter exceeds --enter-depth rc (past the mouth's
bulge, whose depth at dp_c is about 2/3 of its sagitta, 1 rc for H = 6); it "invades" when the oil
reaches the throat's exit (depth >= Lt - 0.5 rc at some snapshot) or, advanced, its depth still grows
faster than --enter-rate rc per time unit over the second half of the run (a meniscus that advanced
and stopped is held by the walls, not invading).
The bracket is on invasion.
The width H_eff: the water-filled throat's equimolar width int n dy / n_bulk (throat_profile), measured in the
rungs whose profile window holds water only: the dividing surface at which the wall tensions Young's
equation gives at p ~ 0 hold at the throat's pressure (zero adsorption; docs/twophase.md section 7). The
nominal-H comparison is reported beside it. The resting menisci of the rungs the oil did not invade: a
circle fit of the phi = 0 line (meniscus_circle), Laplace dp = gamma_wo / R and the apparent angle.

Checks (exit 1 when one fails): each width's k / k_W within --tol-washburn (0.2) + 2 sigma of 1 (with the
static angle); the entry bracket (highest dp that does not enter, lowest that does), widened by
--tol-entry (20%), holds dp_c(H_eff); 0 penetrations.
--quick: the ctest (a slit H = 4 imbibes: L^2 linear in t within loose bounds, and a non-wetting
slit, A_sl = -20, takes no liquid).

Full run (results in validation/results/twophase/capillary.{md,json,png}):
    nice -n 5 /usr/bin/python3 validation/twophase/capillary.py
"""
import argparse
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "walls"))
from common import mdval, penetrations, read_snapshots, run_or_reuse, write_raw_image  # noqa: E402

VOX = 0.5
GAMMA_LV = (7.54, 0.04)  # physics.md section 2 (A = -40, B = 25, rd = 0.75)
GAMMA_WO = (14.72, 0.25)  # docs/twophase.md section 4
THETA = {-35.0: (68.6, 0.8), -30.0: (89.8, 1.7), -20.0: (141.7, 2.4)}  # docs/walls.md section 13
SLIP = (-0.2, 0.05)  # docs/walls.md section 16, wall density 8
PAIR = {"A": -40.0, "B": 25.0, "gamma": 4.5, "rc": 1.0, "rd": 0.75}


def mu_of(n):
    """Reverse-Poiseuille viscosity of the A = -40 liquid at density n (viscosity_density line)."""
    return 5.636 + 1.572 * (n - 6.2), 0.017 + 0.121 * abs(n - 6.2)


def vox(v):
    k = v / VOX
    assert abs(k - round(k)) < 1e-9, v
    return int(round(k))


def scene(name, box, image, patches, species, pairs, steps, seed, fluid_region=None, second=None, force=None,
          every=200):
    geo = {"image": image, "rc_per_voxel": VOX, "flow_axis": "x",
           "species": {"fluid": species[0], "inorganic": "wall"}, "patches": {"file": patches, "seed": 1}}
    if fluid_region:
        geo["fluid_region"] = {"lo": [float(v) for v in fluid_region[0]], "hi": [float(v) for v in fluid_region[1]]}
    if second:
        geo["fluid_species_regions"] = [{"species": second[0], "lo": [float(v) for v in second[1]],
                                          "hi": [float(v) for v in second[2]]}]
    eff = {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {}, "bounce_back": {}}
    if force:
        eff["body_force"] = {sp: [float(force), 0.0, 0.0] for sp in species}
    return {
        "name": name,
        "box": {"lo": [0.0, 0.0, 0.0], "hi": [float(v) for v in box], "periodic": [True, True, True]},
        "species": [{"name": sp} for sp in species] + [{"name": "wall", "frozen": True}],
        "pairs": dict({"default": dict(PAIR)}, **pairs),
        "density_kernel": "warren",
        "kT": 1.0,
        "effects": eff,
        "geometry": geo,
        "initial": {"temperature": 1.0},
        "run": {"dt": 0.01, "steps": int(steps), "seed": int(seed)},
        "output": {"thermo": {"every": 100, "file": "thermo.csv"}, "summary": "summary.json", "progress": False,
                   "snapshot": {"every": int(every), "file": "snap"}},
    }


# ---------------------------------------------------------------- Washburn imbibition
def washburn_run(args, work, H, seed, a_wall, steps, Ls=None, Lr=None, prefill=0.0):
    wt, Lv, Lz = 2.0, 4.0, args.lz
    Ls = per_width(args.slit_length, 0) if Ls is None else Ls
    Lr = per_width(args.reservoir, 0) if Lr is None else Lr
    Lx, Ly = Lv + Lr + Ls, H + wt
    xm = Lv + Lr
    lab = np.zeros((vox(Lx), vox(Ly), vox(Lz)), dtype=np.uint8)
    lab[vox(xm):, :vox(wt), :] = 1
    tag = f"washburn_H{H:g}_A{a_wall:g}_s{seed}"
    if (Ls, Lr, prefill) != (16.0, 12.0, 0.0):  # the default slit keeps its folder name
        tag += f"_Ls{Ls:g}_Lr{Lr:g}_pre{prefill:g}"
    os.makedirs(work, exist_ok=True)
    image = write_raw_image(os.path.join(work, f"{tag}.raw"), lab)
    patches = os.path.join(work, "patches-e0.5-d8-s1.h5")
    s = scene(tag, (Lx, Ly, Lz), image, patches, ["liquid"], {"liquid-wall": {"A": float(a_wall)}}, steps,
              seed, fluid_region=([Lv, 0, 0], [xm + prefill, Ly, Lz]), every=args.every)
    wd = os.path.join(work, tag)
    wall_s = run_or_reuse(s, wd, 1, args.reuse)
    snap_steps, snaps, _ = read_snapshots(wd, 0, species=0)
    summ = json.load(open(os.path.join(wd, "summary.json")))
    nb = int(round(Ls / 0.5))
    edges = xm + 0.5 * np.arange(nb + 1)
    t, L, n_fill, n_core = [], [], [], []
    for st, (x, _v) in zip(snap_steps, snaps):
        pore = (x[:, 1] >= wt) & (x[:, 0] >= xm)
        h, _ = np.histogram(x[pore, 0], bins=edges)
        rho = h / (0.5 * H * Lz)
        nf = float(np.mean(rho[2:6]))
        core = pore & (x[:, 1] >= wt + 1.5) & (x[:, 1] < Ly - 1.5) & (x[:, 0] >= xm + 1) & (x[:, 0] < xm + 3)
        n_core.append(float(core.sum() / (2.0 * (H - 3.0) * Lz)))
        if nf < 3.0:  # the liquid has not reached 3 rc yet
            t.append(st * 0.01)
            L.append(float(np.sum(rho) * 0.5 / 6.1))
            n_fill.append(nf)
            n_core[-1] = float("nan")
            continue
        front = front_of(rho, 0.5 * nf, 0)
        t.append(st * 0.01)
        L.append(front)
        n_fill.append(nf)
    t, L = np.array(t), np.array(L)
    return dict(H=H, seed=seed, a_wall=a_wall, t=t.tolist(), L=L.tolist(), n_fill=n_fill, n_core=n_core, wall_s=wall_s,
                N=summ["particles"], steps=steps, penetrations=penetrations(summ)[0],
                box=[Lx, Ly, Lz], Ls=Ls, Lr=Lr, prefill=prefill)


def front_of(rho, level, first):
    """Distance from the mouth of the first bin (from bin `first` on) whose density is below level,
    linearly interpolated between bin centres (bins of 0.5 rc from the mouth)."""
    below = np.nonzero(rho[first:] < level)[0]
    if not len(below):
        return 0.5 * len(rho)
    k = int(below[0]) + first
    if k == 0:
        return 0.0
    f = (rho[k - 1] - level) / max(rho[k - 1] - rho[k], 1e-12)
    return 0.5 * (k - 1) + 0.25 + 0.5 * min(max(f, 0.0), 1.0)


def per_width(v, i):
    """The i-th width's value of a per-width option (one value: every width)."""
    return float(v[i] if len(v) > 1 else v[0])


def fit_k(t, L, lo, hi):
    """L^2 = k (t - t0) by least squares over lo <= L <= hi (before L first exceeds hi)."""
    t, L = np.asarray(t), np.asarray(L)
    stop = np.nonzero(L > hi)[0]
    end = stop[0] if len(stop) else len(L)
    m = np.zeros(len(L), bool)
    m[:end] = L[:end] >= lo
    if m.sum() < 4:
        return float("nan"), float("nan"), m
    k, c = np.polyfit(t[m], L[m] ** 2, 1)
    return float(k), float(-c / k), m


def washburn(args, work):
    out = []
    th, dth = THETA[args.a_wall]
    c, dc = math.cos(math.radians(th)), math.sin(math.radians(th)) * math.radians(dth)
    for i, (H, steps) in enumerate(zip(args.widths, args.steps_w)):
        Ls, Lr, pre = (per_width(v, i) for v in (args.slit_length, args.reservoir, args.prefill))
        seeds = args.seeds_per_width[i].split(",") if args.seeds_per_width else args.seeds
        runs = [washburn_run(args, work, H, int(sd), args.a_wall, steps, Ls, Lr, pre) for sd in seeds]
        # the fit window: in rc, or (default) from H to 2 H, where the slit's Poiseuille resistance
        # dominates the entrance's (the local slopes below show where that starts)
        lo, hi = args.fit_window if args.fit_window else (args.fit_window_h[0] * H, args.fit_window_h[1] * H)
        ks, halves = [], []
        # the liquid's density in the slit's core (1-3 rc behind the mouth, 1.5 rc from the walls) while
        # the front is in the fit window: the viscosity is the bulk liquid's at this density
        n = float(np.nanmean([v for r in runs for v, LL in zip(r["n_core"], r["L"])
                              if lo <= LL <= hi]))
        mu, dmu = mu_of(n)
        for r in runs:
            k, t0, m = fit_k(r["t"], r["L"], lo, hi)
            mid = lo + 0.5 * (hi - lo)
            k1, _, _ = fit_k(r["t"], r["L"], lo, mid)
            k2, _, _ = fit_k(r["t"], r["L"], mid, hi)
            r.update(k=k, t0=t0, k_first_half=k1, k_second_half=k2, fit_points=int(m.sum()))
            ks.append(k)
            halves += [k1, k2]
        k = float(np.mean(ks))
        dk = float(np.std(ks, ddof=1) / math.sqrt(len(ks))) if len(ks) > 1 else 0.0
        dk = max(dk, 0.5 * abs(np.nanmax(halves) - np.nanmin(halves)) / math.sqrt(len(halves)))
        b, db = SLIP
        slipf = 1 + 6 * b / H
        kW = GAMMA_LV[0] * c * H * slipf / (3 * mu)
        dkW = kW * math.sqrt((GAMMA_LV[1] / GAMMA_LV[0]) ** 2 + (dc / c) ** 2 + (dmu / mu) ** 2
                             + (6 * db / H / slipf) ** 2)
        ratio = k / kW
        dratio = ratio * math.hypot(dk / k, dkW / kW)
        # the window in --segments parts of L: the local slope in each (+- the seeds' spread)
        segs = []
        edges_L = np.linspace(lo, hi, args.segments + 1)
        for a, b_ in zip(edges_L[:-1], edges_L[1:]):
            kk, tm = [], []
            for r in runs:
                k_, _, m = fit_k(r["t"], r["L"], a, b_)
                if np.isfinite(k_):
                    kk.append(k_)
                    tm += np.asarray(r["t"])[m].tolist()
            if kk:
                u = float(np.mean(kk)) / (a + b_)
                segs.append(dict(L_lo=float(a), L_hi=float(b_), t_mid=float(np.mean(tm)), k=float(np.mean(kk)),
                                 k_spread=float(np.std(kk)), seeds=len(kk), u=u, capillary_number=mu * u / GAMMA_LV[0]))
        # early regime: log-log slope of L(t) from L = 1 rc to the fit window (first run)
        r0 = runs[0]
        tt, LL = np.array(r0["t"]), np.array(r0["L"])
        first = np.nonzero(LL >= 3.0)[0]
        e = (LL >= 1.0) & (np.arange(len(LL)) < (first[0] if len(first) else len(LL)))
        early = float(np.polyfit(np.log(tt[e]), np.log(LL[e]), 1)[0]) if e.sum() >= 3 else float("nan")
        tau = n * H * H / (12 * mu)
        out.append(dict(H=H, runs=runs, fit_window=[lo, hi], n=n, mu=mu, mu_err=dmu, theta=th, theta_err=dth, slip=b,
                        slip_factor=slipf, k=k, k_err=dk, k_washburn=kW, k_washburn_err=dkW, ratio=ratio,
                        ratio_err=dratio,
                        early_exponent=early, tau_inertial=tau, segments=segs,
                        passed=bool(abs(ratio - 1) <= args.tol_washburn + 2 * dratio)))
    return out


# ---------------------------------------------------------------- entry pressure
def entry_pc():
    cw, co = (math.cos(math.radians(THETA[a][0])) for a in (-35.0, -20.0))
    dcw, dco = (math.sin(math.radians(THETA[a][0])) * math.radians(THETA[a][1]) for a in (-35.0, -20.0))
    gc = GAMMA_LV[0] * (cw - co)
    dgc = math.hypot(GAMMA_LV[1] * (cw - co), GAMMA_LV[0] * math.hypot(dcw, dco))
    return gc, dgc


def throat_profile(steps, wat, oil, H, ws, Lc, Lo, Lx, Lz, dy=0.1):
    """The liquid-filled width of the throat from the wall-normal density profile (second half of the run).

    Profile: water and oil per 0.1 rc bin across the throat's pore (y in [ws, ws + H)), over x in
    [Lc + 2, Lx - 1] (2 rc past the mouth, 1 rc before the exit). Bulk: all liquid in the chamber's water
    part x in [1.5, Lc - Lo - 1.5] (no walls across y there; the same liquid, at a pressure within
    n f x 6 rc of the throat's). Widths:
      equimolar  H_eq = int (n_w + n_o) dy / n_bulk, the width of uniform bulk liquid holding the same
                 particles: the distance between the Gibbs equimolar surfaces at the two walls, where the
                 liquid's adsorption is zero;
      half       the distance between the outermost points where the total density crosses
                 n_bulk / 2 (0.1 rc bins; the wall's face when the first bin is already above);
      films      int n_w dy / n_bulk and int n_o dy / n_bulk (each liquid's equimolar share of the width).
    Errors: standard error over 4 blocks of snapshots."""
    half = len(steps) // 2
    edges = ws + dy * np.arange(int(round(H / dy)) + 1)
    x0, x1 = Lc + 2.0, Lx - 1.0
    per = []  # (H_eq, water, oil, n_bulk) per snapshot
    n_w = np.zeros(len(edges) - 1)
    n_o = np.zeros(len(edges) - 1)
    nb_all = []
    for (xw, _), (xo, _) in zip(wat[half:], oil[half:]):
        hw = np.histogram(xw[(xw[:, 0] >= x0) & (xw[:, 0] < x1), 1], edges)[0] / (dy * (x1 - x0) * Lz)
        ho = np.histogram(xo[(xo[:, 0] >= x0) & (xo[:, 0] < x1), 1], edges)[0] / (dy * (x1 - x0) * Lz)
        ca, cb = 1.5, Lc - Lo - 1.5
        nb = (np.sum((xw[:, 0] >= ca) & (xw[:, 0] < cb)) + np.sum((xo[:, 0] >= ca) & (xo[:, 0] < cb))) / (
            (cb - ca) * (ws + H) * Lz)
        n_w += hw
        n_o += ho
        nb_all.append(nb)
        per.append((hw.sum() * dy / nb + ho.sum() * dy / nb, hw.sum() * dy / nb, ho.sum() * dy / nb, nb))
    ns = len(per)
    n_w, n_o, nb = n_w / ns, n_o / ns, float(np.mean(nb_all))
    per = np.array(per)
    blocks = np.array([b.mean(axis=0) for b in np.array_split(per, 4)])
    err = blocks.std(axis=0, ddof=1) / 2.0
    tot = n_w + n_o
    t2 = tot
    yc = 0.5 * (edges[1:] + edges[:-1])
    above = np.nonzero(t2 >= 0.5 * nb)[0]
    h_half = float("nan")
    if len(above):
        i, j = above[0], above[-1]

        def cross(a, b):  # the n_bulk / 2 crossing, linear between bin a (above) and bin b (below)
            f = (0.5 * nb - t2[b]) / max(t2[a] - t2[b], 1e-12)
            return yc[b] + f * (yc[a] - yc[b])
        lo_y = cross(i, i - 1) if i > 0 else edges[0]
        hi_y = cross(j, j + 1) if j < len(t2) - 1 else edges[-1]
        h_half = float(hi_y - lo_y)
    return dict(snapshots=ns, n_bulk=nb, H_eq=float(per[:, 0].mean()), H_eq_err=float(err[0]),
                water_width=float(per[:, 1].mean()), oil_width=float(per[:, 2].mean()),
                oil_width_err=float(err[2]), H_half=h_half,
                y=(0.5 * (edges[1:] + edges[:-1]) - ws).tolist(), n_w=n_w.tolist(), n_o=n_o.tolist())


def meniscus_circle(steps, wat, oil, H, ws, Lc):
    """The resting meniscus's circle (second half of a run the oil did not invade): water and oil counted in
    bins of 0.25 rc along x by 0.5 rc across the throat over x in [Lc - 4, Lc + 6] (all z, all snapshots
    summed); in each row the x where phi = (n_w - n_o) / (n_w + n_o) first turns positive (linear between
    bins); an algebraic circle fit to the rows more than 1 rc from the walls. Laplace in a slit (curvature
    in x-y only): dp = gamma_wo / R."""
    half = len(steps) // 2
    xe = np.arange(Lc - 4, Lc + 6 + 1e-9, 0.25)
    ye = np.arange(ws, ws + H + 1e-9, 0.5)
    cw = np.zeros((len(xe) - 1, len(ye) - 1))
    co = np.zeros_like(cw)
    for (xw, _), (xo, _) in zip(wat[half:], oil[half:]):
        cw += np.histogram2d(xw[:, 0], xw[:, 1], [xe, ye])[0]
        co += np.histogram2d(xo[:, 0], xo[:, 1], [xe, ye])[0]
    phi = (cw - co) / np.maximum(cw + co, 1)
    xc, yc = 0.5 * (xe[1:] + xe[:-1]), 0.5 * (ye[1:] + ye[:-1])
    pts = []
    for j, yy in enumerate(yc):
        k = np.nonzero(phi[:, j] > 0)[0]
        if len(k) and k[0] > 0:
            a, b = phi[k[0] - 1, j], phi[k[0], j]
            pts.append((xc[k[0] - 1] + (0 - a) / (b - a) * 0.25, yy))
    pts = np.array(pts)
    m = (pts[:, 1] > ws + 1.0) & (pts[:, 1] < ws + H - 1.0) if len(pts) else np.zeros(0, bool)
    if m.sum() < 5:
        return dict(R=float("nan"))
    X, Y = pts[m, 0], pts[m, 1]
    sol = np.linalg.lstsq(np.c_[2 * X, 2 * Y, np.ones(len(X))], X ** 2 + Y ** 2, rcond=None)[0]
    R = float(math.sqrt(sol[2] + sol[0] ** 2 + sol[1] ** 2))
    rms = float(np.sqrt(np.mean((np.hypot(X - sol[0], Y - sol[1]) - R) ** 2)))
    return dict(R=R, x_centre=float(sol[0] - Lc), y_centre=float(sol[1] - ws), rms=rms, points=int(m.sum()),
                apex=float(pts[np.argmin(np.abs(pts[:, 1] - (ws + H / 2))), 0] - Lc))


def entry_run(args, work, H, ratio, gc):
    ws, Lc, Lo, Lt, Lz = 4.0, args.chamber, args.chamber / 2, args.throat, args.lz
    Lx, Ly = Lc + Lt, H + ws
    lab = np.zeros((vox(Lx), vox(Ly), vox(Lz)), dtype=np.uint8)
    lab[vox(Lc):, :vox(ws), :] = 1
    tag = f"entry_H{H:g}_r{ratio:g}"
    os.makedirs(work, exist_ok=True)
    image = write_raw_image(os.path.join(work, f"entry_H{H:g}.raw"), lab)
    patches = os.path.join(work, "patches-e0.5-d8-s1.h5")
    pc = 2 * gc / H
    n0 = 6.1  # the liquids' density at rest (the force's target; dp is recomputed from the profile)
    f = ratio * pc / (n0 * Lx)
    pairs = {"water-wall": {"A": -35.0}, "oil-wall": {"A": -20.0}, "water-oil": {"A": -20.0}}
    s = scene(tag, (Lx, Ly, Lz), image, patches, ["water", "oil"], pairs, args.steps_e, args.seeds[0],
              second=("oil", [Lc - Lo, 0, 0], [Lc, Ly, Lz]), force=f, every=args.every_e)
    wd = os.path.join(work, tag)
    wall_s = run_or_reuse(s, wd, 1, args.reuse)
    summ = json.load(open(os.path.join(wd, "summary.json")))
    steps, oil, _ = read_snapshots(wd, 0, species=1)
    _, wat, _ = read_snapshots(wd, 0, species=0)
    depth, nint = [], []
    for (xo, _), (xw, _) in zip(oil, wat):
        in_t = (xo[:, 0] >= Lc) & (xo[:, 1] >= ws)
        # n along the loop: the chamber's particles per unit length / cross-section, the throat's
        xa = np.concatenate([xo[:, 0], xw[:, 0]])
        ya = np.concatenate([xo[:, 1], xw[:, 1]])
        ch = xa < Lc
        th = (xa >= Lc) & (ya >= ws)
        nint.append(ch.sum() / (Ly * Lz) + th.sum() / (H * Lz))
        n_t = max(th.sum() / (H * Lz * Lt), 1e-9)
        depth.append(in_t.sum() / (n_t * H * Lz))
    depth = np.array(depth)
    prof = throat_profile(steps, wat, oil, H, ws, Lc, Lo, Lx, Lz)
    men = meniscus_circle(steps, wat, oil, H, ws, Lc)
    q = len(depth) * 3 // 4
    dp = f * float(np.mean(nint))
    d_end = float(np.mean(depth[q:]))
    half = len(depth) // 2
    growth = float(np.polyfit(np.array(steps[half:]) * 0.01, depth[half:], 1)[0]) if len(depth) - half >= 3 else 0.0
    return dict(H=H, ratio_target=ratio, force=f, dp=dp, dp_over_pc=dp / pc, depth_end=d_end,
                depth_growth=growth, depth=depth.tolist(), t=[st * 0.01 for st in steps],
                advanced=bool(d_end > args.enter_depth),
                entered=bool(np.max(depth) >= Lt - 0.5 or (d_end > args.enter_depth and growth > args.enter_rate)),
                wall_s=wall_s, N=summ["particles"], steps=args.steps_e, penetrations=penetrations(summ)[0],
                throat=prof, meniscus=men)


def entry(args, work):
    gc, dgc = entry_pc()
    H = args.entry_width
    pc, dpc = 2 * gc / H, 2 * dgc / H
    rungs = [entry_run(args, work, H, r, gc) for r in args.ratios]
    # entered: the oil reached the throat's exit (invasion); advanced: past the mouth's bulge only
    no = [r["dp"] for r in rungs if not r["entered"]]
    yes = [r["dp"] for r in rungs if r["entered"]]
    lo = max(no) if no else 0.0
    hi = min(yes) if yes else float("inf")
    tol = args.tol_entry
    ok_nominal = bool(no and yes and lo < hi and lo * (1 - tol) <= pc <= hi * (1 + tol))
    # The width Young-Laplace needs: advancing the meniscus by dx displaces the water's volume H_eff Lz dx
    # against dp and replaces water-wall by oil-wall tension over 2 Lz dx. The tensions from Young's
    # equation (angles at coexistence, p ~ 0) hold at the throat's pressure only for the dividing surface
    # where the liquid's adsorption is zero (Gibbs: d gamma = -Gamma dp / n), the equimolar surface; so
    # H_eff is the water-filled throat's equimolar width, measured in the rungs whose profile window holds
    # water only (less than 0.1 rc of oil: the meniscus and its density dip stay outside it).
    wet = [r["throat"] for r in rungs if not r["entered"] and r["throat"]["oil_width"] < 0.1]
    h_eff = float(np.mean([w["H_eq"] for w in wet])) if wet else float("nan")
    h_eff_err = float(np.sqrt(np.mean([w["H_eq_err"] ** 2 for w in wet])) if wet else float("nan"))
    h_half = float(np.mean([w["H_half"] for w in wet])) if wet else float("nan")
    pc_eff = 2 * gc / h_eff
    pc_eff_err = pc_eff * math.hypot(dgc / gc, h_eff_err / h_eff)
    ok = bool(no and yes and lo < hi and lo * (1 - tol) <= pc_eff <= hi * (1 + tol))
    # Laplace at rest: each meniscus the oil did not push through, its curvature against dp / gamma_wo, and
    # the apparent angle it makes with the walls, cos theta_app = (H_eff / 2) / R (through the water)
    for r in rungs:
        mn = r["meniscus"]
        if not r["entered"] and math.isfinite(mn.get("R", float("nan"))):
            mn.update(laplace_dp=GAMMA_WO[0] / mn["R"], cos_app=min(0.5 * h_eff / mn["R"], 1.0))
    return dict(H=H, gamma_cos=gc, gamma_cos_err=dgc, theta_wo=math.degrees(math.acos(gc / GAMMA_WO[0])),
                pc=pc, pc_err=dpc, rungs=rungs, bracket=[lo, hi], passed_nominal=ok_nominal,
                H_eff=h_eff, H_eff_err=h_eff_err, H_half=h_half, pc_eff=pc_eff, pc_eff_err=pc_eff_err,
                oil_filled=[dict(dp_over_pc=r["dp_over_pc"], **{k: r["throat"][k] for k in (
                    "H_eq", "H_eq_err", "water_width", "oil_width", "H_half")}) for r in rungs
                    if r["entered"] and max(r["depth"]) >= args.throat - 0.5],
                passed=ok)


# ---------------------------------------------------------------- report
def report(res, out, args):
    L = ["# Capillarity in image slits: Washburn imbibition and entry pressure\n",
         "mDPD A = -40, B = 25, rd = 0.75, gamma = 4.5, kT = 1, dt = 0.01, fluid density 6.2; image walls "
         "(0.5 rc voxels, patches at density 8), bounce_back, 1 rank.\n"]
    wb = res.get("washburn")
    if wb:
        L += [f"## Washburn imbibition (liquid-wall A = {args.a_wall:g}, theta = {THETA[args.a_wall][0]} +- "
              f"{THETA[args.a_wall][1]} deg, slip b = {SLIP[0]} +- {SLIP[1]} rc)\n",
              "Fit L^2 = k (t - t0) over the window of each row (L in rc, from the mouth); "
              "k_W = gamma cos(theta) H (1 + 6b/H) / (3 mu), gamma = 7.54, mu at the filled slit's density.\n",
              "| H | N | steps | seeds: k | k (mean) | n core | mu | k_W | k / k_W | L end | "
              "early d lnL/d ln t (L 1-3 rc) | rho H^2/(12 mu) | wall s | check |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for w in wb:
            ks = ", ".join(f"{r['k']:.3f}" for r in w["runs"])
            L.append(f"| {w['H']:g} | {w['runs'][0]['N']} | {w['runs'][0]['steps']} | {ks} | {w['k']:.3f} +- "
                     f"{w['k_err']:.3f} | {w['n']:.3f} | {w['mu']:.3f} | {w['k_washburn']:.3f} +- "
                     f"{w['k_washburn_err']:.3f} | **{w['ratio']:.3f} +- {w['ratio_err']:.3f}** | "
                     f"{', '.join('%.1f' % r['L'][-1] for r in w['runs'])} | {w['early_exponent']:.2f} | "
                     f"{w['tau_inertial']:.2f} | {sum(r['wall_s'] for r in w['runs']):.0f} | "
                     f"{'pass' if w['passed'] else 'FAIL'} |")
        L += ["", "The fit window in parts (the same fit over each part of the L window, mean of the seeds that "
              "reached it, +- their spread): the local slope against k_W.\n",
              "| H | L (rc) | seeds | t mid | k local | k / k_W | front speed u = k / (2 L) | Ca = mu u / gamma |",
              "|---|---|---|---|---|---|---|---|"]
        for w in wb:
            for g in w.get("segments", []):
                L.append(f"| {w['H']:g} | {g['L_lo']:.1f}-{g['L_hi']:.1f} | {g['seeds']} | {g['t_mid']:.0f} | {g['k']:.3f} +- "
                         f"{g['k_spread']:.3f} | {g['k'] / w['k_washburn']:.3f} | {g['u']:.3f} | "
                         f"{g['capillary_number']:.3f} |")
        L.append("")
    en = res.get("entry")
    if en:
        L += [f"## Entry pressure of oil into a water-filled slit throat H = {en['H']:g}\n",
              f"gamma_wo cos(theta_wo) = gamma_lv (cos theta_w - cos theta_o) = {en['gamma_cos']:.3f} +- "
              f"{en['gamma_cos_err']:.3f} (theta_wo = {en['theta_wo']:.1f} deg with gamma_wo = 14.72); "
              f"dp_c = 2 gamma_wo cos(theta_wo) / H = **{en['pc']:.3f} +- {en['pc_err']:.3f}**.\n",
              "| force | dp = f int n dx | dp / dp_c | oil depth in the throat, last quarter (rc) | its growth, "
              "second half (rc per time) | advanced (depth > " + f"{args.enter_depth:g}" + ") | "
              "invading (at the exit or still advancing) | N | wall s |",
              "|---|---|---|---|---|---|---|---|---|"]
        for r in en["rungs"]:
            L.append(f"| {r['force']:.5f} | {r['dp']:.3f} | {r['dp_over_pc']:.3f} | {r['depth_end']:.2f} | "
                     f"{r.get('depth_growth', 0):+.4f} | {'yes' if r.get('advanced') else 'no'} | "
                     f"{'yes' if r['entered'] else 'no'} | {r['N']} | {r['wall_s']:.0f} |")
        lo, hi = en["bracket"]
        L += ["", "The throat's liquid-filled width (second half of each run; profile over x in [Lc + 2, Lx - 1], "
              "0.1 rc bins; bulk: the chamber's water part): equimolar H_eq = int (n_w + n_o) dy / n_bulk, half: "
              "between the outermost n_bulk / 2 crossings; water and oil: each liquid's equimolar share.\n",
              "| dp / dp_c | throat holds | n_bulk | H_eq | H - H_eq | half-density width | water | oil |",
              "|---|---|---|---|---|---|---|---|"]
        for r in en["rungs"]:
            t = r["throat"]
            held = "oil" if max(r["depth"]) >= args.throat - 0.5 else ("water" if not r["entered"] else "both")
            L.append(f"| {r['dp_over_pc']:.3f} | {held} | {t['n_bulk']:.3f} | {t['H_eq']:.3f} +- {t['H_eq_err']:.3f} | "
                     f"{en['H'] - t['H_eq']:.3f} | {t['H_half']:.3f} | {t['water_width']:.3f} | {t['oil_width']:.3f} |")
        L += ["", f"H_eff (H_eq of the rungs whose window holds water only) = **{en['H_eff']:.3f} +- "
              f"{en['H_eff_err']:.3f}** (half-density width {en['H_half']:.3f}); dp_c = 2 gamma_wo cos(theta_wo) / "
              f"H_eff = **{en['pc_eff']:.3f} +- {en['pc_eff_err']:.3f}**.\n",
              "The resting menisci (rungs not invading): circle through the phi = 0 points more than 1 rc from the "
              "walls; Laplace: dp = gamma_wo / R (gamma_wo = 14.72); cos theta_app = (H_eff / 2) / R.\n",
              "| dp / dp_c | dp | apex past the mouth (rc) | R | rms (rc) | gamma_wo / R | dp R / gamma_wo | "
              "theta_app (deg) |", "|---|---|---|---|---|---|---|---|"]
        for r in en["rungs"]:
            mn = r["meniscus"]
            if "laplace_dp" in mn:
                L.append(f"| {r['dp_over_pc']:.3f} | {r['dp']:.3f} | {mn['apex']:.2f} | {mn['R']:.2f} | "
                         f"{mn['rms']:.2f} | "
                         f"{mn['laplace_dp']:.3f} | {r['dp'] / mn['laplace_dp']:.3f} | "
                         f"{math.degrees(math.acos(mn['cos_app'])):.1f} |")
        L.append(f"\nBracket (invasion): highest dp not invading {lo:.3f}, lowest invading {hi:.3f} "
                 f"({lo / en['pc']:.2f}-{hi / en['pc']:.2f} dp_c with H, "
                 f"{lo / en['pc_eff']:.2f}-{hi / en['pc_eff']:.2f} "
                 f"with H_eff); dp_c(H) {en['pc']:.3f}: {'pass' if en['passed_nominal'] else 'FAIL'}; dp_c(H_eff) "
                 f"{en['pc_eff']:.3f}: {'pass' if en['passed'] else 'FAIL'} (bracket widened by "
                 f"{100 * args.tol_entry:.0f}%; the check uses H_eff).\n")
    L.append(f"Command: `/usr/bin/python3 validation/twophase/capillary.py {' '.join(sys.argv[1:])}`\n")
    open(os.path.join(out, "capillary.md"), "w").write("\n".join(L))
    print("\n".join(L))


def plot(res, out):
    plt = mdval.pyplot()
    fig, axs = plt.subplots(1, 4, figsize=(20, 4))
    for w in res.get("washburn", []):
        for r in w["runs"]:
            t, L = np.array(r["t"]), np.array(r["L"])
            axs[0].plot(t, L ** 2, ".", ms=3, label=f"H={w['H']:g} seed {r['seed']}")
            axs[1].loglog(t[L > 0.3], L[L > 0.3], "-", lw=0.8)
        tt = np.linspace(0, max(w["runs"][0]["t"]), 50)
        t0 = w["runs"][0]["t0"]
        axs[0].plot(tt, w["k_washburn"] * np.maximum(tt - t0, 0), "k--", lw=0.8)
        axs[0].plot(tt, w["k"] * np.maximum(tt - t0, 0), "r-", lw=0.8)
    axs[0].set_xlabel("t")
    axs[0].set_ylabel("L^2 (red: fit, dashed: Washburn, static angle)")
    axs[0].legend(fontsize=7)
    axs[1].set_xlabel("t")
    axs[1].set_ylabel("L")
    axs[1].set_title("early regime (log-log)")
    en = res.get("entry")
    if en:
        for r in en["rungs"]:
            axs[2].plot(r["t"], r["depth"], label=f"dp/dp_c = {r['dp_over_pc']:.2f}")
        axs[2].set_xlabel("t")
        axs[2].set_ylabel("oil depth in the throat (rc)")
        axs[2].set_title(f"entry, H = {en['H']:g}: dp_c = {en['pc']:.2f}")
        axs[2].legend(fontsize=7)
        for r in en["rungs"]:  # the throat's wall-normal profiles: water-filled and oil-filled rungs
            t = r.get("throat")
            if t and (t["oil_width"] < 0.1 or max(r["depth"]) >= 5.5):
                axs[3].plot(t["y"], np.array(t["n_w"]) + np.array(t["n_o"]), lw=0.8,
                            label=f"{r['dp_over_pc']:.2f} dp_c: n_w + n_o")
                if t["oil_width"] >= 0.1:
                    axs[3].plot(t["y"], t["n_w"], "k:", lw=0.8, label=f"{r['dp_over_pc']:.2f} dp_c: water")
        if "H_eff" in en:
            axs[3].set_title(f"throat H = {en['H']:g}: H_eff = {en['H_eff']:.2f} (equimolar)")
        axs[3].set_xlabel("y from the wall's voxel face (rc)")
        axs[3].set_ylabel("density across the throat")
        axs[3].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "capillary.png"), dpi=110)


def quick(args, work):
    """The ctest: a wetting slit (H = 4) imbibes with L^2 linear in t; a non-wetting one (A = -20) stays dry."""
    fails = []
    r = washburn_run(args, work, 4.0, 1, -35.0, args.steps_w)
    t, L = np.array(r["t"]), np.array(r["L"])
    k, t0, m = fit_k(t, L, 2.0, 7.0)
    k1, _, _ = fit_k(t, L, 2.0, 4.5)
    k2, _, _ = fit_k(t, L, 4.5, 7.0)
    print(f"wetting H = 4: L_end = {L[-1]:.2f} rc, k = {k:.3f} (halves {k1:.3f}, {k2:.3f}), "
          f"{m.sum()} points; {r['wall_s']:.0f} s")
    if not (L[-1] > 5.0):
        fails.append(f"the wetting slit did not imbibe 5 rc (L_end = {L[-1]:.2f})")
    elif not (0.5 < k1 / k2 < 2.0):
        fails.append(f"L^2 not linear in t: k {k1:.3f} over 2-4.5 rc, {k2:.3f} over 4.5-7 rc")
    kW = GAMMA_LV[0] * math.cos(math.radians(68.6)) * 4 * (1 + 6 * SLIP[0] / 4) / (3 * mu_of(6.1)[0])
    if not (0.3 < k / kW < 1.5):
        fails.append(f"k / k_Washburn = {k / kW:.3f} outside [0.3, 1.5]")
    d = washburn_run(args, work, 4.0, 1, -20.0, args.steps_dry)
    print(f"non-wetting H = 4 (A = -20): L_end = {d['L'][-1]:.2f} rc; {d['wall_s']:.0f} s")
    if not (d["L"][-1] < 1.5):
        fails.append(f"the non-wetting slit took liquid: L_end = {d['L'][-1]:.2f} rc")
    for x in (r, d):
        if x["penetrations"] != 0:
            fails.append(f"{x['penetrations']} samples with penetrations")
    return fails


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--parts", nargs="+", default=["washburn", "entry"], choices=["washburn", "entry"])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--widths", type=float, nargs="+", default=[6.0, 10.0])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--a-wall", type=float, default=-35.0, choices=sorted(THETA))
    ap.add_argument("--lz", type=float, default=3.0)
    ap.add_argument("--slit-length", type=float, nargs="+", default=[16.0, 24.0], help="rc; one value or one per width")
    ap.add_argument("--reservoir", type=float, nargs="+", default=[12.0, 16.0], help="rc; one value or one per width")
    ap.add_argument("--prefill", type=float, nargs="+", default=[0.0, 6.0],
                    help="rc of the slit filled at the start (the fit window must start beyond it); one value or "
                         "one per width")
    ap.add_argument("--seeds-per-width", nargs="+", default=None,
                    help="comma-separated seeds of each width (instead of --seeds), e.g. 1,2 1")
    ap.add_argument("--steps-w", type=int, nargs="+", default=[22000, 38000], help="steps per width")
    ap.add_argument("--steps-dry", type=int, default=2000)
    ap.add_argument("--steps-quick", type=int, default=10000)
    ap.add_argument("--every", type=int, default=200)
    ap.add_argument("--fit-window", type=float, nargs=2, default=None, help="rc (instead of --fit-window-h)")
    ap.add_argument("--fit-window-h", type=float, nargs=2, default=[1.0, 2.0],
                    help="the fit window in units of the width H (default H to 2 H: L > H)")
    ap.add_argument("--segments", type=int, default=3, help="parts of the fit window for the local slope")
    ap.add_argument("--entry-width", type=float, default=6.0)
    ap.add_argument("--chamber", type=float, default=12.0)
    ap.add_argument("--throat", type=float, default=6.0)
    ap.add_argument("--ratios", type=float, nargs="+", default=[0.6, 0.85, 1.15, 1.4, 1.8, 2.3])
    ap.add_argument("--steps-e", type=int, default=8000)
    ap.add_argument("--every-e", type=int, default=250)
    ap.add_argument("--enter-depth", type=float, default=2.0)
    ap.add_argument("--enter-rate", type=float, default=0.01,
                    help="rc per time unit: a depth past --enter-depth still growing this fast invades")
    ap.add_argument("--tol-washburn", type=float, default=0.2)
    ap.add_argument("--tol-entry", type=float, default=0.2)
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    base = os.environ.get("MDPORE_VALIDATION_OUT")
    if args.quick:
        args.slit_length, args.reservoir, args.steps_w = [12.0], [8.0], args.steps_quick
        work = os.path.join(base or "/tmp", "capillary_quick")
        fails = quick(args, work)
        for f in fails:
            print("FAIL:", f)
        print("capillary quick:", "all checks pass" if not fails else f"{len(fails)} check(s) failed")
        sys.exit(1 if fails else 0)
    for opt in ("steps_w", "slit_length", "reservoir", "prefill", "seeds_per_width"):
        v = getattr(args, opt)
        if v is not None and len(v) not in ((1, len(args.widths)) if opt != "steps_w" else (len(args.widths),)):
            widths = " ".join(f"{w:g}" for w in args.widths)
            alt = " or one value" if opt != "steps_w" else ""
            sys.exit(f"capillary.py: option --{opt.replace('_', '-')}: expected one value per width "
                     f"({len(args.widths)}: {widths}){alt}, got {len(v)}: {' '.join(str(x) for x in v)}")
    out = args.out or mdval.out_dir("twophase")
    os.makedirs(out, exist_ok=True)
    work = os.path.join(base or "/tmp", "capillary_runs")
    jpath = os.path.join(out, "capillary.json")
    res = json.load(open(jpath)) if os.path.exists(jpath) else {}
    if "washburn" in args.parts:
        res["washburn"] = washburn(args, work)
        mdval.write_json(jpath, res)
    if "entry" in args.parts:
        res["entry"] = entry(args, work)
        mdval.write_json(jpath, res)
    report(res, out, args)
    plot(res, out)
    fails = [f"Washburn H = {w['H']:g}: k / k_W = {w['ratio']:.3f} +- {w['ratio_err']:.3f}"
             for w in res.get("washburn", []) if not w["passed"]]
    en = res.get("entry")
    if en and not en["passed"]:
        fails.append(f"entry H = {en['H']:g}: bracket {en['bracket'][0]:.3f}-{en['bracket'][1]:.3f} (widened by "
                     f"{100 * args.tol_entry:.0f}%) vs dp_c(H_eff) {en['pc_eff']:.3f} (dp_c(H) {en['pc']:.3f})")
    pen = [r for w in res.get("washburn", []) for r in w["runs"] if r["penetrations"]]
    pen += [r for r in (en or {}).get("rungs", []) if r["penetrations"]]
    if pen:
        fails.append(f"{len(pen)} run(s) with penetrations")
    for f in fails:
        print("FAIL:", f)
    print("capillary:", "all checks pass" if not fails else f"{len(fails)} check(s) failed")
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
