"""Shared helpers of the engine validation scripts: build scenes, run mdpore, read its outputs,
block-average time series, and write the table + PNG that every validation leaves behind.

Run with /usr/bin/python3 (Debian numpy, matplotlib, yaml). The mdpore binary is $MDPORE, or
build/bin/mdpore under the repository root.
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import time

import numpy as np
import yaml

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def mdpore_binary():
    exe = os.environ.get("MDPORE") or os.path.join(ROOT, "build", "bin", "mdpore")
    if not os.path.exists(exe):
        sys.exit(f"validation: mdpore binary not found at {exe} (build first, or set MDPORE)")
    return exe


def mpi_env():
    env = dict(os.environ)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_MCA_btl_vader_single_copy_mechanism="none")
    env.setdefault("OMP_NUM_THREADS", "1")
    return env


def mdpd_scene(name, box_hi, fills, *, A=-40.0, B=25.0, rd=0.75, gamma=4.5, rc=1.0, dt=0.01, steps=1000,
               seed=1, thermo_every=10, profile=None, effects=None, dump_every=0, kernel="warren"):
    """A one-species scene dict in the mdpore scene format (docs/scene-format.md)."""
    if effects is None:
        effects = {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {}}
    scene = {
        "name": name,
        "box": {"lo": [0.0, 0.0, 0.0], "hi": [float(v) for v in box_hi], "periodic": [True, True, True]},
        "species": [{"name": "liquid", "mass": 1.0}],
        "pairs": {"default": {"A": float(A), "B": float(B), "gamma": float(gamma), "rc": float(rc),
                              "rd": float(rd)}},
        "density_kernel": kernel,
        "kT": 1.0,
        "effects": effects,
        "initial": {"fill": fills, "temperature": 1.0},
        "run": {"dt": float(dt), "steps": int(steps), "seed": int(seed)},
        "output": {"thermo": {"every": int(thermo_every), "file": "thermo.csv"}, "summary": "summary.json",
                   "progress": False},
    }
    if profile:
        scene["output"]["profile"] = dict(profile, file="profile.csv")
    if dump_every:
        scene["output"]["dump"] = {"every": int(dump_every), "file": "dump.lammpstrj"}
    return scene


def fill_box(box_hi, density, lo=None, hi=None, mode="random"):
    return {"species": "liquid", "lo": list(lo or [0.0, 0.0, 0.0]), "hi": list(hi or box_hi),
            "density": float(density), "mode": mode}


def run(scene, workdir, np_ranks=2, timeout=3600):
    """Write scene.yaml into workdir, run mdpore on np_ranks ranks there; returns wall seconds."""
    if os.path.isdir(workdir):
        shutil.rmtree(workdir)
    os.makedirs(workdir)
    with open(os.path.join(workdir, "scene.yaml"), "w") as f:
        yaml.safe_dump(scene, f, sort_keys=False)
    cmd = [mdpore_binary(), "run", "scene.yaml"]
    if np_ranks > 1:
        cmd = ["mpiexec", "-n", str(np_ranks), "--oversubscribe"] + cmd
    t0 = time.time()
    proc = subprocess.run(cmd, cwd=workdir, env=mpi_env(), capture_output=True, text=True, timeout=timeout)
    wall = time.time() - t0
    with open(os.path.join(workdir, "stdout.txt"), "w") as f:
        f.write(proc.stdout)
    with open(os.path.join(workdir, "stderr.txt"), "w") as f:
        f.write(proc.stderr)
    if proc.returncode != 0:
        sys.stderr.write(proc.stdout[-3000:] + proc.stderr[-3000:])
        raise RuntimeError(f"mdpore failed in {workdir} (exit {proc.returncode})")
    return wall


def read_table(path):
    """A CSV written by mdpore (lines starting with '#' are metadata) as a dict of float arrays."""
    with open(path) as f:
        rows = [line for line in f if line.strip() and not line.startswith("#")]
    reader = csv.reader(rows)
    header = [h.strip() for h in next(reader)]
    data = np.array([[float(v) for v in r] for r in reader if r])
    return {h: data[:, i] for i, h in enumerate(header)}


def column(table, *names):
    for n in names:
        if n in table:
            return table[n]
    raise KeyError(f"none of {names} in columns {list(table)}")


def block_average(x, min_blocks=16):
    """Mean and standard error of a correlated series (Flyvbjerg & Petersen 1989): the error is the
    largest block-average estimate over block sizes that still leave >= min_blocks blocks."""
    x = np.asarray(x, dtype=float)
    n = len(x)
    if n < 2:
        return float(x.mean()) if n else float("nan"), float("inf")
    best = x.std(ddof=1) / math.sqrt(n)
    size = 1
    while n // size >= min_blocks:
        nb = n // size
        blocks = x[: nb * size].reshape(nb, size).mean(axis=1)
        best = max(best, blocks.std(ddof=1) / math.sqrt(nb))
        size *= 2
    return float(x.mean()), float(best)


def thermo_window(workdir, start_step):
    t = read_table(os.path.join(workdir, "thermo.csv"))
    mask = column(t, "step") >= start_step
    return {k: v[mask] for k, v in t.items()}


def out_dir(name):
    d = os.environ.get("MDPORE_VALIDATION_OUT") or os.path.join(ROOT, "validation", "results")
    d = os.path.join(d, name)
    os.makedirs(d, exist_ok=True)
    return d


def write_report(outdir, name, header, rows, notes=""):
    """Markdown table (name.md) and CSV (name.csv) side by side."""
    with open(os.path.join(outdir, name + ".csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    with open(os.path.join(outdir, name + ".md"), "w") as f:
        if notes:
            f.write(notes.rstrip() + "\n\n")
        f.write("| " + " | ".join(header) + " |\n")
        f.write("|" + "---|" * len(header) + "\n")
        for r in rows:
            f.write("| " + " | ".join(fmt(v) for v in r) + " |\n")
    print(open(os.path.join(outdir, name + ".md")).read())


def fmt(v):
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def write_json(path, obj):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(obj, f, indent=2)
    os.replace(tmp, path)


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def read_dump_frames(path):
    """Frames of a LAMMPS-style text dump: list of (step, box_lo, box_hi, dict column -> array)."""
    frames = []
    with open(path) as f:
        lines = f.read().splitlines()
    i = 0
    while i < len(lines):
        if lines[i].startswith("ITEM: TIMESTEP"):
            step = int(lines[i + 1])
            n = int(lines[i + 3])
            bounds = [list(map(float, lines[i + 5 + k].split()[:2])) for k in range(3)]
            cols = lines[i + 8].split()[2:]
            data = np.array([list(map(float, l.split())) for l in lines[i + 9:i + 9 + n]])
            frames.append((step, np.array([b[0] for b in bounds]), np.array([b[1] for b in bounds]),
                           {c: data[:, k] for k, c in enumerate(cols)}))
            i += 9 + n
        else:
            i += 1
    return frames


def void_fraction(frame, cell=2.0, threshold=0.3):
    """Fraction of coarse cells (~cell wide) whose particle count is below threshold x the mean: ~0 in a
    homogeneous liquid, large once it has separated into liquid and vapour."""
    _, lo, hi, cols = frame
    pos = np.stack([cols["x"], cols["y"], cols["z"]], axis=1)
    nb = np.maximum(1, np.floor((hi - lo) / cell).astype(int))
    idx = np.floor((pos - lo) / (hi - lo) * nb).astype(int) % nb
    counts = np.zeros(nb)
    np.add.at(counts, (idx[:, 0], idx[:, 1], idx[:, 2]), 1)
    return float(np.mean(counts < threshold * counts.mean()))
