#!/usr/bin/python3
"""Validation (d): momentum conservation and temperature control against the time step.

mDPD liquid (A = -40, B = 25, rd = 0.75, gamma = 4.5, rho = 6.2, kT = 1) in a periodic 8^3 box, no
forcing. Asserts: total momentum stays zero to rounding (|P| <= 1e-9 N) at every sample; <T> within 1% of
kT at dt = 0.01. Reports <T> - 1 against dt with the wall time per unit of simulated time: the time step's
error-vs-cost curve (promise 1). A time step too large for the random start must stop the run with the
engine's message (promise 2); such a row is reported as "stopped", not as a failure. --quick: dt in {0.01, 0.02}, shorter runs.
"""
import argparse
import os
import sys

import numpy as np

import mdval


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--np", type=int, default=2)
    args = ap.parse_args()
    dts = [0.01, 0.02] if args.quick else [0.005, 0.01, 0.015, 0.02, 0.03]
    t_total, t_equil = (30.0, 10.0) if args.quick else (40.0, 10.0)
    L, rho = 8.0, 6.2
    out = mdval.out_dir("temperature" + ("_quick" if args.quick else ""))
    rows, ok, stopped = [], True, []
    for dt in dts:
        steps = int(round(t_total / dt))
        box = [L, L, L]
        scene = mdval.mdpd_scene(f"temperature_dt{dt:g}", box, [mdval.fill_box(box, rho)], dt=dt, steps=steps,
                                 thermo_every=max(1, int(round(0.1 / dt))))
        wd = os.path.join(out, f"dt{dt:g}")
        try:
            wall = mdval.run(scene, wd, args.np)
        except RuntimeError:
            # Promise 2: a step too large for the start must stop with a message naming the cause.
            if abs(dt - 0.01) < 1e-12:
                raise
            msg = open(os.path.join(wd, "stderr.txt")).readline().strip()
            stopped.append(dt)
            rows.append([dt, steps, "-", "-", "-", "-", "-", "-", "-", "-", "stopped: " + msg[:120]])
            continue
        full = mdval.read_table(os.path.join(wd, "thermo.csv"))
        n = int(mdval.column(full, "N", "n_total")[0])
        pmax = float(np.max(np.sqrt(sum(mdval.column(full, k, "momentum_" + k[-1]) ** 2 for k in ("px", "py", "pz")))))
        t = mdval.thermo_window(wd, int(round(t_equil / dt)))
        T, dT = mdval.block_average(mdval.column(t, "T", "temperature"))
        mom_ok = pmax <= 1e-9 * n
        t_ok = abs(T - 1.0) <= 0.01 if abs(dt - 0.01) < 1e-12 else True
        ok &= mom_ok and t_ok
        rows.append([dt, steps, n, round(T, 4), round(dT, 4), f"{100 * (T - 1):+.2f}%", f"{pmax:.2e}",
                     round(wall, 1), round(wall / t_total, 3), round(n * steps / wall / 1e6, 3),
                     "pass" if (mom_ok and t_ok) else "FAIL"])
    mdval.write_report(out, "temperature",
                       ["dt", "steps", "N", "T", "T_err", "T-kT", "max|P|", "wall_s", "wall_per_time",
                        "MPS", "verdict"], rows,
                       notes=f"mDPD liquid A=-40, rho={rho}, gamma=4.5, box {L:g}^3, simulated time {t_total:g} "
                             f"({t_equil:g} discarded), {args.np} ranks. Pass: T within 1% at dt=0.01 and "
                             f"|P| <= 1e-9 N at every sample.")
    rows = [r for r in rows if r[3] != "-"]
    plt = mdval.pyplot()
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].errorbar([r[0] for r in rows], [r[3] - 1 for r in rows], yerr=[r[4] for r in rows], fmt="o-")
    ax[0].axhspan(-0.01, 0.01, color="g", alpha=0.15, label="1% band")
    ax[0].set_xlabel("dt")
    ax[0].set_ylabel("<T> - kT")
    ax[0].legend()
    ax[1].loglog([r[8] for r in rows], [max(abs(r[3] - 1), 1e-4) for r in rows], "o-")
    for r in rows:
        ax[1].annotate(f"dt={r[0]:g}", (r[8], max(abs(r[3] - 1), 1e-4)), fontsize=7)
    ax[1].set_xlabel("wall seconds per unit simulated time")
    ax[1].set_ylabel("|<T> - kT|")
    ax[1].set_title("time step: error vs cost")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "temperature.png"), dpi=120)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
