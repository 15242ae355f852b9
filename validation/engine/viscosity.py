#!/usr/bin/python3
"""Validation (e): shear viscosity by reverse (periodic) Poiseuille flow (Backer et al. 2005).

Body force +g along x for y < L_y/2 and -g above (scene: body_force reverse_along: y). In each half
u(y) = (n m g / (2 mu)) y' (L_y/2 - y'), y' = y mod L_y/2; mu follows from a weighted linear fit of the
measured u_x(y) profile against that shape (n = measured mean number density).
References (physics.md section 2): standard DPD a = 25, rho = 3, gamma = 4.5: eta = 0.870 +- 0.003;
mDPD A = -40, B = 25, rd = 0.75, gamma = 4.5 (liquid density 6.07): eta = 5.49 +- 0.03. Pass: within 2%.
The wall-bounded flows of later issues are judged against these numbers.
The flow needs time to develop: its slowest mode decays with tau = (L_y / 2 pi)^2 / nu, so the first
6 tau are discarded (tau from the reference nu; it sets only the equilibration length, not the fit).
--quick: L_y = 10 (force x4, same peak velocity), a shorter average, 8% tolerance.
"""
import argparse
import os
import sys

import numpy as np

import mdval

CASES = {
    "dpd": dict(rho=3.0, g=0.02, eta=0.870, eta_err=0.003, A=25.0, B=0.0,
                effects=lambda g: {"dpd_conservative": {}, "dpd_thermostat": {},
                                   "body_force": {"liquid": [g, 0.0, 0.0], "reverse_along": "y"}}),
    "mdpd": dict(rho=6.07, g=0.05, eta=5.49, eta_err=0.03, A=-40.0, B=25.0,
                 effects=lambda g: {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {},
                                    "body_force": {"liquid": [g, 0.0, 0.0], "reverse_along": "y"}}),
}


def fit_viscosity(y, u, du, n, g, Ly):
    """mu from u = s(y) n g / (2 mu) y'(Ly/2 - y'): linear least squares in c = n g / (2 mu)."""
    h = Ly / 2
    yp = np.mod(y, h)
    shape = np.where(y < h, 1.0, -1.0) * yp * (h - yp)
    w = 1.0 / np.maximum(du, 1e-12) ** 2
    c = np.sum(w * shape * u) / np.sum(w * shape * shape)
    dc = 1.0 / np.sqrt(np.sum(w * shape * shape))
    chi2 = float(np.sum(w * (u - c * shape) ** 2) / (len(u) - 1))
    mu = n * g / (2 * c)
    return mu, mu * dc / c * max(1.0, np.sqrt(chi2)), chi2, c * shape


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--case", action="append", choices=list(CASES))
    ap.add_argument("--gscale", type=float, default=1.0, help="scale the body force (shear-rate check)")
    ap.add_argument("--rho", type=float, help="mdpd only: measure at this density instead of 6.07 (the fluid of "
                                              "image campaigns fills pores at 6.2); no reference there, so the "
                                              "value is reported, not checked")
    args = ap.parse_args()
    production, tol, Ly, gscale = (3000, 0.08, 10.0, 4.0) if args.quick else (15000, 0.02, 20.0, 1.0)
    Lx, Lz, dt = 10.0, 10.0, 0.01
    out = mdval.out_dir("viscosity" + ("_quick" if args.quick else "") +
                        (f"_g{args.gscale:g}" if args.gscale != 1.0 else "") +
                        (f"_rho{args.rho:g}" if args.rho else ""))
    if args.rho and (args.case or ["mdpd"]) != ["mdpd"]:
        sys.exit("viscosity.py: --rho applies to --case mdpd only")
    if args.rho:
        args.case = ["mdpd"]
    rows, ok, curves = [], True, {}
    for name in (args.case or list(CASES)):
        c = dict(CASES[name])
        c["g"] *= gscale * args.gscale
        checked = not args.rho
        if args.rho:
            c["rho"] = args.rho
        tau = (Ly / (2 * np.pi)) ** 2 / (c["eta"] / c["rho"])
        equil = int(np.ceil(6 * tau / dt / 100.0)) * 100
        steps = equil + production
        box = [Lx, Ly, Lz]
        scene = mdval.mdpd_scene(f"viscosity_{name}", box, [mdval.fill_box(box, c["rho"])], A=c["A"], B=c["B"],
                                 steps=steps, effects=c["effects"](c["g"]),
                                 profile={"axis": "y", "bins": 40, "every": 10, "start": equil})
        wd = os.path.join(out, name)
        wall = mdval.run(scene, wd, args.np)
        prof = mdval.read_table(os.path.join(wd, "profile.csv"))
        y = mdval.column(prof, "y", "position", "coord", "bin_center")
        u = mdval.column(prof, "vx", "velocity_x", "ux")
        du = mdval.column(prof, "vx_err", "velocity_x_err", "ux_err")
        n = float(np.mean(mdval.column(prof, "density", "density_liquid", "n_liquid", "rho")))
        mu, dmu, chi2, model = fit_viscosity(y, u, du, n, c["g"], Ly)
        curves[name] = (y, u, du, model)
        passed = abs(mu - c["eta"]) <= tol * c["eta"] or not checked
        ok &= passed
        N = int(round(c["rho"] * Lx * Ly * Lz))
        rows.append([name, c["rho"], N, steps, c["g"], round(n, 4), round(mu, 4), round(dmu, 4), c["eta"],
                     f"{100 * (mu - c['eta']) / c['eta']:+.2f}%", round(chi2, 2), round(float(np.max(np.abs(u))), 3),
                     round(wall, 1), ("pass" if passed else "FAIL") if checked else "measured (no reference)"])
    mdval.write_report(out, "viscosity",
                       ["case", "rho", "N", "steps", "g", "n_measured", "eta", "err", "eta_ref", "dev", "chi2/dof", "u_max",
                        "wall_s", "verdict"], rows,
                       notes=f"Reverse Poiseuille, box {Lx:g}x{Ly:g}x{Lz:g}, force along x flipped along y, "
                             f"6 tau discarded then {production} steps averaged, dt={dt:g}, {args.np} ranks. "
                             f"Tolerance {100 * tol:g}%.")
    plt = mdval.pyplot()
    fig, axs = plt.subplots(1, len(curves), figsize=(5 * len(curves), 4), squeeze=False)
    for ax, (name, (y, u, du, model)) in zip(axs[0], curves.items()):
        ax.errorbar(y, u, yerr=du, fmt=".", label="mdpore")
        ax.plot(y, model, "-", label="parabolic fit")
        ax.set_xlabel("y")
        ax.set_ylabel("u_x")
        ax.set_title(name)
        ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "viscosity.png"), dpi=120)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
