#!/usr/bin/python3
"""Decomposition independence of run statistics: the same mDPD bulk scene on 1, 2 and 4 MPI ranks.

Random forces are keyed on (seed, step, pair ids), so the runs start identical and part only through
rounding (chaos); their time averages of T, p and the diagonal pressure components must agree within
3 combined block-averaged standard errors.
On a machine with fewer cores than ranks (CI: 2 cores, 4 ranks) every halo exchange waits for a
descheduled peer, so the CI variant is short (--steps 800).
"""
import argparse
import itertools
import math
import os
import sys

import mdval


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--equil", type=int, default=500)
    ap.add_argument("--ranks", default="1,2,4")
    args = ap.parse_args()
    L, rho, equil = 6.0, 6.2, args.equil
    out = mdval.out_dir("ranks")
    stats = {}
    for np_ranks in (int(r) for r in args.ranks.split(",")):
        box = [L, L, L]
        scene = mdval.mdpd_scene("ranks", box, [mdval.fill_box(box, rho)], steps=args.steps, seed=7,
                                 thermo_every=2)
        wd = os.path.join(out, f"np{np_ranks}")
        mdval.run(scene, wd, np_ranks)
        t = mdval.thermo_window(wd, equil)
        stats[np_ranks] = {k: mdval.block_average(mdval.column(t, k)) for k in ("T", "p", "Pxx", "Pyy", "Pzz")}
    rows, ok = [], True
    for (a, sa), (b, sb) in itertools.combinations(stats.items(), 2):
        for k in sa:
            d = sa[k][0] - sb[k][0]
            s = math.hypot(sa[k][1], sb[k][1])
            passed = abs(d) <= 3 * s
            ok &= passed
            rows.append([f"{a} vs {b}", k, round(sa[k][0], 4), round(sb[k][0], 4), round(d, 4), round(s, 4),
                         "pass" if passed else "FAIL"])
    mdval.write_report(out, "ranks", ["ranks", "quantity", "mean_a", "mean_b", "diff", "sigma", "verdict"], rows,
                       notes=f"mDPD bulk A=-40 rho={rho} box {L:g}^3, {args.steps} steps ({equil} discarded).")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
