#!/usr/bin/python3
"""Validation (a): standard DPD equation of state (a = 25, gamma = 4.5, kT = 1).

Reference pressures (physics.md section 2; LAMMPS pair dpd, 10^3 box, dt = 0.01, 1e4 steps):
p = 23.69 (rho = 3), 66.4 (rho = 5), 169.9 (rho = 8); pass = within 1%. The Groot-Warren fit
p = rho kT + 0.101 a rho^2 is drawn as the trend (it is ~8% high at rho = 3 by construction).
--quick: a 6^3 box and 3000 steps, 3% tolerance (the ctest variant).
"""
import argparse
import os
import sys

import numpy as np

import mdval

REF = {3.0: 23.69, 5.0: 66.4, 8.0: 169.9}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--np", type=int, default=2)
    args = ap.parse_args()
    L, steps, equil, tol = (6.0, 3000, 500, 0.03) if args.quick else (10.0, 12000, 2000, 0.01)
    out = mdval.out_dir("dpd_eos" + ("_quick" if args.quick else ""))
    rows, ok = [], True
    for rho, pref in REF.items():
        box = [L, L, L]
        scene = mdval.mdpd_scene(f"dpd_eos_rho{rho:g}", box, [mdval.fill_box(box, rho)], A=25.0, B=0.0,
                                 steps=steps, effects={"dpd_conservative": {}, "dpd_thermostat": {}})
        wd = os.path.join(out, f"rho{rho:g}")
        wall = mdval.run(scene, wd, args.np)
        t = mdval.thermo_window(wd, equil)
        p, dp = mdval.block_average(mdval.column(t, "p", "pressure"))
        T, dT = mdval.block_average(mdval.column(t, "T", "temperature"))
        gw = rho + 0.101 * 25.0 * rho ** 2
        rel = (p - pref) / pref
        passed = abs(rel) <= tol
        ok &= passed
        n = int(round(rho * L ** 3))
        rows.append([rho, n, round(p, 3), round(dp, 3), pref, f"{100 * rel:+.2f}%", round(gw, 2),
                     round(T, 4), round(dT, 4), round(wall, 1), round(n * steps / wall / 1e6, 3),
                     "pass" if passed else "FAIL"])
    mdval.write_report(out, "dpd_eos",
                       ["rho", "N", "p", "err", "p_ref", "dev", "p_GW_fit", "T", "T_err", "wall_s", "MPS",
                        "verdict"], rows,
                       notes=f"Standard DPD EOS, a=25, gamma=4.5, kT=1, dt=0.01, box {L:g}^3, {steps} steps "
                             f"({equil} discarded), {args.np} ranks. Tolerance {100 * tol:g}%.")
    plt = mdval.pyplot()
    r = np.linspace(2.5, 8.5, 50)
    plt.plot(r, r + 0.101 * 25 * r ** 2, "k--", label="Groot-Warren fit")
    plt.plot(list(REF), list(REF.values()), "s", mfc="none", ms=10, label="reference (LAMMPS)")
    plt.errorbar([x[0] for x in rows], [x[2] for x in rows], yerr=[x[3] for x in rows], fmt="o",
                 label="mdpore")
    plt.xlabel("number density rho")
    plt.ylabel("pressure p")
    plt.legend()
    plt.title("Standard DPD equation of state (a = 25)")
    plt.savefig(os.path.join(out, "dpd_eos.png"), dpi=120)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
