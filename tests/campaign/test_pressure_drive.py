#!/usr/bin/python3
"""ctest campaign_pressure_drive: `mdpore permeability --drive pressure` against `--drive body` on the
CI slit (CPU, 2 gradients each, <= 4000 steps on 2 ranks).

Slit: `mdpore image make slit --width 8 --wall 4 --length 12 --depth 8` at rc_per_voxel 0.5 (L_sample =
6 rc, h = 4 rc, period 8 rc). The pressure drive pads it along x with a 4 rc open reservoir and pushes
the fluid with inlet_force in the reservoir's middle; G = (P_in - P_out) / L_sample is measured
between probe slabs just outside the sample faces (docs/permeability.md, "Pressure-driven runs").

Asserted:
 1. bad input refused: --drive other, --drive pressure on a scene without a geometry image (the
    scene case: campaign_scene_pressure), --reservoir < 3;
 2. --emit-scenes: the scene names inlet_force (no body_force), the box and the image grow by the
    reservoir, the folders differ from the body-force ones (the hash sees the drive);
 3. every pressure run: the momentum balance, |dp / (inlet force / A_total) - 1| within 3 dp errors
    (+ 0.03 for the probes' finite width): the fluid between the probes carries the inlet force by
    the pressure step alone (open, periodic reservoir: no drag of its own);
 4. k_pressure against k_body: 0.5 k_body < k_pressure < k_body + 2 sigma. Not equal: the measured dp
    also holds the entrance and exit losses of the flow into and out of the slit (the body force
    has none: it drives every pore section alike), so k_pressure is lower. Measured 0.77 +- 0.03
    with 5 gradients, 0.81 +- 0.03 for a slit twice as long, 0.68 +- 0.04 in this test's short runs
    (docs/permeability.md). The bound 0.5: the thin-wall limit of a face loss (the 2D Stokes slit
    loss, Hasimoto 1958, adds at most 8 h / (3 pi) = 0.85 h_eff ~ 3.1 rc to L_sample = 6 rc: 0.66)
    less 4 errors (0.04 each) of these short runs' ratio;
 5. the pressure campaign rerun: every run reused (the cache), the same k; --collect the same k.
"""
import json
import os
import shutil
import subprocess
import sys

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "pressure_test_out"))
NP = os.environ.get("MDPORE_TEST_NP", "2")
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def mdpore(*args):
    return subprocess.run([MDPORE, *args], capture_output=True, text=True, cwd=OUT)


def expect_error(args, needle, what):
    p = mdpore(*args)
    check(p.returncode != 0 and needle in p.stderr,
          f"{what}: exit {p.returncode}, stderr names '{needle}'" + ("" if needle in p.stderr else f" (got: {p.stderr.strip()[:300]})"))


def runs_of(wd):
    return [l.split()[3] for l in open(os.path.join(wd, "campaign.txt")) if l.startswith("run: ")]


def k_of(wd):
    j = json.load(open(os.path.join(wd, "permeability.json")))
    return j["axes"]["x"]["k_rc2"], j["axes"]["x"]["k_rc2_err"]


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    p = mdpore("image", "make", "slit", "--width", "8", "--wall", "4", "--length", "12", "--depth", "8",
               "-o", "slit.h5")
    if p.returncode:
        sys.exit("image make failed: " + p.stderr)
    open(os.path.join(OUT, "scene.yaml"), "w").write("name: x\n")
    grads = ["--gradients", "0.1,0.2"]
    common = ["--max-steps", "8000", "--target-error", "0.05", "--np", NP]

    # 1. bad input
    expect_error(["permeability", "slit.h5", "--axis", "x", "--drive", "piston"], "--drive", "unknown drive")
    expect_error(["permeability", "scene.yaml", "--axis", "x", "--drive", "pressure"], "no image to pad",
                 "pressure drive of a scene without a geometry image")
    expect_error(["permeability", "slit.h5", "--axis", "x", "--drive", "pressure", "--reservoir", "2"],
                 "--reservoir", "reservoir too short")

    # 2. emitted scenes
    p = mdpore("permeability", "slit.h5", "--axis", "x", "--drive", "pressure", *grads, "--emit-scenes", "em_p")
    q = mdpore("permeability", "slit.h5", "--axis", "x", *grads, "--emit-scenes", "em_b")
    ok = p.returncode == 0 and q.returncode == 0
    check(ok, "--emit-scenes for both drives" + ("" if ok else f": {p.stderr} {q.stderr}"))
    if ok:
        rp = runs_of(os.path.join(OUT, "em_p"))
        rb = runs_of(os.path.join(OUT, "em_b"))
        text = open(os.path.join(rp[0], "scene.yaml")).read()
        check("inlet_force:" in text and "body_force" not in text and "hi: [10, 8, 4]" in text
              and "reservoir_x.raw" in text,
              "pressure scene: inlet_force, no body_force, box 6 + 4 rc along x, the padded image")
        check(not set(os.path.basename(d) for d in rp) & set(os.path.basename(d) for d in rb),
              "the run folders (hashes) of the two drives differ")
        info = subprocess.run([MDPORE, "image", "info", os.path.join(OUT, "em_p", "reservoir_x.raw")],
                              capture_output=True, text=True).stdout
        check("20 x 16 x 8" in info, "padded image: 12 + 8 voxels along x")
        ex = subprocess.run([MDPORE, "run", "--explain", "scene.yaml"], cwd=rp[0], capture_output=True,
                            text=True)
        check(ex.returncode == 0 and "inlet_force: constant force per particle inside x in [7, 9)" in ex.stdout,
              "--explain shows the inlet force in the reservoir's middle")

    # 3.-4. campaigns
    wd_b, wd_p = os.path.join(OUT, "body"), os.path.join(OUT, "pressure")
    pb = mdpore("permeability", "slit.h5", "--axis", "x", *grads, "--workdir", wd_b, *common)
    pp = mdpore("permeability", "slit.h5", "--axis", "x", "--drive", "pressure", *grads, "--workdir", wd_p,
                *common)
    print(pp.stdout)
    check(pb.returncode == 0 and pp.returncode == 0,
          "both campaigns ran" + ("" if pb.returncode == 0 and pp.returncode == 0 else f": {pb.stderr[-800:]} {pp.stderr[-800:]}"))
    if pb.returncode or pp.returncode:
        return
    for d in runs_of(wd_p):
        s = json.load(open(os.path.join(d, "summary.json")))["flux"]
        pd = s["pressure_drop"]
        bal, rel = pd["dp_over_force_per_area"], pd["dp_err"] / pd["dp"]
        check(s["G_source"].startswith("inlet_force") and abs(s["G"] - pd["dp"] / 6.0) < 1e-9 * abs(s["G"]),
              f"{os.path.basename(d)}: G = dp / L_sample = {s['G']:.4g} +- {s['G_err']:.2g}")
        check(abs(bal - 1) < 3 * rel + 0.03,
              f"{os.path.basename(d)}: momentum balance dp / (F / A) = {bal:.3f} (dp rel. error {rel:.3f})")
        check(os.path.exists(os.path.join(d, "pressure_profile.csv")), "pressure_profile.csv written")
    kb, kb_e = k_of(wd_b)
    kp, kp_e = k_of(wd_p)
    ratio = kp / kb
    print(f"k_body = {kb:.4f} +- {kb_e:.4f}, k_pressure = {kp:.4f} +- {kp_e:.4f}, ratio {ratio:.3f}")
    check(0.5 * kb < kp < kb + 2 * (kb_e ** 2 + kp_e ** 2) ** 0.5,
          f"0.5 k_body < k_pressure < k_body + 2 sigma: {kp:.4f} vs {kb:.4f} (ratio {ratio:.3f})")
    table = open(os.path.join(wd_p, "flow_x.csv")).read()
    check("pressure-driven runs" in table and "effective variance" in table, "flow table says how G was measured")

    # 5. cache and collect
    pr = mdpore("permeability", "slit.h5", "--axis", "x", "--drive", "pressure", *grads, "--workdir", wd_p,
                *common)
    check(pr.returncode == 0 and pr.stderr.count("reused") >= 2 and "running in" not in pr.stderr,
          "rerun: both pressure runs reused")
    check(pr.returncode == 0 and abs(k_of(wd_p)[0] - kp) < 1e-12, "rerun: the same k")
    pc = mdpore("permeability", "--collect", wd_p)
    check(pc.returncode == 0 and abs(k_of(wd_p)[0] - kp) < 1e-12, "--collect: the same k")


if __name__ == "__main__":
    main()
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")
