#!/usr/bin/env python3
"""A run with a `units:` block (docs/scene-format.md, "units"): summary.json gives q in m/s and G in
Pa/m equal to the reduced values times the factors of physics.md section 4, recomputed here (water
mapping: rc^3 = N_m n m_water / rho_water, m = N_m m_water, kT = kB T, tau = rc sqrt(m / kT),
velocity rc / tau, pressure gradient kT / rc^4, 1 D = 9.869233e-13 m^2), and the text summary
states the mapping. The same scene without the block runs the same trajectory (outputs only: same
q bit for bit) and its summary has no SI keys (unchanged output).
Usage: check_units.py MDPORE SCENE OUTDIR"""
import json
import math
import os
import shutil
import subprocess
import sys

KB = 1.380649e-23
M_WATER = 18.01528 * 1.66053906660e-27
RHO_WATER = 997.0
DARCY = 9.869233e-13

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def close(a, b, rel=1e-6):
    return a is not None and b is not None and abs(a - b) <= rel * abs(b)


def run(mdpore, scene, out):
    shutil.rmtree(out, ignore_errors=True)
    p = subprocess.run([mdpore, "run", "--output-dir", out, scene], capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1"))
    if p.returncode:
        sys.exit(f"mdpore run {scene} failed:\n{p.stderr}")
    with open(os.path.join(out, "summary.json")) as f:
        return p.stdout, json.load(f)


def main():
    mdpore, scene, out = sys.argv[1:4]
    os.makedirs(out, exist_ok=True)
    text, s = run(mdpore, scene, os.path.join(out, "with_units"))
    flux, units = s["flux"], s.get("units")
    check(units is not None, "summary.json has a units object")
    if units is None:
        sys.exit(1)
    # The factors from physics.md section 4: N_m = 3, n = 3 (the fill), T = 298.15 K.
    n_m, n, T = 3.0, 3.0, 298.15
    rc = (n_m * n * M_WATER / RHO_WATER) ** (1.0 / 3.0)
    m = n_m * M_WATER
    kT = KB * T
    tau = rc * math.sqrt(m / kT)
    print(f"rc = {rc:.6g} m, tau = {tau:.6g} s, velocity {rc / tau:.6g} m/s, G {kT / rc**4:.6g} Pa/m")
    check(units["mapping"] == "water" and close(units["rc_m"], rc) and close(units["tau_s"], tau),
          f"units: water mapping, rc {units['rc_m']:.6g} m and tau {units['tau_s']:.6g} s as recomputed")
    check(close(units["factors"]["pressure_gradient_Pa_per_m"], kT / rc**4) and
          close(units["factors"]["velocity_m_per_s"], rc / tau) and
          close(units["factors"]["permeability_nD"], rc * rc / DARCY * 1e9),
          "factors: kT / rc^4, rc / tau, rc^2 in nD")
    check(close(flux["q_m_per_s"], flux["q"] * rc / tau) and
          close(flux["q_err_m_per_s"], flux["q_err"] * rc / tau),
          f"q = {flux['q']:.6g} -> {flux['q_m_per_s']:.6g} m/s = q x rc / tau")
    check(close(flux["G_Pa_per_m"], flux["G"] * kT / rc**4),
          f"G = {flux['G']:.6g} -> {flux['G_Pa_per_m']:.6g} Pa/m = G x kT / rc^4")
    check(units["viscosity_matched"] is False and "not viscosity-matched" in units["statement"],
          "the summary says the mapping is not viscosity-matched")
    check("in SI: q = " in text and "m/s" in text and "Pa/m" in text and
          "\nunits: mDPD water mapping" in text, "the text summary gives q, G in SI and the mapping")

    # The same scene without the block.
    plain_scene = os.path.join(out, "plain.yaml")
    with open(scene) as f, open(plain_scene, "w") as g:
        g.write("".join(l for l in f if not l.startswith("units:")))
    text0, s0 = run(mdpore, plain_scene, os.path.join(out, "plain"))
    check("units" not in s0 and "q_m_per_s" not in s0["flux"] and "G_Pa_per_m" not in s0["flux"],
          "without units: no SI keys in summary.json")
    check("in SI" not in text0 and "\nunits:" not in text0, "without units: no SI lines in the text")
    check(s0["flux"]["q"] == flux["q"], "the block changes no physics: the same q bit for bit")
    print("PASS" if not failures else f"{len(failures)} check(s) failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
