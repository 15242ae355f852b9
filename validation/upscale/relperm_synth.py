#!/usr/bin/env python3
"""Writes a synthetic relative-permeability table in the format of `mdpore relperm`'s relperm.csv
(docs/relperm.md section 3): a Corey law with Gaussian noise of stated size at a fixed seed.

Usage: relperm_synth.py OUT.csv [--seed N] [--rows N] [--sw-range LO HI]
                        [--corey SWC SOR KRW_MAX NW KRO_MAX NO] [--rel-err R] [--abs-err A]
The error of each kr is R kr + A (defaults 0.02 and 0.003), the noise drawn from N(0, err^2)."""
import argparse

import numpy as np


def corey(sw, swc, sor, krw_max, nw, kro_max, no):
    se = np.clip((sw - swc) / (1.0 - swc - sor), 0.0, 1.0)
    return krw_max * se**nw, kro_max * (1.0 - se)**no


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--seed", type=int, default=20251129)
    ap.add_argument("--rows", type=int, default=14)
    ap.add_argument("--sw-range", type=float, nargs=2, default=[0.2, 0.78])
    ap.add_argument("--corey", type=float, nargs=6, default=[0.12, 0.18, 0.45, 2.6, 0.9, 1.9],
                    metavar=("SWC", "SOR", "KRW_MAX", "NW", "KRO_MAX", "NO"))
    ap.add_argument("--rel-err", type=float, default=0.02)
    ap.add_argument("--abs-err", type=float, default=0.003)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    sw = np.linspace(a.sw_range[0], a.sw_range[1], a.rows)
    krw, kro = corey(sw, *a.corey)
    ew, eo = a.rel_err * krw + a.abs_err, a.rel_err * kro + a.abs_err
    krw_m, kro_m = krw + ew * rng.standard_normal(a.rows), kro + eo * rng.standard_normal(a.rows)
    with open(a.out, "w") as f:
        f.write("# synthetic relperm.csv (validation/upscale/relperm_synth.py): Corey swc sor krw_max nw "
                "kro_max no = " + " ".join(f"{v:g}" for v in a.corey) + "\n")
        f.write(f"# noise: err = {a.rel_err:g} kr + {a.abs_err:g}, seed {a.seed}\n")
        f.write("# rc_m: 8.2e-10\n# temperature_K: 298\n")
        f.write("Sw,Sw_err,krw,krw_err,kro,kro_err,Ca,Snw_connected,Snw_disconnected,pc,pc_err\n")
        for i in range(a.rows):
            f.write(f"{sw[i]:.6f},0.002,{krw_m[i]:.6g},{ew[i]:.4g},{kro_m[i]:.6g},{eo[i]:.4g},"
                    f"1e-3,{1 - sw[i]:.4f},0,,\n")


if __name__ == "__main__":
    main()
