#!/usr/bin/python3
"""Viscosity ratio M = mu_oil / mu_water of two mDPD liquids through the thermostat weight's exponent
(docs/twophase.md section 4).

Each liquid's viscosity is set by its like pair's thermostat: gamma and the exponent s of the weight
w_R = (1 - r/rc)^s, w_D = w_R^2 (pairs.X.s; Fan et al., Phys. Fluids 18, 063102, 2006). A, B and rd,
hence the equation of state, the interface tension and the wetting, are those of water for both.

Parts (--parts, default both):
  visc     reverse Poiseuille (twophase.viscosity: box 8 x 16 x 6, density 6.05, g = 0.05 flipped along
           y, dt = 0.01, 1 rank) of each (gamma, s) in --settings (water 4.5,1 first): mu, M = mu / mu_water,
           and the thermal temperature T (the run's kinetic temperature less the flow's part, from the
           velocity profile) against the set kT = 1. Check: |T - 1| <= 0.01 + 2 sigma for every setting
           listed in --stable (the documented range); the others are reported.
  coflow   layered co-current flow in a slit (twophase.slit: h = --h, A_wo = --a-wo, Sw = 0.5, g = 0.05 on
           both liquids) for each oil in --coflow (gamma,s pairs), with M from the visc part, against the
           exact krw = Sw^2 (3 - Sw) / 2, krn = (1 - Sw)^3 + (3/2) M Sw (2 - Sw) (1 - Sw) at the hydraulic
           Sw (twophase.coflow_analysis; |kr - exact| <= 0.1 + 2 sigma).

Results: validation/results/twophase/viscosity_ratio.{md,json,png}.
    /usr/bin/python3 validation/twophase/viscosity_ratio.py
--quick (the ctest): water and the oil 13.5,0.25 (or --settings) in a box 4 x 16 x 4, 5000 steps (the
first 2000 discarded), no co-flow; fails unless M lies in --m-bounds and both temperatures are within 1%.
"""
import argparse
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "engine"))
import mdval  # noqa: E402
import twophase as tp  # noqa: E402

DEFAULT_SETTINGS = ["4.5,1", "4.5,0.5", "13.5,0.5", "4.5,0.25", "13.5,0.25", "27,0.25", "40,0.25", "54,0.25"]
# the documented stable range at dt = 0.01 (gamma 40 and 54 at s 0.25 stop within their first steps: listed to
# show where the range ends)
DEFAULT_STABLE = DEFAULT_SETTINGS[:-2]


def interface_velocity(single, rr, h, g, mu_w, wt=2.0):
    """Where a layered run's oil flux is lost: the film's velocity at the interface against the water-only
    run's at the same place.

    With the stress tau(y) = g int_mid^y n dy fixed by the momentum balance (n: all liquid; the same in
    both runs within 1-2%), a continuum film of water's viscosity moves exactly as the water-only slit
    at the same y, whatever the core holds. So r_i = u(y_i) / u_single(y_i) is 1 in the continuum, and
    the deficit, expressed as a layer of thickness delta = (u_single - u) mu_w / tau(y_i) that does not
    shear (the extra resistance of the interface zone), measures what the interface costs the film.
    y_i: where phi = (n_w - n_o) / (n_w + n_o) crosses 0; profiles symmetrised about the slit's middle.
    Also the local viscosity tau / (-du/dy) averaged over the 0.5 rc on each side of y_i."""
    y = np.asarray(rr["y"])
    dy = y[1] - y[0]
    mid = wt + h / 2
    up = y > mid

    def sym(a):
        a = np.asarray(a)
        return 0.5 * (a[up] + np.interp(2 * mid - y[up], y, a))
    ys = y[up] - mid
    u, us = sym(rr["u"]), sym(single["u"])
    nw, no = sym(rr["n_w"]), sym(rr["n_o"])
    phi = (nw - no) / np.maximum(nw + no, 1e-12)
    k = int(np.nonzero(phi > 0)[0][0])
    yi = float(ys[k - 1] + (0 - phi[k - 1]) / (phi[k] - phi[k - 1]) * dy)
    n = nw + no
    tau = g * (np.cumsum(n) - 0.5 * n) * dy
    ui, usi, taui = (float(np.interp(yi, ys, a)) for a in (u, us, tau))
    # bin errors of the two velocities at y_i (symmetrised: two bins averaged)
    e = math.hypot(*(float(np.interp(yi, ys, sym(r["u_err"]))) / math.sqrt(2) for r in (rr, single)))
    dudy = np.gradient(u, dy)

    def mu_loc(lo, hi):
        m = (ys >= lo) & (ys < hi)
        return float(np.sum(tau[m]) / max(-np.sum(dudy[m]), 1e-12))
    # the interface's 10-90 width of phi
    w_lo = float(np.interp(-0.8, phi, ys)) if np.all(np.diff(phi) >= -0.2) else float("nan")
    w_hi = float(np.interp(0.8, phi, ys)) if np.all(np.diff(phi) >= -0.2) else float("nan")
    return dict(y_i=yi, u_i=ui, u_single_i=usi, r_i=ui / usi, r_i_err=e / usi, tau_i=taui,
                delta=(usi - ui) * mu_w / taui, delta_err=e * mu_w / taui,
                mu_oil_side=mu_loc(yi - 0.5, yi), mu_water_side=mu_loc(yi, yi + 0.5), width_10_90=w_hi - w_lo,
                profile={"y": ys.tolist(), "u": u.tolist(), "u_single": us.tolist(), "phi": phi.tolist()})


def pair_list(words):
    return [tuple(float(v) for v in w.split(",")) for w in words]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--parts", nargs="+", default=["visc", "coflow"], choices=["visc", "coflow"])
    ap.add_argument("--settings", nargs="+", default=DEFAULT_SETTINGS,
                    help="gamma,s of each liquid measured; the first is the water (4.5,1)")
    ap.add_argument("--stable", nargs="*", default=None,
                    help="gamma,s settings that must run and keep T within 1%% of kT (default: all but 40,0.25 and 54,0.25; "
                         "with --settings: all)")
    ap.add_argument("--coflow", nargs="*", default=["13.5,0.25", "4.5,0.25"], help="gamma,s of the oils run in the slit")
    ap.add_argument("--steps", type=int, default=12000)
    ap.add_argument("--equil", type=int, default=3000)
    ap.add_argument("--h", type=float, default=6.0)
    ap.add_argument("--a-wo", type=float, default=-30.0)
    ap.add_argument("--g", type=float, default=0.05)
    ap.add_argument("--slit-steps", type=int, default=25000)
    ap.add_argument("--slit-equil", type=int, default=7000)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--m-bounds", type=float, nargs=2, metavar=("LO", "HI"),
                    help="fail unless LO <= M <= HI for the second setting (the ctest)")
    ap.add_argument("--out", default=None)
    ap.add_argument("--reuse", action="store_true", help="analyse finished runs again instead of running them")
    args = ap.parse_args()
    if args.quick:
        args.visc_box = (4.0, 16.0, 4.0)  # the full runs' width across the flow, thinner
        args.steps, args.equil = 5000, 2000
        if args.settings == DEFAULT_SETTINGS:
            args.settings = ["4.5,1", "13.5,0.25"]
        args.parts = ["visc"]
    tp.REUSE = args.reuse
    tp.A_WO = args.a_wo
    args.rho = 6.05
    args.visc_steps, args.visc_equil = args.steps, args.equil
    args.slit_x, args.slit_z = 6.0, 4.0
    args.slit_steps, args.slit_equil = args.slit_steps, args.slit_equil
    out = args.out or mdval.out_dir("twophase_viscosity_ratio" if args.quick else "twophase")
    raw = os.path.join(out, "viscosity_ratio_runs")
    os.makedirs(raw, exist_ok=True)
    jpath = os.path.join(out, "viscosity_ratio.json")
    settings = pair_list(args.settings)
    if args.stable is None:
        args.stable = DEFAULT_STABLE if args.settings == DEFAULT_SETTINGS else args.settings
    stable = pair_list(args.stable)
    fails = []
    res = {"settings": [], "coflow": {}}
    if os.path.exists(jpath) and "visc" not in args.parts:
        import json
        res = json.load(open(jpath))
    if "visc" in args.parts:
        for k, (gamma, s_exp) in enumerate(settings):
            try:
                v = tp.viscosity(args, raw, "water" if k == 0 else "oil", gamma, s_exp)
            except RuntimeError as e:  # the run stopped (its stderr says why): unstable at this dt
                v = dict(gamma=gamma, s=s_exp, failed=str(e))
            res["settings"].append(v)
            mdval.write_json(jpath, res)
        w = res["settings"][0]
        for v in res["settings"]:
            v["checked"] = (v["gamma"], v["s"]) in stable
            if v.get("failed"):
                if v["checked"]:
                    fails.append(f"gamma {v['gamma']:g}, s {v['s']:g}: {v['failed']}")
                continue
            v["M"] = v["mu"] / w["mu"]
            v["M_err"] = v["M"] * math.hypot(v["mu_err"] / v["mu"], w["mu_err"] / w["mu"])
            v["T_ok"] = bool(abs(v["T"] - 1.0) <= 0.01 + 2 * v["T_err"])
            if v["checked"] and not v["T_ok"]:
                fails.append(f"gamma {v['gamma']:g}, s {v['s']:g}: T = {v['T']:.4f} +- {v['T_err']:.4f} (kT 1)")
        if args.m_bounds and len(res["settings"]) > 1:
            M = res["settings"][1]["M"]
            if not args.m_bounds[0] <= M <= args.m_bounds[1]:
                fails.append(f"M = {M:.3f} outside [{args.m_bounds[0]:g}, {args.m_bounds[1]:g}]")
        mdval.write_json(jpath, res)
    if "coflow" in args.parts and args.coflow:
        args.sw = [0.5]
        w = res["settings"][0]
        runs = {"single": tp.slit(args, raw, "single", 1.0, 4.5)}
        runs["M1_sw0.5"] = tp.slit(args, raw, "M1_sw0.5", 0.5, 4.5)
        oils = {}
        for gamma, s_exp in pair_list(args.coflow):
            vo = [v for v in res["settings"] if v["gamma"] == gamma and v["s"] == s_exp and not v.get("failed")]
            if not vo:
                sys.exit(f"coflow oil gamma {gamma:g}, s {s_exp:g}: not among the measured --settings")
            tag = f"M_g{gamma:g}_s{s_exp:g}_sw0.5"
            runs[tag] = tp.slit(args, raw, tag, 0.5, gamma, s_exp)
            oils[tag] = vo[0]
        # against the shared water-only reference; coflow_analysis takes one oil at a time
        hyd = tp.coflow_analysis({"single": runs["single"], "M1_sw0.5": runs["M1_sw0.5"]}, args.h, False, w, None,
                                 fails)
        for tag, vo in oils.items():
            tp.coflow_analysis({"single": runs["single"], tag: runs[tag]}, args.h, False, w, vo, fails)
        z1 = hyd["zeros"][1] - (2.0 + args.h / 2)  # the hydraulic zero above the middle
        for tag, rr in runs.items():
            if tag != "single":
                rr["interface"] = interface_velocity(runs["single"], rr, args.h, args.g, w["mu"])
                rr["interface"]["film_hyd"] = z1 - rr["interface"]["y_i"]
        for rr in runs.values():  # the profiles stay in the raw folders
            for key in ("y", "u", "u_err", "n_w", "n_o"):
                rr.pop(key, None)
        res["coflow"] = {"runs": runs, "h": args.h, "a_wo": args.a_wo, "g": args.g, **hyd}
        mdval.write_json(jpath, res)
    report(res, out, args, fails)
    for f in fails:
        print("FAIL:", f)
    print("viscosity_ratio:", "all checks pass" if not fails else f"{len(fails)} check(s) failed")
    sys.exit(1 if fails else 0)


def shown_args():
    """The command line's options for the report, less --out and its folder."""
    shown, skip = [], False
    for a in sys.argv[1:]:
        if skip or a.startswith("--out="):
            skip = False
            continue
        if a == "--out":
            skip = True
            continue
        shown.append(a)
    return shown


def report(res, out, args, fails):
    box = " x ".join(f"{v:g}" for v in res["settings"][0].get("box", (8, 16, 6)))
    L = ["# Viscosity ratio through the thermostat weight's exponent s\n",
         f"Reverse Poiseuille (box {box}, density 6.05, g = 0.05, dt = 0.01, 1 rank, "
         f"{args.steps} steps, first {args.equil} discarded); A = -40, B = 25, rd = 0.75, kT = 1 for every "
         "liquid; the thermostat weight w_R = (1 - r/rc)^s, w_D = w_R^2. T: the kinetic temperature less the "
         "flow's part (block error), against kT = 1.\n",
         "| gamma | s | mu | M = mu / mu_water | T | T within 1% |", "|---|---|---|---|---|---|"]
    for v in res["settings"]:
        if v.get("failed"):
            L.append(f"| {v['gamma']:g} | {v['s']:g} | unstable: the run stops (displacement check) | | | |")
            continue
        L.append(f"| {v['gamma']:g} | {v['s']:g} | {v['mu']:.3f} +- {v['mu_err']:.3f} | "
                 f"{v.get('M', float('nan')):.3f} +- {v.get('M_err', float('nan')):.3f} | "
                 f"{v['T']:.4f} +- {v['T_err']:.4f} | {'yes' if v.get('T_ok') else 'no'} |")
    co = res.get("coflow") or {}
    if co.get("runs"):
        L += ["", f"## Layered co-current flow in a slit (h = {co['h']:g}, A_wo = {co['a_wo']:g}, "
                  f"g = {co['g']:g}, Sw = 0.5)\n",
              f"Water-only flow Q_1 = {co['runs']['single']['Q_w']:.4f} +- {co['runs']['single']['Q_w_err']:.4f}; "
              f"hydraulic width {co['h_hyd']:.3f}. Exact values at the hydraulic Sw.\n",
              "| run | oil gamma, s | Sw hyd | M | krw | exact | krn | exact | krn / exact | check |",
              "|---|---|---|---|---|---|---|---|---|---|"]
        for tag, r in co["runs"].items():
            if tag == "single":
                continue
            L.append(f"| {tag} | {r['gamma_oil']:g}, {r.get('s_oil', 1.0):g} | {r['Sw_hyd']:.3f} | "
                     f"{r['M']:.3f} +- {r['M_err']:.3f} | {r['krw']:.3f} +- {r['krw_err']:.3f} | "
                     f"{r['krw_exact_hyd']:.3f} | {r['krn']:.3f} +- {r['krn_err']:.3f} | {r['krn_exact_hyd']:.3f} | "
                     f"{r['krn'] / r['krn_exact_hyd']:.3f} | {'pass' if r['pass'] else 'FAIL'} |")
        L += ["", "The interface (profiles symmetrised about the middle; y from the middle): y_i where phi = 0, the "
              "hydraulic film a = (upper hydraulic zero) - y_i, the 10-90 width of phi; the film's velocity at y_i "
              "against the water-only run's there (1 in the continuum: the film sees the same stress "
              "tau = g int n dy); "
              "delta = (u_single - u) mu_w / tau(y_i), the layer of no shear that would cost as much; the local "
              "viscosity tau / (-du/dy) over 0.5 rc on each side of y_i (water 5.45).\n",
              "| run | y_i | film a | a / width 10-90 | u(y_i) | u_single(y_i) | ratio | delta (rc) | mu oil side | "
              "mu water side |", "|---|---|---|---|---|---|---|---|---|---|"]
        for tag, r in co["runs"].items():
            f = r.get("interface")
            if f:
                L.append(f"| {tag} | {f['y_i']:.2f} | {f['film_hyd']:.2f} | {f['film_hyd'] / f['width_10_90']:.1f} | "
                         f"{f['u_i']:.4f} | {f['u_single_i']:.4f} | {f['r_i']:.3f} +- {f['r_i_err']:.3f} | "
                         f"{f['delta']:.2f} +- {f['delta_err']:.2f} | "
                         f"{f['mu_oil_side']:.1f} | {f['mu_water_side']:.1f} |")
    L += ["", "Checks: " + ("all pass" if not fails else "; ".join(fails)), "",
          "Command: `/usr/bin/python3 validation/twophase/viscosity_ratio.py"
          + "".join(" " + a for a in shown_args())
          + "` (`--reuse` analyses finished runs again; `--out DIR` writes elsewhere)", ""]
    open(os.path.join(out, "viscosity_ratio.md"), "w").write("\n".join(L))
    print("\n".join(L))
    plot(res, out)


def plot(res, out):
    plt = mdval.pyplot()
    co = res.get("coflow") or {}
    layered = [(t, r["interface"]) for t, r in co.get("runs", {}).items() if r.get("interface", {}).get("profile")]
    fig, axs = plt.subplots(1, 3 if layered else 2, figsize=(16.5 if layered else 11, 4))
    for s_exp in sorted({v["s"] for v in res["settings"]}, reverse=True):
        vs = sorted([v for v in res["settings"] if v["s"] == s_exp and not v.get("failed")], key=lambda v: v["gamma"])
        g = [v["gamma"] for v in vs]
        axs[0].errorbar(g, [v["M"] for v in vs], yerr=[v["M_err"] for v in vs], fmt="o-", label=f"s = {s_exp:g}")
        axs[1].errorbar(g, [v["T"] for v in vs], yerr=[v["T_err"] for v in vs], fmt="o-", label=f"s = {s_exp:g}")
    axs[0].set_xlabel("gamma")
    axs[0].set_ylabel("M = mu / mu_water (gamma 4.5, s 1)")
    axs[0].legend(fontsize=8)
    axs[1].axhspan(0.99, 1.01, color="0.9")
    axs[1].set_xlabel("gamma")
    axs[1].set_ylabel("thermal T (kT = 1; band: 1%)")
    axs[1].legend(fontsize=8)
    if layered:  # the layered runs' velocity against the water-only run's, across the upper half
        p0 = layered[0][1]["profile"]
        axs[2].plot(p0["y"], p0["u_single"], "k-", lw=1, label="water only")
        for tag, f in layered:
            axs[2].plot(f["profile"]["y"], f["profile"]["u"], "o-", ms=3, lw=0.8,
                        label=f"{tag}: u(y_i) / u_single = {f['r_i']:.3f}")
            axs[2].axvline(f["y_i"], color="0.6", lw=0.8)
        axs[2].set_xlabel(f"y from the slit's middle (h = {co['h']:g}; grey: phi = 0)")
        axs[2].set_ylabel("u")
        axs[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "viscosity_ratio.png"), dpi=110)


if __name__ == "__main__":
    main()
