"""mdpore run --replicas (meso/run/run_replicas.c): several one-rank runs at once in one process.

Four small scenes of different physics and outputs (the flux slit at two seeds and forces; the
mDPD box of the checkpoint tests at two seeds, with HDF5 checkpoints and snapshots) run
first alone, then together with a fourth replica that fails at set-up (its restart file is
missing). Checked:
  - every file a replica writes is the one it writes alone: text outputs byte for byte, the summary
    but for its timing, the HDF5 files dataset by dataset and attribute by attribute;
  - the failing replica is named and the command exits 1, after the others finished;
  - a scene that does not load stops the command before anything runs (nothing written);
  - two replicas whose outputs would be one file are refused, naming both scenes.
usage: test_replicas.py MDPORE SCENES_DIR OUT_DIR
"""
import filecmp
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

MDPORE, SCENES, OUT = sys.argv[1], sys.argv[2], sys.argv[3]
ENV = dict(os.environ, OMP_NUM_THREADS="1")  # the same threads alone and as a replica
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def run(args):
    p = subprocess.run([MDPORE, "run", "--backend", "cpu"] + args, cwd=OUT, env=ENV,
                       capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def scene(name, source, edits=()):
    os.makedirs(os.path.join(OUT, name))
    text = open(os.path.join(SCENES, source)).read()
    for old, new in edits:
        assert old in text, (source, old)
        text = text.replace(old, new)
    open(os.path.join(OUT, name, "scene.yaml"), "w").write(text)
    return f"{name}/scene.yaml"


def h5_same(a, b):
    """1 when two HDF5 files hold the same groups, datasets (values, bits) and attributes."""
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        names_a, names_b = [], []
        fa.visit(names_a.append)
        fb.visit(names_b.append)
        if sorted(names_a) != sorted(names_b):
            return False
        for n in ["/"] + names_a:
            oa, ob = fa[n], fb[n]
            if sorted(oa.attrs) != sorted(ob.attrs):
                return False
            for k in oa.attrs:
                if not np.array_equal(np.asarray(oa.attrs[k]), np.asarray(ob.attrs[k])):
                    return False
            if isinstance(oa, h5py.Dataset):
                va, vb = oa[()], ob[()]
                if va.dtype != vb.dtype or va.shape != vb.shape or va.tobytes() != vb.tobytes():
                    return False
    return True


def summary_sans_timing(path):
    j = json.load(open(path))
    j.pop("timing", None)
    return j


def same_outputs(alone, replica):
    """The files of two folders compared as the run writes them; a list of the differing ones."""
    names = sorted(set(os.listdir(alone)) | set(os.listdir(replica)))
    bad = []
    for n in names:
        a, b = os.path.join(alone, n), os.path.join(replica, n)
        if not (os.path.exists(a) and os.path.exists(b)):
            bad.append(n + " (only in one)")
        elif n == "summary.json":
            if summary_sans_timing(a) != summary_sans_timing(b):
                bad.append(n)
        elif n.endswith(".h5"):
            if not h5_same(a, b):
                bad.append(n)
        elif not filecmp.cmp(a, b, shallow=False):
            bad.append(n)
    return bad


shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)
good = [
    scene("slit7", "flux_slit.yaml", [("steps: 40000", "steps: 1500")]),
    scene("slit8", "flux_slit.yaml", [("steps: 40000", "steps: 1200"), ("seed: 7", "seed: 8"),
                                      ("liquid: [0.2, 0, 0]", "liquid: [0.1, 0, 0]")]),
    scene("mdpd", "checkpoint_faults.yaml", [("steps: 600", "steps: 300")]),
    scene("mdpd98", "checkpoint_faults.yaml", [("steps: 600", "steps: 300"), ("seed: 99", "seed: 98")]),
]
broken = scene("norestart", "flux_slit.yaml", [("steps: 40000", "steps: 200"),
                                               ("name: flux_slit", "name: flux_slit\nrestart: gone.h5")])

# alone, each into its own folder; the outputs kept aside, the folder emptied but for its scene
for s in good:
    d = os.path.dirname(s)
    rc, log = run(["--output-dir", d, s])
    check(rc == 0, f"{s} alone: exit 0 ({log[-300:] if rc else ''})")
    shutil.copytree(os.path.join(OUT, d), os.path.join(OUT, "alone_" + d))
    for n in os.listdir(os.path.join(OUT, d)):
        if n != "scene.yaml":
            p = os.path.join(OUT, d, n)
            shutil.rmtree(p) if os.path.isdir(p) else os.remove(p)

# a scene that does not load: nothing runs
rc, log = run(["--replicas", good[0], "missing/scene.yaml"])
check(rc != 0 and "missing/scene.yaml (replica 2 of 2) did not load; nothing ran" in log,
      f"a scene that does not load stops the command (exit {rc})")
check(os.listdir(os.path.join(OUT, "slit7")) == ["scene.yaml"], "... before any replica wrote")

# two replicas writing one file: refused, naming both
shutil.copy(os.path.join(OUT, good[0]), os.path.join(OUT, "slit7", "twin.yaml"))
rc, log = run(["--replicas", good[0], "slit7/twin.yaml"])
check(rc == 2 and "slit7/scene.yaml and slit7/twin.yaml would both write" in log,
      f"two replicas with one output file refused (exit {rc})")
os.remove(os.path.join(OUT, "slit7", "twin.yaml"))

# together, with one that fails at set-up
rc, log = run(["--replicas"] + good + [broken])
check(rc == 1, f"the replicas with a failing one: exit 1 (got {rc})")
check("replica 5 of 5 (norestart/scene.yaml) failed" in log and
      "1 of 5 replicas failed; the others finished" in log, "the failing replica named")
for s in good:
    d = os.path.dirname(s)
    bad = same_outputs(os.path.join(OUT, "alone_" + d), os.path.join(OUT, d))
    n = len(os.listdir(os.path.join(OUT, d)))
    check(not bad, f"{d}: {n} files as a replica the same as alone" + (f": differ {bad}" if bad else ""))
check(not os.path.exists(os.path.join(OUT, "norestart", "summary.json")),
      "the failing replica wrote no summary")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all checks passed")
