#!/usr/bin/env python3
"""mdpore permeability on a SCENE with a `units:` block (docs/permeability.md, "Conventions and
units"): the campaign's rc, temperature and particle mass come from the block (recomputed here from
physics.md section 4's water mapping: rc^3 = N_m n m_water / rho_water, m = N_m m_water), the report
and permeability.json give k in nD = k* rc^2 / 9.869233e-13 m^2 x 1e9; --temperature wins over the
block (a note says so); a bad block stops the campaign with the scene parser's message.
A 2-gradient campaign of a 180-particle slit (<= 2000 steps per run, 1 rank): seconds."""
import json
import os
import shutil
import subprocess
import sys

MDPORE = os.environ["MDPORE"]
OUT = os.environ["MDPORE_TEST_OUT"]
KB = 1.380649e-23
M_WATER = 18.01528 * 1.66053906660e-27
RHO_WATER = 997.0
DARCY = 9.869233e-13

SCENE = """name: units_slit
box: {lo: [0, 0, 0], hi: [4, 5, 3], periodic: [true, false, true]}
species:
  - {name: liquid}
  - {name: wall, frozen: true}
pairs:
  default: {A: 25, gamma: 4.5, rc: 1.0}
effects:
  dpd_conservative: {}
  dpd_thermostat: {}
  box_walls: {}
initial:
  fill:
    - {species: liquid, lo: [0, 1, 0], hi: [4, 4, 3], density: 3.0}
    - {species: wall, lo: [0, 0, 0], hi: [4, 1, 3], density: 3.0}
    - {species: wall, lo: [0, 4, 0], hi: [4, 5, 3], density: 3.0}
run: {dt: 0.02, steps: 2000, seed: 7}
output:
  progress: false
%s
"""

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def close(a, b, rel=1e-6):
    return a is not None and b is not None and abs(a - b) <= rel * abs(b)


def mdpore(*args):
    return subprocess.run([MDPORE, *args], capture_output=True, text=True, cwd=OUT,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))


def manifest(folder):
    out = {}
    for line in open(os.path.join(OUT, folder, "campaign.txt")):
        if ": " in line:
            k, v = line.rstrip("\n").split(": ", 1)
            out.setdefault(k, v)
    return out


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    with open(os.path.join(OUT, "slit.yaml"), "w") as f:
        f.write(SCENE % "units: {mapping: water, coarse_graining: 2, temperature: 310}")
    with open(os.path.join(OUT, "bad.yaml"), "w") as f:
        f.write(SCENE % "units: {mapping: water, rc: 1e-9}")
    # The water mapping at N_m = 2, n = 3 (the fill), T = 310 K.
    rc = (2 * 3.0 * M_WATER / RHO_WATER) ** (1.0 / 3.0)
    mass = 2 * M_WATER

    # Its two strong gradients heat this small DPD liquid by 11-33%: the campaign would leave both runs
    # out of the Darcy range (no k, exit 3). This test is about the units, so it lifts the bound.
    p = mdpore("permeability", "slit.yaml", "--axis", "x", "--gradients", "0.1,0.2", "--max-steps",
               "2000", "--target-error", "0.2", "--workdir", "camp", "--temperature-tolerance", "0.5")
    print(p.stdout[-3000:])
    if p.returncode:
        print(p.stderr[-3000:])
    check(p.returncode == 0, "the campaign on a scene with units ran")
    check(f"units: rc = {rc:.4g} m (the scene's units block" in p.stdout,
          f"the report gives rc = {rc:.4g} m from the scene's units block")
    path = os.path.join(OUT, "camp", "permeability.json")
    if os.path.exists(path):
        j = json.load(open(path))
        u, x = j["units"], j["axes"]["x"]
        check(close(u["rc_m"], rc), f"permeability.json rc_m {u['rc_m']:.6g} = {rc:.6g} m")
        check(close(u["temperature_K"], 310) and close(u["particle_mass_kg"], mass) and
              close(u["water_molecules_per_particle"], 2, 1e-4),
              "temperature 310 K and m = 2 m_water from the block")
        check(close(x["k_nD"], x["k_rc2"] * rc * rc / DARCY * 1e9),
              f"k = {x['k_rc2']:.4g} rc^2 = {x['k_nD']:.4g} nD = k* rc^2 in nD")
    else:
        check(False, "permeability.json written")

    # --temperature wins over the block (the length and the mass stay the block's).
    p = mdpore("permeability", "slit.yaml", "--axis", "x", "--gradients", "0.1,0.2",
               "--temperature", "350", "--emit-scenes", "emit_T")
    m = manifest("emit_T") if p.returncode == 0 else {}
    check(p.returncode == 0 and "--temperature wins over the scene's units block" in p.stderr,
          "--temperature: a note that the option wins")
    check(close(float(m.get("temperature_K", "nan")), 350) and "energy_J" not in m and
          close(float(m.get("length_unit_m", "nan")), rc) and
          close(float(m.get("particle_mass_kg", "nan")), mass),
          "manifest: T = 350 K from the option, rc and m from the block")

    p = mdpore("permeability", "bad.yaml", "--axis", "x", "--gradients", "0.1,0.2", "--emit-scenes",
               "emit_bad")
    check(p.returncode != 0 and "key 'units.rc': expected no rc with mapping water" in p.stderr,
          "a bad units block stops the campaign with the parser's message")
    print("PASS" if not failures else f"{len(failures)} check(s) failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
