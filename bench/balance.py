#!/usr/bin/env python3
"""Load balance on heterogeneous rock: one image, half dense solid and half open
pores along x, run on NP CPU ranks cut along x, once with uniform cuts and once with cuts placed by
cost (balance.cuts: cost), optionally a third run whose cuts move during the run by measured cost
(balance.every). Prints per run: particle-steps/s (all and fluid), the imbalance factors the summary
reports (max / mean over the ranks of busy time and of particle weight), the rebalancings, and the
ratio of the two runs' throughputs measured in the same call.

The image: NX x NY x NZ voxels at 0.5 rc per voxel; x < NX/2 a dense random-sphere pack (porosity
about 0.3, with a straight 2-voxel channel along x so that the flow percolates), x >= NX/2 open
(porosity about 0.85). mDPD water (A = -40, B = 25, rd = 0.75), frozen wall, bounce_back, body
force 0.02 along x.

With --gpu-compare LAYOUTS (e.g. 16x1,4x4,2x8: MPI ranks x OpenMP threads), the same scene with cost
cuts on all those CPU layouts and once on the GPU (CUDA backend, one rank), in the same call; prints
the GPU / fastest-CPU throughput ratio (users compare with a CPU cluster).

usage: /usr/bin/python3 bench/balance.py [--np 2] [--nx 96] [--ny 32] [--nz 32] [--steps 400]
           [--threads 1] [--dynamic] [--check] [--workdir DIR] [--frozen-weight W]
           [--gpu-compare LAYOUTS] [--backend cpu|cuda] [--one-rank] [--image RAW] [--make-image-only]
--backend cuda: the runs on NP GPUs (one per rank), with --one-rank the same image on one
GPU first (strong scaling). --image: a stored image (the GPU machine has no numpy).
--check (the ctest variant): fails unless cost cuts bring the weight imbalance to <= 1.05 and below
the uniform cuts', the particle count is conserved, and with --dynamic a deliberately wrong
frozen weight is corrected by at least one rebalancing that lowers the busy-time imbalance.
"""
import argparse
import json
import os
import subprocess
import sys

try:  # numpy builds the images; the GPU machine's python has none (the test then reads a stored one)
    import numpy as np
except ImportError:
    np = None

BIND = "none"
ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def spheres(shape, porosity, radius, rng):
    """Random overlapping spheres (label 1) in a periodic block until the pore fraction <= porosity."""
    lab = np.zeros(shape, dtype=np.uint8)
    r = int(np.ceil(radius))
    off = np.arange(-r, r + 1)
    d2 = off[:, None, None] ** 2 + off[None, :, None] ** 2 + off[None, None, :] ** 2
    ball = d2 <= radius * radius
    pore = lab.size
    while pore > porosity * lab.size:
        c = (rng.uniform(0, 1, 3) * np.array(shape)).astype(int)
        idx = np.ix_(*[(c[a] + off) % shape[a] for a in range(3)])  # periodic stamp
        pore -= int(np.count_nonzero(ball & (lab[idx] == 0)))
        lab[idx] |= ball.astype(np.uint8)
    return lab


def make_image(path, nx, ny, nz, seed, homogeneous=False):
    rng = np.random.default_rng(seed)
    half = nx // 2
    dense = spheres((half, ny, nz), 0.85 if homogeneous else 0.30, 3.0 if homogeneous else 4.0, rng)
    dense[:, ny // 2 - 1:ny // 2 + 1, nz // 2 - 1:nz // 2 + 1] = 0  # a channel: the flow percolates
    open_ = spheres((nx - half, ny, nz), 0.85, 3.0, rng)
    lab = np.concatenate([dense, open_], axis=0)
    # raw + sidecar (docs/images.md); numpy only, so that it also runs on the GPU machine
    with open(path, "wb") as f:
        f.write(np.ascontiguousarray(lab.transpose(2, 1, 0)).tobytes())
    with open(path + ".hdr", "w") as f:
        f.write(f"dims: {nx} {ny} {nz}\ntype: uint8\naxis_order: xyz\nlabels: pore=0;inorganic=1\n")
    return float((lab[:half] == 0).mean()), float((lab[half:] == 0).mean())


def scene(image, box, steps, np_ranks, balance):
    s = {
        "name": "balance_bench",
        "box": {"lo": [0, 0, 0], "hi": box, "periodic": [True, True, True], "procs": [np_ranks, 1, 1]},
        "species": [{"name": "liquid"}, {"name": "wall", "frozen": True}],
        "pairs": {"default": {"A": -40, "B": 25, "gamma": 4.5, "rc": 1.0, "rd": 0.75}},
        "effects": {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {},
                    "body_force": {"liquid": [0.02, 0, 0]}, "bounce_back": {}},
        "geometry": {"image": image, "labels": "pore=0,inorganic=1", "rc_per_voxel": 0.5,
                     "flow_axis": "x", "species": {"fluid": "liquid", "inorganic": "wall"},
                     "isolated_pores": "fill"},
        "run": {"dt": 0.01, "steps": steps, "seed": 7},
        "output": {"thermo": {"every": 100, "file": "thermo.csv"}, "summary": "summary.json",
                   "progress": False},
    }
    if balance:
        s["balance"] = balance
    return s


def run(mdpore, wd, sc, np_ranks, threads, backend="cpu"):
    os.makedirs(wd, exist_ok=True)
    with open(os.path.join(wd, "scene.yaml"), "w") as f:
        json.dump(sc, f, indent=1)  # JSON is YAML: no PyYAML needed
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
    cmd = ["mpiexec", "-n", str(np_ranks), "--oversubscribe", "--bind-to", BIND, mdpore, "run",
           "--backend", backend, "scene.yaml"]
    p = subprocess.run(cmd, cwd=wd, env=env, capture_output=True, text=True)
    log = p.stdout + p.stderr
    open(os.path.join(wd, "run.log"), "w").write(log)
    if p.returncode:
        sys.exit(f"balance bench: mdpore run failed in {wd}:\n{log[-3000:]}")
    summ = json.load(open(os.path.join(wd, "summary.json")))
    return summ, log


def gpu_compare(a, mdpore, wd, img, box, cost):
    """The scene on each CPU layout (cost cuts) and on one GPU; the ratio GPU / fastest CPU."""
    best = None
    for lay in a.gpu_compare.split(","):
        nr, nt = (int(v) for v in lay.split("x"))
        summ, _ = run(mdpore, os.path.join(wd, f"cpu_{nr}x{nt}"), scene(img, box, a.steps, nr, cost), nr, nt)
        t, lb = summ["timing"], summ.get("load_balance", {})
        mps = t["particle_steps_per_second"]
        print(f"CPU {nr:2d} ranks x {nt:2d} threads: {mps / 1e6:8.3f} M particle-steps/s "
              f"({t['particles']} particles, loop {t['loop_seconds']:.2f} s; busy imbalance "
              f"{lb.get('imbalance_busy')})")
        if best is None or mps > best[1]:
            best = (lay, mps)
    summ, _ = run(mdpore, os.path.join(wd, "gpu"), scene(img, box, a.steps, 1, None), 1, 1, "cuda")
    g = summ["timing"]["particle_steps_per_second"]
    print(f"GPU (cuda, 1 rank):          {g / 1e6:8.3f} M particle-steps/s")
    print(f"GPU / fastest CPU layout ({best[0]}): {g / best[1]:.1f}x (same call)")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--nx", type=int, default=96)
    ap.add_argument("--ny", type=int, default=32)
    ap.add_argument("--nz", type=int, default=32)
    ap.add_argument("--steps", type=int, default=400)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--frozen-weight", type=float, default=None)
    ap.add_argument("--dynamic", action="store_true")
    ap.add_argument("--moving-every", type=int, default=0,
                    help="also a run whose cost cuts (default frozen weight) move by measured cost every N "
                         "steps when the busy-time imbalance exceeds 1.05")
    ap.add_argument("--runs", default=None,
                    help="comma-separated subset of the runs to make (uniform, cost, cost+moving, measured)")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--workdir", default="balance-bench")
    ap.add_argument("--gpu-compare", default=None)
    ap.add_argument("--homogeneous", action="store_true",
                    help="both halves open (porosity 0.85): the busy-time imbalance of uniform cuts is then "
                         "the machine's timing noise floor")
    ap.add_argument("--bind", default="none", help="mpiexec --bind-to (none, core)")
    ap.add_argument("--image", default=None,
                    help="a stored image of this kind (raw + .hdr, NX x NY x NZ) instead of making one "
                         "(machines without numpy: make it elsewhere with --make-image-only)")
    ap.add_argument("--make-image-only", action="store_true", help="write WORKDIR/hetero.raw and stop")
    ap.add_argument("--backend", default="cpu", help="cpu or cuda (one GPU per rank)")
    ap.add_argument("--one-rank", action="store_true",
                    help="also run on one rank (no balancing): the strong-scaling speed-up of each cut")
    a = ap.parse_args()
    mdpore = os.environ.get("MDPORE") or os.path.join(ROOT, "build", "bin", "mdpore")
    os.makedirs(a.workdir, exist_ok=True)
    wd = os.path.abspath(a.workdir)
    img = os.path.join(wd, "hetero.raw")
    if a.image:
        img = os.path.abspath(a.image)
        p_dense = p_open = float("nan")
    else:
        p_dense, p_open = make_image(img, a.nx, a.ny, a.nz, 11, a.homogeneous)
    if a.make_image_only:
        print(f"image {img}: porosity {p_dense:.3f} | {p_open:.3f}")
        return 0
    global BIND
    BIND = a.bind
    box = [a.nx * 0.5, a.ny * 0.5, a.nz * 0.5]
    print(f"image {a.nx}x{a.ny}x{a.nz} voxels (box {box[0]} x {box[1]} x {box[2]} rc): porosity "
          f"{p_dense:.3f} (x < half) | {p_open:.3f} (x >= half); {a.np} CPU ranks along x, "
          f"{a.threads} OpenMP thread(s) each, {a.steps} steps")
    cost = {"cuts": "cost"}
    if a.frozen_weight is not None:
        cost["frozen_weight"] = a.frozen_weight
    if a.gpu_compare:
        return gpu_compare(a, mdpore, wd, img, box, cost)
    runs = [("uniform", None), ("cost", cost)]
    if a.dynamic:
        runs.append(("cost+moving", {"cuts": "cost", "frozen_weight": 2.0,
                                     "every": max(a.steps // 8, 10), "threshold": 1.05}))
    if a.moving_every > 0:
        runs.append(("measured", {"cuts": "cost", "every": a.moving_every, "threshold": 1.05}))
    if a.runs:
        keep = a.runs.split(",")
        runs = [r for r in runs if r[0] in keep]
    res = {}
    one = None
    if a.one_rank:
        summ, _ = run(mdpore, os.path.join(wd, "one_rank"), scene(img, box, a.steps, 1, None), 1, a.threads,
                      a.backend)
        one = summ["timing"]["particle_steps_per_second"]
        print(f"one rank     {one / 1e6:8.3f} M particle-steps/s (all {summ['timing']['particles']} particles, "
              f"backend {a.backend})")
    for name, bal in runs:
        summ, log = run(mdpore, os.path.join(wd, name.replace("+", "_")), scene(img, box, a.steps, a.np, bal),
                        a.np, a.threads, a.backend)
        lb, t = summ["load_balance"], summ["timing"]
        res[name] = (lb, t)
        busy = lb["imbalance_busy"]
        print(f"{name:12s} {t['particle_steps_per_second'] / 1e6:8.3f} M particle-steps/s "
              f"(all {t['particles']} particles), loop {t['loop_seconds']:.2f} s; imbalance busy "
              f"{busy if busy is None else f'{busy:.3f}'}, weight {lb['imbalance_weight']:.3f}; "
              f"rebalances {lb['rebalances']}; busy fraction {lb.get('busy_fraction') or 0:.2f}")
        if one:
            sp = t["particle_steps_per_second"] / one
            print(f"    speed-up over one rank {sp:.3f}, strong-scaling efficiency {sp / a.np:.3f}")
        for line in log.splitlines():
            if "load balancing" in line or "cuts moved" in line:
                print("    " + line.strip())
        for key in ("busy_seconds_since_move", "busy_seconds_run"):
            per = lb.get(key)
            if per:  # which ranks are slow (rank order = slab order along x)
                mean = sum(per) / len(per)
                print(f"    {key} / mean: " + " ".join(f"{b / mean:.3f}" for b in per))
    if "uniform" not in res or "cost" not in res:
        return 0
    u, c = res["uniform"][1], res["cost"][1]
    ratio = c["particle_steps_per_second"] / u["particle_steps_per_second"]
    print(f"throughput cost / uniform cuts: {ratio:.3f} (same call)")
    if not a.check:
        return 0
    bad = []
    lu, lc = res["uniform"][0], res["cost"][0]
    if not lc["imbalance_weight"] <= 1.05:
        bad.append(f"cost cuts: weight imbalance {lc['imbalance_weight']:.3f} > 1.05")
    if not lc["imbalance_weight"] < lu["imbalance_weight"]:
        bad.append("cost cuts did not lower the weight imbalance of uniform cuts")
    if u["particles"] != c["particles"]:
        bad.append("particle counts differ between the runs")
    if a.dynamic:
        ld = res["cost+moving"][0]
        if ld["rebalances"] < 1:
            bad.append("the wrong frozen weight (2.0) was never corrected by a rebalancing")
    for b in bad:
        print("FAIL: " + b)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
