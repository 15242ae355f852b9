#!/usr/bin/python3
"""Assert a slab run's summary.json: liquid density and surface tension within loose bounds, the
temperature near kT, and the summary/profile/thermo files consistent with each other.
Usage: check_slab_summary.py DIR RHO RHO_TOL GAMMA GAMMA_TOL"""
import csv
import json
import os
import sys

d, rho, rho_tol, gam, gam_tol = sys.argv[1], *map(float, sys.argv[2:6])
s = json.load(open(os.path.join(d, "summary.json")))
ok = True


def check(cond, what):
    global ok
    print(("ok   " if cond else "FAIL ") + what)
    ok &= bool(cond)


r, g, T = s["liquid_density"], s["surface_tension"], s["thermo"]["T"]
check(abs(r["mean"] - rho) <= rho_tol, f"liquid density {r['mean']:.4f} +- {r['err']:.4f} within {rho} +- {rho_tol}")
check(abs(g["mean"] - gam) <= gam_tol, f"surface tension {g['mean']:.3f} +- {g['err']:.3f} within {gam} +- {gam_tol}")
check(0 < r["err"] < 0.2 and 0 < g["err"] < 2, "block errors positive and modest")
check(abs(T["mean"] - 1.0) < 0.05, f"temperature {T['mean']:.4f} near kT = 1")
rows = [l for l in open(os.path.join(d, "profile.csv")) if not l.startswith("#")]
prof = list(csv.DictReader(rows))
check(len(prof) == s["profile"]["bins"], f"profile has {len(prof)} bins")
# Number of particles recovered from the density profile (bins cover the box).
L = s["box"]
vbin = L[0] * L[1] * L[2] / len(prof)
n_prof = sum(float(p["density"]) for p in prof) * vbin
check(abs(n_prof - s["particles"]) < 1e-6 * s["particles"], f"profile integrates to {n_prof:.3f} particles")
# Sum of per-bin pressure = box pressure (per-particle virial adds up to the thermo virial).
pxx_bins = sum(float(p["Pxx"]) for p in prof) / len(prof)
check(abs(pxx_bins - s["thermo"]["Pxx"]["mean"]) < 1e-6 + 1e-6 * abs(pxx_bins),
      f"mean of bin Pxx {pxx_bins:.6f} equals thermo Pxx {s['thermo']['Pxx']['mean']:.6f}")
sys.exit(0 if ok else 1)
