#!/usr/bin/env python3
"""Load balancing (balance:, meso/domain/balance.c, meso/engine/sim_balance.c) on 2 CPU ranks, on the
heterogeneous image of bench/balance.py (half dense solid, half open pores along x):
  1. cuts by cost, and cuts moved during the run (balance.every 5, threshold 1: a move at every
     check), give the same particles at step 20 as uniform cuts, to summation-order rounding (the
     particles were redistributed, none lost or doubled, the rebuilt backend continued the
     trajectory);
  2. cost cuts: weight imbalance <= 1.05 where uniform cuts give > 1.1, reported in the summary;
  3. a run with cost cuts restarts bitwise from its checkpoint (the checkpoint's cuts are adopted);
  4. bad balance keys are refused naming the key.
With BACKEND cuda (2 ranks sharing the GPUs there are; skipped, exit 77, without one): the same on
the GPU path, positions to float-rounding tolerance (single-precision pair math), and no rebalancing
during the run (the busy time of asynchronous GPU phases is not measured: the cuts stay by weight).
usage: test_balance.py MDPORE MPIEXEC [cpu|cuda]
"""
import copy
import importlib.util
import json
import os
import shutil
import subprocess
import sys


try:  # the GPU machine has no h5py: read the dump there
    import h5py
except ImportError:
    h5py = None

M, MPI = sys.argv[1], sys.argv[2]
BACKEND = sys.argv[3] if len(sys.argv) > 3 else "cpu"
GPU = BACKEND == "cuda"
HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("balance_bench", os.path.join(HERE, "..", "..", "bench", "balance.py"))
bench = importlib.util.module_from_spec(spec)
spec.loader.exec_module(bench)

W = os.path.abspath(f"balance_test_{BACKEND}")
shutil.rmtree(W, ignore_errors=True)
os.makedirs(W)
if GPU:
    probe = subprocess.run([M, "run", "--backend", "cuda", "--explain", os.path.join(HERE, "scenes", "restart_small.yaml")],
                           capture_output=True, text=True)
    if probe.returncode:
        print("skipped: no GPU (" + probe.stderr.strip().split("available: ")[-1] + ")")
        sys.exit(77)
img = os.path.join(W, "hetero.raw")
STORED = os.path.join(HERE, "data", "balance_hetero_48x20x20.raw")  # make_image(.., 48, 20, 20, 3)
if bench.np is not None:
    bench.make_image(img, 48, 20, 20, 3)
    # the stored copy (for machines without numpy) must be what make_image makes
    if open(img, "rb").read() != open(STORED, "rb").read():
        sys.exit(f"FAIL: {STORED} differs from bench/balance.py make_image(48, 20, 20, seed 3)")
else:
    shutil.copy(STORED, img)
    shutil.copy(STORED + ".hdr", img + ".hdr")
BOX = [24.0, 10.0, 10.0]
fails = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        fails.append(what)


def run(name, balance, steps=20, extra=(), scene_changes=None):
    wd = os.path.join(W, name)
    os.makedirs(wd, exist_ok=True)
    sc = bench.scene(img, BOX, steps, 2, balance)
    sc["output"]["snapshot"] = {"every": 10, "file": "snap"}
    sc["output"]["checkpoint"] = {"every": 10, "file": "restart.h5"}
    sc["output"]["dump"] = {"every": 10, "file": "dump.lammpstrj"}
    if scene_changes:
        scene_changes(sc)
    with open(os.path.join(wd, "scene.yaml"), "w") as f:
        json.dump(sc, f, indent=1)  # JSON is YAML
    p = subprocess.run([MPI, "-n", "2", M, "run", "--backend", BACKEND, "scene.yaml", *extra], cwd=wd,
                       capture_output=True, text=True)
    return p, wd


def particles(wd, step):
    """ids, positions, velocities at `step`, sorted by id: the HDF5 snapshot, else the dump."""
    if h5py is not None:
        with h5py.File(os.path.join(wd, f"snap_{step:09d}.h5"), "r") as f:
            ids = [int(i) for i in f["/particles/id"][:]]
            pos = [tuple(float(c) for c in r) for r in f["/particles/position"][:]]
            vel = [tuple(float(c) for c in r) for r in f["/particles/velocity"][:]]
    else:  # the GPU machine's python has neither h5py nor numpy: the dump, in plain Python
        lines = open(os.path.join(wd, "dump.lammpstrj")).read().split("ITEM: TIMESTEP\n")
        frame = [fr for fr in lines if fr.split("\n", 1)[0].strip() == str(step)][0]
        rows = [[float(v) for v in r.split()[:8]] for r in frame.split("ITEM: ATOMS")[1].split("\n")[1:]
                if r.strip()]
        ids = [int(r[0]) for r in rows]
        pos = [tuple(r[2:5]) for r in rows]
        vel = [tuple(r[5:8]) for r in rows]
    order = sorted(range(len(ids)), key=lambda k: ids[k])
    return [ids[k] for k in order], [pos[k] for k in order], [vel[k] for k in order]


def max_abs_diff(a, b):
    """largest |a - b| over all components of two equally long lists of tuples"""
    return max((abs(u - w) for ra, rb in zip(a, b) for u, w in zip(ra, rb)), default=0.0)


results = {}
# The frozen weight is named (0.4, the CPU's default), so that both backends test the same cuts; the
# backend's own default is checked after.
FW = {"frozen_weight": 0.4}
for name, bal in [("uniform", dict(FW)), ("cost", {"cuts": "cost", **FW}),
                  ("moving", {"cuts": "cost", "every": 5, "threshold": 1.0, **FW})]:
    p, wd = run(name, bal)
    if p.returncode:
        print(p.stdout[-2000:], p.stderr[-2000:])
        sys.exit(f"FAIL: the {name} run failed")
    results[name] = (wd, json.load(open(os.path.join(wd, "summary.json"))), p.stdout)

ids0, x0, v0 = particles(results["uniform"][0], 20)
for name in ("cost", "moving"):
    ids, x, v = particles(results[name][0], 20)
    same = ids == ids0
    check(same, f"{name}: the same {len(ids0)} particle ids at step 20 as uniform cuts")
    if same:
        dx = max_abs_diff(x, x0)
        dv = max_abs_diff(v, v0)
        tol_x, tol_v = (1e-3, 1e-1) if GPU else (1e-8, 1e-6)
        check(dx < tol_x and dv < tol_v, f"{name}: positions within {dx:.2e} rc, velocities within {dv:.2e} of uniform cuts'")

lu = results["uniform"][1]["load_balance"]
lc = results["cost"][1]["load_balance"]
lm = results["moving"][1]["load_balance"]
print(f"weight imbalance: uniform {lu['imbalance_weight']:.3f}, cost {lc['imbalance_weight']:.3f}; "
      f"busy: uniform {lu['imbalance_busy']}, cost {lc['imbalance_busy']}; moving: {lm['rebalances']} rebalancings")
check(lu["cuts"] == "uniform" and lc["cuts"] == "cost", "summary names the cuts")
su = results["uniform"][1]
check(su.get("backend") == BACKEND and su.get("pair_rng") == "philox",
      f"summary names the backend and the pair generator ({su.get('backend')}, {su.get('pair_rng')})")
check(lu["imbalance_weight"] > 1.1, f"uniform cuts are imbalanced on this image ({lu['imbalance_weight']:.3f} > 1.1)")
check(lc["imbalance_weight"] <= 1.05, f"cost cuts: weight imbalance {lc['imbalance_weight']:.3f} <= 1.05")
check(abs(lc["imbalance_weight_uniform_cuts"] - lu["imbalance_weight"]) < 0.05,
      "the summary's uniform-cut imbalance matches the uniform run's start")
if GPU:
    check(lm["rebalances"] == 0 and lm["imbalance_busy"] is None,
          "GPU: no busy time measured, no rebalancing during the run (cuts by weight)")
else:
    check(lm["rebalances"] == 3, f"balance.every 5 with threshold 1: 3 rebalancings in 20 steps, none at the last (got {lm['rebalances']})")
    check(lu["imbalance_busy"] > 0, "CPU: the busy-time imbalance is measured")
    per = lm.get("busy_seconds_run") or []
    since = lm.get("busy_seconds_since_move") or []
    ok = len(per) == 2 and len(since) == 2 and min(per) > 0
    if ok:  # the summary's imbalances are max / mean of the per-rank seconds it lists
        ok = abs(max(per) / (sum(per) / 2) - lm["imbalance_busy_run"]) < 1e-4 and \
            abs(max(since) / (sum(since) / 2) - lm["imbalance_busy"]) < 1e-4 and sum(since) < sum(per)
    check(ok, f"CPU: each rank's busy seconds listed (run {per}, since the last move {since}), "
              "their max / mean = the imbalances reported")
check("cuts placed by cost" in results["cost"][2], "the run says where the cuts went")

# 2b. without balance.frozen_weight: the backend's default (CPU 0.4, GPU 1.0: bench/RESULTS.md)
p, wd = run("cost_default", {"cuts": "cost"}, steps=2)
want = 1.0 if GPU else 0.4
got = json.load(open(os.path.join(wd, "summary.json")))["load_balance"]["frozen_weight"] if not p.returncode else None
check(got == want, f"default frozen weight on the {BACKEND} backend: {got} (expected {want})")
check(f"frozen particle weight {want:g})" in p.stdout, "the run names the weight it used")

# 3. a cost-cut run of 10 steps, restarted from its checkpoint for 10 more: bitwise at step 20
p1, wd1 = run("cost_first", {"cuts": "cost"}, steps=10)
p, wd = run("cost_restart", {"cuts": "cost"}, steps=10,
            extra=["--restart", os.path.join(wd1, "restart.h5")])
if p1.returncode or p.returncode:
    print(p1.stderr[-1000:], p.stdout[-2000:], p.stderr[-2000:])
    check(False, "restart of a cost-cut run from its checkpoint ran")
else:
    a = particles(results["cost"][0], 20)
    b = particles(wd, 20)
    if GPU:
        dx = max_abs_diff(a[1], b[1])
        check(a[0] == b[0] and dx < 1e-3, f"GPU cost cuts: restart from step 10 within {dx:.2e} rc at step 20")
    else:
        check(a == b, "cost cuts: restart from step 10 is bitwise at step 20")
    check("cuts placed by cost" not in p.stdout, "the restart keeps its checkpoint's cuts (no new placement)")

# 4. bad keys
for bad, key in [({"cuts": "sideways"}, "balance.cuts"), ({"every": 10}, "balance.every"),
                 ({"cuts": "cost", "threshold": 0.5}, "balance.threshold"),
                 ({"cuts": "cost", "frozen_weight": -1}, "balance.frozen_weight")]:
    p, wd = run("bad", bad, steps=1)
    check(p.returncode != 0 and key in p.stderr, f"bad {bad} refused naming '{key}'")

if fails:
    sys.exit(f"{len(fails)} check(s) failed")
print("load balancing: consistent trajectories, balanced weights, bitwise restart, bad keys refused")
