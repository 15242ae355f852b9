#!/usr/bin/env python3
"""ctest campaign_resolution: the voxel edge of an IMAGE campaign from the image's critical throat
(campaign/campaign_resolution.c, docs/permeability.md "Resolution"). Runs nothing (--emit-scenes and
--collect on the emitted folder: seconds).

Slits `mdpore image make slit --width W --wall 4 --length 12 --depth 8` (critical throat W voxels
along x and z, none along y):
- W = 8, no --rc-per-voxel: 4 rc / 8 voxels = 0.5 rc per voxel, the manifest records the throats,
  the choice and the estimated particles;
- W = 6: 4 / 6 rounded up to 0.67; with --rc-per-voxel 0.5 (a 3 rc throat) refused, naming the
  throat, the limit and what to try, nothing planned; with --force planned, the warning on stderr,
  in the manifest, in permeability.json and in the report; --min-throat 3 accepts 0.5;
- W = 2: 2 rc per voxel, coarser than the walls' reach (rc + rd = 1.75): the estimate counts one wall
  layer, the fill adds what the walls adsorb, and a short run of the scene builds one voxel layer of
  wall with no particle inside it;
- the regime: no voxel size (the water mapping, 0.82 nm) nanopore, 10 nm voxels at 0.5 rc per voxel
  (rc 20 nm) intermediate, 1 um voxels continuum.
"""
import json
import os
import shutil
import subprocess
import sys

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "campaign_resolution_out"))
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def mdpore(*args):
    return subprocess.run([MDPORE, *args], capture_output=True, text=True, cwd=OUT)


def manifest(folder):
    out = {}
    path = os.path.join(OUT, folder, "campaign.txt")
    if not os.path.exists(path):
        return out
    for line in open(path):
        if ": " in line:
            k, v = line.rstrip("\n").split(": ", 1)
            out.setdefault(k, v)
    return out


def slit(width, name, *extra):
    p = mdpore("image", "make", "slit", "--width", str(width), "--wall", "4", "--length", "12", "--depth", "8",
               *extra, "-o", name)
    if p.returncode:
        sys.exit("image make failed: " + p.stderr)


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    slit(8, "slit8.h5")
    slit(6, "slit6.h5")
    slit(8, "slit8_10nm.h5", "--voxel-size", "10nm")
    slit(8, "slit8_1um.h5", "--voxel-size", "1um")

    # width 8: the default stays 0.5 rc per voxel
    p = mdpore("permeability", "slit8.h5", "--axis", "x", "--emit-scenes", "w8")
    m = manifest("w8")
    check(p.returncode == 0 and float(m.get("rc_per_voxel", "nan")) == 0.5,
          f"slit 8: default rc_per_voxel 0.5 (exit {p.returncode}, manifest {m.get('rc_per_voxel')})")
    check(m.get("throat_voxels") == "8 0 8" and m.get("min_throat") == "4",
          f"slit 8: manifest throat_voxels 8 0 8, min_throat 4 (got {m.get('throat_voxels')}, {m.get('min_throat')})")
    check(m.get("rc_per_voxel_source", "").startswith("chosen") and "resolution_warning" not in m,
          f"slit 8: the choice recorded, no warning ({m.get('rc_per_voxel_source')})")
    check("critical throat" in p.stderr and "rc per voxel 0.5" in p.stderr and "particles per run" in p.stderr
          and "time at the step budget" in p.stderr and "H200" in p.stderr,
          "slit 8: the report names the throat, the choice, the particles and the time")
    parts = float(m.get("particles_estimate", "nan"))
    # fluid: 8 x 12 x 8 pore voxels of 0.125 rc^3 at 6.2; walls: of the 4 solid layers each side the
    # 3 whose centres lie within 1.75 rc = 3.5 voxels of a pore voxel centre (the wall builder's
    # thickness; the fourth is 4 voxels from this pore and 5 from the next across the periodic face),
    # 6 x 12 x 8 voxels at density 4
    check(abs(parts - (6.2 * 768 * 0.125 + 4.0 * 576 * 0.125)) < 1e-6,
          f"slit 8: particles estimate {parts} (fluid 595.2 + walls 288)")

    # width 6: the default makes the throat 4 rc
    p = mdpore("permeability", "slit6.h5", "--axis", "x", "--emit-scenes", "w6")
    m = manifest("w6")
    check(p.returncode == 0 and abs(float(m.get("rc_per_voxel", "nan")) - 0.67) < 1e-12,
          f"slit 6: default rc_per_voxel 0.67 (exit {p.returncode}, manifest {m.get('rc_per_voxel')})")

    # width 6 at 0.5 rc per voxel: a 3 rc throat, refused
    p = mdpore("permeability", "slit6.h5", "--axis", "x", "--rc-per-voxel", "0.5", "--emit-scenes", "w6_05")
    msg = p.stderr
    check(p.returncode != 0 and "critical throat along x is 6 voxels = 3 rc" in msg and "--min-throat 4" in msg
          and "--rc-per-voxel 0.67" in msg and "--force" in msg,
          f"slit 6 at 0.5: refused naming the throat, the limit and what to try (got: {msg.strip()[-400:]})")
    check(not os.path.exists(os.path.join(OUT, "w6_05", "campaign.txt")), "slit 6 at 0.5: nothing planned")

    # ... accepted with --force, the warning recorded
    p = mdpore("permeability", "slit6.h5", "--axis", "x", "--rc-per-voxel", "0.5", "--force", "--emit-scenes",
               "w6_force")
    m = manifest("w6_force")
    check(p.returncode == 0 and "warning" in p.stderr and m.get("resolution_warning", "").startswith("--force"),
          f"slit 6 at 0.5 --force: planned with a warning (exit {p.returncode}, {m.get('resolution_warning')})")
    c = mdpore("permeability", "--collect", "w6_force")
    path = os.path.join(OUT, "w6_force", "permeability.json")
    res = json.load(open(path)).get("resolution", {}) if os.path.exists(path) else {}
    check(res.get("critical_throat_voxels") == [6, 0, 6] and res.get("warning", "").startswith("--force")
          and res.get("rc_per_voxel_source") == "--rc-per-voxel",
          f"permeability.json: resolution with throats and the warning ({res})")
    check("WARNING: --force" in c.stdout, "the report prints the warning")

    # ... and with a lower limit
    p = mdpore("permeability", "slit6.h5", "--axis", "x", "--rc-per-voxel", "0.5", "--min-throat", "3",
               "--emit-scenes", "w6_min3")
    check(p.returncode == 0 and "warning" not in p.stderr, f"--min-throat 3 accepts 0.5 (exit {p.returncode})")
    p = mdpore("permeability", "slit6.h5", "--axis", "x", "--min-throat", "-1", "--emit-scenes", "bad")
    check(p.returncode != 0 and "--min-throat" in p.stderr, "--min-throat -1 refused")

    # width 2: the throat made 4 rc wide at 2 rc per voxel, coarser than the walls' reach rc + rd = 1.75:
    # the wall builder keeps one voxel layer (2 rc); the fill adds what the walls adsorb
    slit(2, "slit2.h5")
    p = mdpore("permeability", "slit2.h5", "--axis", "x", "--emit-scenes", "w2")
    m = manifest("w2")
    check(p.returncode == 0 and float(m.get("rc_per_voxel", "nan")) == 2 and "resolution_warning" not in m,
          f"slit 2: default rc_per_voxel 2, no warning (exit {p.returncode}, manifest {m.get('rc_per_voxel')}; "
          f"{p.stderr[-300:]})")
    parts = float(m.get("particles_estimate", "nan"))
    # fluid: 12 x 2 x 8 pore voxels of 8 rc^3 at 6.2; walls: one solid layer each side (centres 1 voxel
    # = 2 rc from the pore), 2 x 12 x 8 voxels at density 4
    check(abs(parts - (6.2 * 192 * 8 + 4.0 * 192 * 8)) < 1e-6, f"slit 2: particles estimate {parts} (9523.2 + 6144)")
    fill = float(m.get("fill_density", "nan"))
    check(abs(fill - (6.2 + 2 * 0.26 / 4.0)) < 1e-9 and float(m.get("wall_adsorption", "nan")) == 0.26,
          f"slit 2: fill 6.2 + 2 Gamma / h = 6.33 (h = 4 rc) in the manifest ({fill})")
    runs = os.path.join(OUT, "w2", "runs")
    run = os.path.join(runs, sorted(os.listdir(runs))[0]) if os.path.isdir(runs) else OUT
    r = subprocess.run([MDPORE, "run", "scene.yaml", "--steps", "40"], capture_output=True, text=True, cwd=run)
    out = r.stdout + r.stderr
    check(r.returncode == 0 and "thickness 2 rc (1 voxels) = one voxel edge" in out,
          f"slit 2: the wall builder keeps one voxel layer (exit {r.returncode}; {out[-600:]})")
    check("penetrations: 0 of" in out, "slit 2: no particle inside a wall in 40 steps")

    # regimes
    for name, regime in (("slit8", "nanopore"), ("slit8_10nm", "intermediate"), ("slit8_1um", "continuum")):
        p = mdpore("permeability", f"{name}.h5", "--axis", "x", "--emit-scenes", f"r_{name}")
        m = manifest(f"r_{name}")
        check(p.returncode == 0 and m.get("regime") == regime and f"{regime} regime" in p.stderr
              or (regime == "intermediate" and m.get("regime") == regime and "between" in p.stderr),
              f"{name}: {regime} regime (got {m.get('regime')})")

    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
