#!/usr/bin/python3
"""ctest campaign_scene_pressure: `mdpore permeability SCENE --drive pressure` on the CI
slit (CPU, 2 gradients of <= 3000 steps on 2 ranks: about half a minute on 2 cores).

A SCENE whose particles come from `geometry: {image: ...}` gets its image padded with the open
reservoir and its body force replaced by inlet_force by the same code as an IMAGE input
(campaign_template.c write_padded_images, campaign_scene.c pressure_drive). The strongest check of
"the same code" is that the scene of the IMAGE campaign (its template.yaml), given back as a SCENE,
plans byte-identical run scenes and therefore reuses the IMAGE campaign's runs.

Asserted:
 1. a SCENE whose particles do not come from an image (initial.fill) is refused: exit != 0, the
    message names the scene file, the key geometry.image, where its particles come from and why
    (no image to pad); nothing is planned;
 2. --emit-scenes: the IMAGE campaign and the SCENE campaign (its template.yaml copied elsewhere)
    write byte-identical padded images and run scenes identical up to the work folder's path;
 3. a hand-written scene (relative image path, voxels_per_rc 4, axis_map [y, x, z], its own
    species names and body force, flow along y): the padded image is in the box frame (16 x 28 x 8
    voxels: 12 + 16 reservoir voxels of 0.25 rc along box y), the run scene's box grows by 4 rc
    along y, inlet_force on its fluid species replaces its body force, axis_map is gone (the padded
    image is already permuted), and `mdpore forces` builds the particles of that scene (box = image);
 4. the IMAGE pressure campaign runs; the SCENE campaign in the same work folder plans the same run
    folders, reuses every run (runs nothing) and writes the same flow table rows and the same k;
 5. the SCENE campaign in a fresh work folder runs its own runs: k agrees with the IMAGE campaign's
    within 2 combined standard errors (the same scenes and seeds up to the image path, so the runs
    may even repeat the IMAGE runs exactly; the bound does not rely on that).
"""
import json
import os
import shutil
import subprocess
import sys

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "scene_pressure_test_out"))
NP = os.environ.get("MDPORE_TEST_NP", "2")
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def mdpore(*args, cwd=None):
    return subprocess.run([MDPORE, *args], capture_output=True, text=True, cwd=cwd or OUT)


def runs_of(wd):
    return [l.split()[3] for l in open(os.path.join(wd, "campaign.txt")) if l.startswith("run: ")]


def k_of(wd):
    j = json.load(open(os.path.join(wd, "permeability.json")))
    return j["axes"]["x"]["k_rc2"], j["axes"]["x"]["k_rc2_err"]


def table_rows(wd):
    return [l for l in open(os.path.join(wd, "flow_x.csv")) if l.strip() and not l.startswith("#")]


def read(path, mode="r"):
    with open(path, mode) as f:
        return f.read()


USER_SCENE = """name: user_slit
box: {lo: [0, 0, 0], hi: [4, 3, 2]}
species:
  - {name: water, mass: 1.0}
  - {name: rock, mass: 1.0, frozen: true}
pairs: {default: {A: -40.0, B: 25.0, gamma: 4.5, rc: 1.0, rd: 0.75}}
kT: 1.0
effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}, body_force: {water: [0.01, 0, 0]},
          bounce_back: {}}
geometry:
  image: slit.h5
  voxels_per_rc: 4
  axis_map: [y, x, z]
  flow_axis: y
  fluid_density: 6.2
  species: {fluid: water, inorganic: rock}
initial: {temperature: 1.0}
run: {dt: 0.01, steps: 100}
"""

FILL_SCENE = """name: bulk
box: {lo: [0, 0, 0], hi: [4, 4, 4]}
species: [{name: a}]
pairs: {default: {A: -40.0, B: 25.0, gamma: 4.5, rc: 1.0, rd: 0.75}}
kT: 1.0
effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}}
initial: {fill: [{species: a, density: 6}], temperature: 1.0}
run: {dt: 0.01, steps: 100}
"""


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(os.path.join(OUT, "user"))
    p = mdpore("image", "make", "slit", "--width", "8", "--wall", "4", "--length", "12", "--depth", "8",
               "-o", "slit.h5")
    if p.returncode:
        sys.exit("image make failed: " + p.stderr)
    shutil.copy(os.path.join(OUT, "slit.h5"), os.path.join(OUT, "user", "slit.h5"))
    open(os.path.join(OUT, "user", "user.yaml"), "w").write(USER_SCENE)
    open(os.path.join(OUT, "fill.yaml"), "w").write(FILL_SCENE)
    grads = ["--gradients", "0.1,0.2"]
    common = ["--max-steps", "3000", "--target-error", "0.05", "--np", NP]

    # 1. a scene without an image
    fill = os.path.join(OUT, "fill.yaml")
    p = mdpore("permeability", "fill.yaml", "--axis", "x", "--drive", "pressure", *grads,
               "--emit-scenes", "em_fill")
    msg = p.stderr
    check(p.returncode != 0 and fill in msg and "key 'geometry.image'" in msg and "initial.fill" in msg
          and "no image to pad" in msg,
          f"fill scene refused: exit {p.returncode}, names the file, the key, the particle source and why"
          + ("" if p.returncode and "no image to pad" in msg else f" (got: {msg.strip()[:400]})"))
    check(not os.path.exists(os.path.join(OUT, "em_fill", "campaign.txt")), "fill scene: nothing planned")

    # 2. the IMAGE's template as a SCENE: the same padded image and the same run scenes
    p = mdpore("permeability", "slit.h5", "--axis", "x", "--drive", "pressure", *grads, "--emit-scenes", "em_i")
    ok = p.returncode == 0
    if ok:
        shutil.copy(os.path.join(OUT, "em_i", "template.yaml"), os.path.join(OUT, "user", "template_scene.yaml"))
        q = mdpore("permeability", "user/template_scene.yaml", "--axis", "x", "--drive", "pressure", *grads,
                   "--emit-scenes", "em_s")
        ok = q.returncode == 0
    check(ok, "--emit-scenes: IMAGE and its template as a SCENE" + ("" if ok else f": {p.stderr} {q.stderr}"))
    if ok:
        check(read(os.path.join(OUT, "em_i", "reservoir_x.raw"), "rb")
              == read(os.path.join(OUT, "em_s", "reservoir_x.raw"), "rb"), "the same padded image (bytes)")
        ri, rs = runs_of(os.path.join(OUT, "em_i")), runs_of(os.path.join(OUT, "em_s"))
        same = len(ri) == len(rs) == 2
        for a, b in zip(ri, rs):
            ta = read(os.path.join(a, "scene.yaml")).replace(os.path.join(OUT, "em_i"), "WORKDIR")
            tb = read(os.path.join(b, "scene.yaml")).replace(os.path.join(OUT, "em_s"), "WORKDIR")
            same = same and ta.split("\n", 1)[1] == tb.split("\n", 1)[1] and "inlet_force" in tb
        check(same, "the run scenes are identical up to the work folder (inlet_force, padded image)")

    # 3. a hand-written scene: relative image, voxels_per_rc, axis_map, its own species
    p = mdpore("permeability", "user/user.yaml", "--axis", "y", "--drive", "pressure", *grads,
               "--emit-scenes", "em_u")
    check(p.returncode == 0, "--emit-scenes: hand-written scene" + ("" if p.returncode == 0 else f": {p.stderr}"))
    if p.returncode == 0:
        info = mdpore("image", "info", os.path.join(OUT, "em_u", "reservoir_y.raw")).stdout
        check("16 x 28 x 8" in info, "padded image in the box frame: 16 x (12 + 16) x 8 voxels")
        d = runs_of(os.path.join(OUT, "em_u"))[0]
        text = read(os.path.join(d, "scene.yaml"))
        check("hi: [4, 7, 2]" in text and "inlet_force: {water: [0, " in text and "body_force" not in text
              and "axis_map" not in text and "reservoir_y.raw" in text and "along: y" in text,
              "run scene: box 3 + 4 rc along y, inlet_force on water, no body_force, no axis_map")
        f = mdpore("forces", "scene.yaml", cwd=d)
        check(f.returncode == 0 and "particles" in f.stdout,
              "mdpore forces builds the run scene (box = padded image)"
              + ("" if f.returncode == 0 else f": {f.stderr.strip()[-400:]}"))

    # 4. IMAGE campaign, then the SCENE campaign in the same folder: the same runs, reused
    wd = os.path.join(OUT, "camp")
    pi = mdpore("permeability", "slit.h5", "--axis", "x", "--drive", "pressure", *grads, "--workdir", wd, *common)
    check(pi.returncode == 0, "IMAGE pressure campaign ran" + ("" if pi.returncode == 0 else f": {pi.stderr[-800:]}"))
    if pi.returncode:
        return
    runs_i, rows_i, (k_i, k_i_err) = runs_of(wd), table_rows(wd), k_of(wd)
    shutil.copy(os.path.join(wd, "template.yaml"), os.path.join(OUT, "user", "camp_scene.yaml"))
    ps = mdpore("permeability", "user/camp_scene.yaml", "--axis", "x", "--drive", "pressure", *grads,
                "--workdir", wd, *common)
    check(ps.returncode == 0 and runs_of(wd) == runs_i, "SCENE campaign in the same folder: the same run folders")
    check(ps.returncode == 0 and ps.stderr.count("reused") >= 2 and "running in" not in ps.stderr,
          "SCENE campaign: every run reused, none run")
    check(ps.returncode == 0 and table_rows(wd) == rows_i and abs(k_of(wd)[0] - k_i) < 1e-12,
          f"SCENE campaign: the same flow table rows and k = {k_i:.4f} +- {k_i_err:.4f} rc^2")

    # 5. the SCENE campaign on its own: k within error bars of the IMAGE's
    wd2 = os.path.join(OUT, "camp_scene")
    ps = mdpore("permeability", "user/camp_scene.yaml", "--axis", "x", "--drive", "pressure", *grads,
                "--workdir", wd2, *common)
    check(ps.returncode == 0 and ps.stderr.count("running in") == 2,
          "SCENE campaign in a fresh folder ran its 2 runs" + ("" if ps.returncode == 0 else f": {ps.stderr[-800:]}"))
    if ps.returncode == 0:
        k_s, k_s_err = k_of(wd2)
        print(f"k_image = {k_i:.4f} +- {k_i_err:.4f}, k_scene = {k_s:.4f} +- {k_s_err:.4f}")
        check(abs(k_s - k_i) <= 2 * (k_i_err ** 2 + k_s_err ** 2) ** 0.5,
              f"k_scene {k_s:.4f} within 2 sigma of k_image {k_i:.4f}")
        check("pressure-driven runs" in read(os.path.join(wd2, "flow_x.csv")), "the flow table says how G was measured")


if __name__ == "__main__":
    main()
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")
