#!/usr/bin/python3
"""ctest campaign_permeability: a CI-sized `mdpore permeability` campaign on a slit image (CPU).

Slit: `mdpore image make slit --width 8 --wall 4 --length 12 --depth 8` at rc_per_voxel 0.5: a pore
of h = 4 rc between walls, period H = 8 rc along y (porosity 0.5), flow along x. Superficial
velocity q = (h / H) h^2 / (12 mu) G, so k = h^3 / (12 H) = 0.667 rc^2 with no slip. The campaign's
walls (wall density 4, bounce_back) have no slip within 0.09 rc (docs/walls.md section 16: 6 b / h
<= 13% at h = 4, measured -0.01 / -0.05 rc at this width), so k must recover h^2/12:
asserted |k / k_noslip - 1| <= 0.10 + 2 sigma, Darcy fitted. (With the paper's wall density 8 the
slip is -0.2 rc and k would be 0.73 k_noslip: the check fails then, which is the point.)

Steps:
 1. bad input: a missing image, a bad axis, bad gradient lists, a non-percolating axis -> exit != 0
    with a message naming the culprit;
 2. --emit-scenes with --gradients auto: 5 scenes, log-spaced g = 12 mu u / (n h^2), u = 0.02..0.2,
    and a commands list;
 3. a campaign of 3 gradients killed (SIGTERM) during its second run: the first run's summary exists,
    the second's not;
 4. the campaign of 5 gradients (a superset) in the same folder: the finished run is reused (summary
    untouched, "reused" on stderr), the killed one and the new ones run; flow table valid (5 rows,
    metadata), `mdpore fit` chose a law and fitted Darcy, k within the bounds; permeability.json;
 5. --collect on the folder gives the same k;
 6. every run measured the pore core's density (pore voxels >= 1.5 rc from the solid: the slit's 4
    middle voxel layers, 4 x 12 x 8 = 384 voxels) near the fill's 6.2, and k used the standard
    water's viscosity at the core density of the run with the smallest body force
    (campaign/campaign_viscosity.c).
"""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "campaign_test_out"))
NP = os.environ.get("MDPORE_TEST_NP", "2")
STEPS = "8000"
# campaign/campaign.h: the generated template's wall density and the default mu (docs/permeability.md)
DEFAULT_WALL_DENSITY, DEFAULT_VISCOSITY = 4.0, 5.41
# campaign/campaign_viscosity.c: the standard water's mu against density (validation/results/engine/
# viscosity_density.md)
WATER_MU_AT_6_2, WATER_MU_SLOPE = 5.636, 1.572
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def mdpore(*args, **kw):
    return subprocess.run([MDPORE, *args], capture_output=True, text=True, cwd=OUT, **kw)


def expect_error(args, needle, what):
    p = mdpore(*args)
    check(p.returncode != 0 and needle in p.stderr,
          f"{what}: exit {p.returncode}, stderr names '{needle}'" + ("" if needle in p.stderr else f" (got: {p.stderr.strip()[:300]})"))


def read_table(path):
    meta, rows, cols = {}, [], None
    for line in open(path):
        line = line.strip()
        if line.startswith("#"):
            if ": " in line:
                k, v = line[1:].strip().split(": ", 1)
                meta[k] = v
            continue
        if cols is None:
            cols = line.split(",")
        else:
            rows.append(dict(zip(cols, map(float, line.split(",")))))
    return meta, cols, rows


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    os.environ.setdefault("MDPORE_CACHE_DIR", os.path.join(OUT, "cache"))
    p = mdpore("image", "make", "slit", "--width", "8", "--wall", "4", "--length", "12", "--depth", "8",
               "-o", "slit.h5")
    if p.returncode:
        sys.exit("image make failed: " + p.stderr)
    common = ["--max-steps", STEPS, "--target-error", "0.04", "--np", NP]

    # 1. bad input
    expect_error(["permeability", "missing.h5", "--axis", "x"], "missing.h5", "missing image")
    expect_error(["permeability", "slit.h5", "--axis", "w"], "--axis", "bad axis")
    expect_error(["permeability", "slit.h5", "--axis", "x", "--gradients", "0.1,abc"], "--gradients",
                 "bad gradient list")
    expect_error(["permeability", "slit.h5", "--axis", "x", "--gradients", "0.1"], "at least 2",
                 "one gradient")
    expect_error(["permeability", "slit.h5", "--axis", "x", "--gradients", "0.1,0,0.2"], "g = 0",
                 "zero gradient")
    expect_error(["permeability", "slit.h5", "--axis", "y", "--emit-scenes", "bad_y"], "does not percolate along y",
                 "non-percolating axis")
    expect_error(["permeability", "--collect", "nowhere"], "campaign.txt", "collect without a campaign")

    # 2. auto ladder, emitted
    p = mdpore("permeability", "slit.h5", "--axis", "x", "--emit-scenes", "emitted")
    runs = [l.split() for l in open(os.path.join(OUT, "emitted", "campaign.txt")) if l.startswith("run: ")] \
        if p.returncode == 0 else []
    g = [float(r[2]) for r in runs]
    g_exp = [12 * DEFAULT_VISCOSITY * u / (6.2 * 16) for u in [0.02 * 10 ** (i / 4) for i in range(5)]]
    check(p.returncode == 0 and len(g) == 5 and all(abs(a / b - 1) < 1e-3 for a, b in zip(g, g_exp)),
          f"auto ladder: 5 gradients g = 12 mu u / (n h^2), u = 0.02..0.2 log-spaced: {g} vs {[round(x, 5) for x in g_exp]}")
    cmds = open(os.path.join(OUT, "emitted", "commands.txt")).read().splitlines() if p.returncode == 0 else []
    check(len(cmds) == 5 and all(" run scene.yaml" in c for c in cmds), "commands.txt: one run per line")
    # --accuracy presets (docs/accuracy.md): the scene's run settings; explicit options win; bad name refused
    p = mdpore("permeability", "slit.h5", "--axis", "x", "--accuracy", "precise", "--target-error", "0.02",
               "--emit-scenes", "emitted_precise")
    runs_p = [l.split()[3] for l in open(os.path.join(OUT, "emitted_precise", "campaign.txt")) if l.startswith("run: ")] \
        if p.returncode == 0 else []
    text = open(os.path.join(runs_p[0], "scene.yaml")).read() if runs_p else ""
    check(p.returncode == 0 and "dt: 0.005" in text and "target_error: 0.02" in text and "steps: 400000" in text,
          "--accuracy precise: dt 0.005 and 400000 steps from the preset, the explicit --target-error 0.02 wins")
    expect_error(["permeability", "slit.h5", "--axis", "x", "--accuracy", "medium"], "--accuracy", "unknown accuracy preset")
    # --wall-density: the template's geometry.wall_density (default CAMP_DEFAULT_WALL_DENSITY, the manifest
    # and permeability.json carry it); bad values and a SCENE input refused
    p = mdpore("permeability", "slit.h5", "--axis", "x", "--wall-density", "5.5", "--emit-scenes", "emitted_wd")
    tmpl = open(os.path.join(OUT, "emitted_wd", "template.yaml")).read() if p.returncode == 0 else ""
    man = open(os.path.join(OUT, "emitted_wd", "campaign.txt")).read() if p.returncode == 0 else ""
    check(p.returncode == 0 and "wall_density: 5.5" in tmpl and "wall_density: 5.5" in man,
          "--wall-density 5.5 reaches the template's geometry and the manifest")
    tmpl0 = open(os.path.join(OUT, "emitted", "template.yaml")).read()
    check(f"wall_density: {DEFAULT_WALL_DENSITY:g}" in tmpl0,
          f"default wall density {DEFAULT_WALL_DENSITY:g} in the generated template")
    expect_error(["permeability", "slit.h5", "--axis", "x", "--wall-density", "-1"], "--wall-density",
                 "negative wall density")
    with open(os.path.join(OUT, "with_wd.yaml"), "w") as f:
        f.write(tmpl0)
    expect_error(["permeability", "with_wd.yaml", "--axis", "x", "--wall-density", "6"], "geometry.wall_density",
                 "--wall-density with a SCENE input")

    # --rng: the template's thermostat generator, in the manifest; the default leaves the template as it was
    p = mdpore("permeability", "slit.h5", "--axis", "x", "--rng", "fast", "--emit-scenes", "emitted_rng")
    tmpl = open(os.path.join(OUT, "emitted_rng", "template.yaml")).read() if p.returncode == 0 else ""
    man = open(os.path.join(OUT, "emitted_rng", "campaign.txt")).read() if p.returncode == 0 else ""
    man0 = open(os.path.join(OUT, "emitted", "campaign.txt")).read()
    check(p.returncode == 0 and "dpd_thermostat: {rng: fast}" in tmpl and "pair_rng: fast" in man,
          "--rng fast reaches the template's thermostat and the manifest")
    check("dpd_thermostat: {}" in tmpl0 and "pair_rng: philox" in man0,
          "default: philox, the thermostat's options empty (earlier runs' hashes unchanged)")
    expect_error(["permeability", "slit.h5", "--axis", "x", "--rng", "xorshift"], "--rng", "unknown generator")
    bad_man = os.path.join(OUT, "emitted_rng_bad")
    shutil.copytree(os.path.join(OUT, "emitted_rng"), bad_man)
    with open(os.path.join(bad_man, "campaign.txt"), "w") as f:
        f.write(man.replace("pair_rng: fast", "pair_rng: bogus"))
    expect_error(["permeability", "--collect", bad_man], "key 'pair_rng'", "a manifest naming an unknown generator")
    expect_error(["permeability", "with_wd.yaml", "--axis", "x", "--rng", "fast"], "dpd_thermostat.rng",
                 "--rng with a SCENE input")

    # 3. a campaign killed during its second run
    wd = os.path.join(OUT, "camp")
    first = ["permeability", "slit.h5", "--axis", "x", "--gradients", "0.1,0.22,0.14", "--workdir", wd, *common]
    proc = subprocess.Popen([MDPORE, *first], cwd=OUT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)
    rundirs = {}
    deadline = time.time() + 240
    killed = False
    while time.time() < deadline and proc.poll() is None:
        if os.path.exists(os.path.join(wd, "campaign.txt")) and not rundirs:
            for l in open(os.path.join(wd, "campaign.txt")):
                if l.startswith("run: "):
                    _, ax, gv, d = l.split()
                    rundirs[float(gv)] = d
        if rundirs and os.path.exists(os.path.join(rundirs[0.1], "summary.json")) and \
                os.path.exists(os.path.join(rundirs[0.22], "run.log")):
            # the second run has started (its log is opened before mdpore run starts): kill now. No
            # wait here: on an idle machine a run of this slit meets its target error in about a
            # second (no-slip walls flow faster), and a wait let it finish before the signal.
            proc.send_signal(signal.SIGTERM)
            killed = True
            break
        time.sleep(0.05)
    proc.communicate(timeout=60)
    check(killed and proc.returncode != 0, f"campaign killed during its second run (exit {proc.returncode})")
    s1 = os.path.join(rundirs.get(0.1, "-"), "summary.json")
    s2 = os.path.join(rundirs.get(0.22, "-"), "summary.json")
    check(os.path.exists(s1) and not os.path.exists(s2), "after the kill: run 1 finished, run 2 has no summary")
    st1 = os.stat(s1) if os.path.exists(s1) else None
    time.sleep(0.5)
    # no run process of the killed campaign may be left
    left = subprocess.run(["pgrep", "-f", rundirs.get(0.22, "-none-")], capture_output=True, text=True).stdout.strip()
    check(left == "", "no run process left behind by the killed campaign")

    # 4. the full campaign in the same folder
    t0 = time.time()
    p = mdpore("permeability", "slit.h5", "--axis", "x", "--gradients", "0.06,0.1,0.14,0.18,0.22", "--workdir", wd,
               *common)
    print(p.stdout)
    print(p.stderr)
    print(f"campaign: {time.time() - t0:.1f} s")
    check(p.returncode == 0, f"campaign exit 0 (got {p.returncode})")
    st1b = os.stat(s1) if os.path.exists(s1) else None
    check(st1 is not None and st1b is not None and st1.st_mtime_ns == st1b.st_mtime_ns and st1.st_ino == st1b.st_ino,
          "the finished run's summary was not rewritten (reused)")
    check(f"reused {rundirs.get(0.1)}" in p.stderr, "stderr reports the finished run as reused")
    check(p.stderr.count("running in") == 4, f"4 runs executed (the killed one + 3 new): {p.stderr.count('running in')}")
    check("progress 5/5 runs done" in p.stderr and "remaining" in p.stderr, "progress and ETA on stderr")
    table = os.path.join(wd, "flow_x.csv")
    meta, cols, rows = read_table(table) if os.path.exists(table) else ({}, [], [])
    check(cols[:4] == ["pressure_gradient", "darcy_velocity", "darcy_velocity_stderr", "run_length"] and len(rows) == 5,
          f"flow table: columns and 5 rows ({len(rows)})")
    check(meta.get("axis") == "x" and meta.get("viscosity") and meta.get("length_unit_m") and
          meta.get("voxel_size") == "0.5" and "porosity = 0.5" in open(table).read(),
          "flow table metadata: axis, viscosity, length_unit_m, voxel size, porosity")
    gs = [0.06, 0.1, 0.14, 0.18, 0.22]
    # G = N g / V_pore: every fluid particle carries the body force, so n is the template's fill (the
    # liquid's 6.2 plus what the walls adsorb, 2 Gamma / h), not the core's 6.2
    tmpl = open(os.path.join(wd, "template.yaml")).read() if os.path.exists(os.path.join(wd, "template.yaml")) else ""
    m = re.search(r"fluid_density: ([0-9.eE+-]+)", tmpl)
    n_fill = float(m.group(1)) if m else float("nan")
    check(abs(n_fill - (6.2 + 2 * 0.26 / 4.0)) < 1e-3, f"the fill adds what the walls adsorb: {n_fill} = 6.2 + 2 x 0.26 / h (h = 4)")
    check(len(rows) == 5 and all(r["darcy_velocity_stderr"] > 0 and r["darcy_velocity"] > 0 for r in rows) and
          all(abs(r["pressure_gradient"] - n_fill * x) < 1e-9 * n_fill for r, x in zip(rows, gs)),
          "rows: G = n_fill g, q > 0, q_err > 0")
    fit = json.load(open(os.path.join(wd, "fit_x.json"))) if os.path.exists(os.path.join(wd, "fit_x.json")) else {}
    darcy = [m for m in fit.get("models", []) if m["law"] == "darcy"]
    check(bool(darcy) and darcy[0]["ok"] and darcy[0]["converged"] and fit.get("chosen"), "mdpore fit: Darcy fitted, a law chosen")
    res = json.load(open(os.path.join(wd, "permeability.json"))) if os.path.exists(os.path.join(wd, "permeability.json")) else {}
    k = res.get("axes", {}).get("x", {}).get("k_rc2") or float("nan")
    k_err = res.get("axes", {}).get("x", {}).get("k_rc2_err") or float("nan")
    check(res.get("pair_rng") == "philox", f"permeability.json names the pair generator ({res.get('pair_rng')})")
    h, H = 4.0, 8.0
    k_noslip = h ** 3 / (12 * H)
    print(f"k = {k:.4f} +- {k_err:.4f} rc^2; k_noslip = h^3/(12 H) = {k_noslip:.4f}; k / k_noslip = "
          f"{k / k_noslip:.3f} +- {k_err / k_noslip:.3f}")
    check(abs(k / k_noslip - 1) <= 0.10 + 2 * k_err / k_noslip,
          f"k = {k:.4f} +- {k_err:.4f} rc^2 recovers h^3 / (12 H) = {k_noslip:.4f} within 10% + 2 sigma (no-slip walls)")
    check(res.get("axes", {}).get("x", {}).get("k_nD", 0) > 0 and "nD" in p.stdout and "m^2" in p.stdout,
          "k in m^2 and nD printed and written")

    dr = res.get("axes", {}).get("x", {}).get("darcy_range", {})
    check(dr.get("rows", 0) >= 2 and dr.get("k_rc2", 0) > 0 and "Darcy range" in p.stdout,
          f"the Darcy range reported: {dr.get('rows')} rows, k = {dr.get('k_rc2')}")

    # 5. collect again
    p = mdpore("permeability", "--collect", wd)
    res2 = json.load(open(os.path.join(wd, "permeability.json"))) if p.returncode == 0 else {}
    check(p.returncode == 0 and abs(res2["axes"]["x"]["k_rc2"] - k) <= 1e-12 * abs(k),
          "--collect reproduces k from the folder")

    # 6. the pore core's density, and the viscosity at it
    man = open(os.path.join(wd, "campaign.txt")).read().splitlines()
    cores, gs = [], []
    for l in man:
        if l.startswith("run: "):
            sp = os.path.join(l.split()[3], "summary.json")
            cores.append(json.load(open(sp)).get("pore_core_density") if os.path.exists(sp) else None)
            gs.append(float(l.split()[2]))
    check(len(cores) == 5 and all(c and c["voxels"] == 384 and c["samples"] > 0 for c in cores),
          f"every run's summary has the pore core's density over 384 voxels: {[c and c['voxels'] for c in cores]}")
    means = [c["mean"] for c in cores if c]
    print("pore core densities: " + ", ".join(f"{m:.4f}" for m in means))
    check(means and all(abs(m / 6.2 - 1) < 0.02 for m in means),
          "pore core densities within 2% of the liquid's 6.2 (the fill adds what the walls adsorb)")
    if len(means) == len(gs) and means:
        gentle = means[gs.index(min(gs))]
        mu_exp = WATER_MU_AT_6_2 + WATER_MU_SLOPE * (gentle - 6.2)
        check(abs(res.get("viscosity", 0) - mu_exp) < 1e-3 and "pore core" in res.get("viscosity_source", ""),
              f"k used mu = {res.get('viscosity')} at the core density of the smallest body force's run "
              f"(expected {mu_exp:.4f})")

    if failures:
        print(f"{len(failures)} check(s) failed:\n  " + "\n  ".join(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
