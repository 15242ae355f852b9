#!/usr/bin/python3
"""The flux output (output.flux) and the early stop (run.target_error) on a body-force slit
(scenes/flux_slit.yaml, CPU):
  A  2 ranks, target 0.03 within 40000 steps: the run stops early (summary flux.reached and
     stopped_early, last_step < 40000, relative error <= 0.03); flux.csv has the documented columns,
     a row every 10 steps up to the last step, N constant; q > 0 along the force; the Darcy
     relaxation time rho q / (phi G) in the summary, the correlation time used at least it and at
     least 30 independent samples at the stop; G = n F = 0.6 and
     the fluid fraction 3/5 exactly; the summary's q is the mean of the CSV's q from
     steady_from_step on; the profile's mobile flux sum_b density_b vx_b / (n bins) over its window
     equals the CSV's mean q over the same samples (the same definition, 1e-5), and q agrees with it
     within 4 q_err, and so does the porosity times the density-weighted mean profile velocity;
  B  1 rank, --steps 1000: the target is not reached: reached false, stderr says so;
  C  HDF5 file, no target, a checkpoint at step 200 and two restarts from it: the file is cut back
     to step 200 before the second continuation appends (no duplicated rows) and its rows equal the
     first continuation's (bitwise restarts), reached null;
  D  the same scene without output.flux: no flux file, no "flux" in the summary.
Usage: check_flux.py MDPORE "MPIEXEC [FLAGS]" SCENE WORKDIR"""
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

mdpore, mpi, scene, work = sys.argv[1:5]
ok = True


def check(cond, what):
    global ok
    print(("ok   " if cond else "FAIL ") + what)
    ok &= bool(cond)


def run(name, args, np_=1, text=None):
    d = os.path.join(work, name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    s = scene
    if text is not None:
        s = os.path.join(d, "scene.yaml")
        open(s, "w").write(text)
    cmd = (mpi.split() + ["-n", str(np_)] if np_ > 1 else []) + [mdpore, "run", "--backend", "cpu",
                                                                 "--output-dir", d] + args + [s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    print(p.stdout[-1500:], p.stderr[-800:])
    check(p.returncode == 0, f"{name}: mdpore run exit {p.returncode}")
    return d, p


def read_csv(path):
    lines = [l for l in open(path) if not l.startswith("#")]
    return lines[0].strip(), np.array([[float(v) for v in l.split(",")] for l in lines[1:]])


base = open(scene).read()
# ---- A: early stop on 2 ranks -------------------------------------------------------------------
d, p = run("A", [], np_=2)
s = json.load(open(os.path.join(d, "summary.json")))
f = s["flux"]
cols, rows = read_csv(os.path.join(d, "flux.csv"))
check(cols == "step,time,q,Q,G,u,N", f"flux.csv columns '{cols}'")
check(len(rows) > 100 and np.all(np.diff(rows[:, 0]) == 10) and rows[0, 0] == 0,
      f"flux.csv: {len(rows)} rows every 10 steps from 0")
check(rows[-1, 0] == s["last_step"], f"last row at the last step {s['last_step']}")
check(np.all(rows[:, 6] == 108), "N = 108 fluid particles in every row")
check(f["reached"] is True and f["stopped_early"] is True and s["last_step"] < 40000,
      f"target reached, stopped early at step {s['last_step']} of 40000")
check(f["relative_error"] <= 0.03 and abs(f["q_err"] / f["q"] - f["relative_error"]) < 1e-9,
      f"relative error {f['relative_error']:.4g} <= 0.03")
check(f["q"] > 0 and f["q_err"] > 0, f"q = {f['q']:.5g} +- {f['q_err']:.2g} > 0 along the force")
# the floor of the correlation time: the Darcy relaxation time rho q / (phi G) in steps (rho = 3,
# phi = 0.6, G = 0.6, dt = 0.02), and the correlation time used is at least it
relax = 3.0 * f["q"] / (0.6 * 0.6) / 0.02
check(abs(f["relaxation_steps"] - relax) < 1e-9 * relax and f["correlation_steps"] >= relax * (1 - 1e-12)
      and f["independent_samples"] >= 30,
      f"relaxation time {f['relaxation_steps']:.1f} steps = rho q / (phi G dt) = {relax:.1f}; correlation time "
      f"{f['correlation_steps']:.1f} >= it, {f['independent_samples']:.1f} independent samples")
check(abs(f["G"] - 0.6) < 1e-12 and abs(f["fluid_fraction"] - 0.6) < 1e-12,
      f"G = {f['G']} = n F = 0.6, fluid fraction {f['fluid_fraction']}")
check(np.allclose(rows[:, 2] * 15, rows[:, 3], rtol=1e-8) and np.allclose(rows[:, 2], 0.6 * rows[:, 5], rtol=1e-8),
      "Q = q A_total (A = 15) and q = phi u in every row")
steady = rows[rows[:, 0] >= f["steady_from_step"]]
check(len(steady) == f["samples_used"] and abs(steady[:, 2].mean() - f["q"]) < 1e-8 * abs(f["q"]),
      f"summary q = mean of the {len(steady)} CSV rows from step {f['steady_from_step']}")
# the profile over its own window (steps >= 1000, every 10: the same samples as the CSV)
plines = [l for l in open(os.path.join(d, "profile.csv")) if not l.startswith("#")]
hdr = plines[0].strip().split(",")
prof = np.array([[float(v) for v in l.split(",")] for l in plines[1:]])
col = {h: i for i, h in enumerate(hdr)}
rho, vx, y = prof[:, col["density_liquid"]], prof[:, col["vx"]], prof[:, col["y"]]
q_prof = float(np.sum(rho * vx) / (3.0 * len(y)))
window = rows[rows[:, 0] >= 1000, 2]
check(abs(q_prof - window.mean()) < 1e-5 * abs(q_prof),
      f"profile flux sum_b rho_b vx_b / (n bins) = {q_prof:.7g} = CSV mean over the same samples {window.mean():.7g}")
check(abs(f["q"] - q_prof) < 4 * f["q_err"], f"q {f['q']:.5g} agrees with the profile's {q_prof:.5g} within 4 q_err")
# porosity x mean profile velocity: the density-weighted mean (sum_b rho_b vx_b / sum_b rho_b) is
# the one q equals; the plain mean over the channel bins is only near it, as the density dips next
# to the walls and some fluid sits in the rough walls (printed, not checked)
phi_v = 0.6 * float(np.sum(rho * vx) / np.sum(rho))
check(abs(phi_v - q_prof) < 1e-3 * abs(q_prof) and abs(f["q"] - phi_v) < 4 * f["q_err"],
      f"q {f['q']:.5g} = porosity x density-weighted profile velocity {phi_v:.5g} within 4 q_err")
channel = (y > 1.0) & (y < 4.0)
print(f"info porosity x plain mean of the channel bins' vx: {0.6 * vx[channel].mean():.5g}")

# ---- B: budget too small -----------------------------------------------------------------------
d, p = run("B", ["--steps", "1000"])
f = json.load(open(os.path.join(d, "summary.json")))["flux"]
check(f["reached"] is False and f["stopped_early"] is False, "B: target not reached in 1000 steps")
check("NOT reached" in p.stderr and "NOT reached" in p.stdout, "B: stderr and summary say so")

# ---- C: HDF5, restarts cut the file back --------------------------------------------------------
text = base.replace("flux.csv", "flux.h5").replace(", target_error: 0.03", "")
text = text.replace("progress: false", "progress: false\n  checkpoint: {every: 1000, file: restart.h5}")
d, p = run("C", ["--steps", "200"], text=text)
shutil.copy(os.path.join(d, "restart.h5"), os.path.join(d, "at200.h5"))
sc = os.path.join(d, "scene.yaml")
out = os.path.join(d, "out")
for k in (1, 2):
    q = subprocess.run([mdpore, "run", "--backend", "cpu", "--output-dir", d, "--steps", "100",
                        "--restart", os.path.join(d, "at200.h5"), sc], capture_output=True, text=True)
    check(q.returncode == 0, f"C: restart {k} from step 200 exit {q.returncode} {q.stderr[-300:]}")
    with h5py.File(os.path.join(d, "flux.h5"), "r") as h:
        data = h["flux"][:]
        check(h["flux"].attrs["columns"] in ("step,time,q,Q,G,u,N", b"step,time,q,Q,G,u,N"), "C: HDF5 columns")
    check(np.array_equal(data[:, 0], np.arange(0, 301, 10)), f"C: restart {k}: rows 0..300 every 10, none twice")
    if k == 1:
        first = data.copy()
check(np.array_equal(first, data), "C: the second continuation rewrote the same rows (bitwise)")
f = json.load(open(os.path.join(d, "summary.json")))["flux"]
check(f["samples"] == 31 and f["reached"] is None and f["target_error"] is None,
      f"C: the summary analyses all 31 samples; no target: reached null")

# ---- D: not asked, nothing done ----------------------------------------------------------------
text = base.replace("  flux: {axis: x, every: 10, file: flux.csv}\n", "").replace(", target_error: 0.03", "")
d, p = run("D", ["--steps", "50"], text=text)
check(not os.path.exists(os.path.join(d, "flux.csv")) and "flux" not in json.load(open(os.path.join(d, "summary.json"))),
      "D: without output.flux no file and no summary entry")
sys.exit(0 if ok else 1)
