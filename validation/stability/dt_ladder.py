#!/usr/bin/python3
"""Hard case: a time-step ladder up to and past the stable limit on a porous image.

A simple-cubic sphere array (c = 0.125; --quick: one 6 rc cell, 12^3 voxels of 0.5 rc; full: 2^3
cells) with the standard mDPD water scene, bounce_back walls and a body force g = 0.05 along x, run
for the same simulated time (--time tau) at each dt of the ladder, each run on --np ranks. A run is
"stable" when it ends with exit 0; then it must have no penetration, a finite temperature within
--t-tol of kT and its particle count. A run is "unstable" when the engine stops it; then its stderr
must name the cause and the step ("run stopped at step N") and what to try (a dt), and the run must
leave no NaN in its outputs. Anything else (a crash, a silent NaN, an unstable run that ends with
exit 0 and a wrong number) fails.

Reports the largest stable dt and the smallest unstable one, the stop message of each unstable run,
and T of each stable one; writes validation/stability/results/dt_ladder{,_quick}.{md,json}.
Exit 1 when a check fails, or when the ladder has no unstable rung (it must go past the limit).

Usage: dt_ladder.py [--quick] [--np N] [--ladder 0.005,0.01,...] [--time TAU] [--out DIR]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "engine"))
sys.path.insert(0, os.path.join(HERE, "..", "walls"))
import mdval  # noqa: E402
from common import image_scene  # noqa: E402

import yaml  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--backend", choices=("cpu", "cuda"), default="cpu",
                    help="the engine backend of every run (cuda: all ranks share the visible GPUs)")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--ladder", default="0.005,0.01,0.02,0.03,0.04,0.06")
    ap.add_argument("--time", type=float, default=None, help="simulated time per run (tau)")
    ap.add_argument("--t-tol", type=float, default=0.1, help="stable runs: |T - kT| <= t_tol kT")
    ap.add_argument("--out", default=os.environ.get("MDPORE_VALIDATION_OUT", os.path.join(HERE, "results")))
    args = ap.parse_args()
    tag = ("dt_ladder_quick" if args.quick else "dt_ladder") + ("_cuda" if args.backend == "cuda" else "")
    work = os.path.join(args.out, tag)
    os.makedirs(work, exist_ok=True)
    sim_time = args.time or (10.0 if args.quick else 50.0)
    cells = 1 if args.quick else 2
    exe = mdval.mdpore_binary()
    image = os.path.join(work, "spheres.h5")
    p = subprocess.run([exe, "image", "make", "spheres", "--cell", "12", "--c", "0.125", "--cells", str(cells),
                        "-o", image], capture_output=True, text=True)
    if p.returncode:
        sys.exit(p.stderr)
    box = [6.0 * cells] * 3
    patches = os.path.join(work, "patches-e0.5-d8-s7.h5")
    failures, rows = [], []

    def check(cond, what):
        print(("ok   " if cond else "FAIL ") + what, flush=True)
        if not cond:
            failures.append(what)

    for dt in (float(x) for x in args.ladder.split(",")):
        steps = max(10, int(round(sim_time / dt)))
        scene = image_scene(f"dt_{dt:g}", box, image, patches, steps=steps, seed=11, patch_seed=7,
                            g=[0.05, 0.0, 0.0], thermo_every=max(1, steps // 50))
        scene["run"]["dt"] = dt
        wd = os.path.join(work, f"dt_{dt:g}")
        os.makedirs(wd, exist_ok=True)
        with open(os.path.join(wd, "scene.yaml"), "w") as f:
            yaml.safe_dump(scene, f, sort_keys=False)
        cmd = [exe, "run", "scene.yaml", "--backend", args.backend]
        if args.np > 1:
            cmd = ["mpiexec", "-n", str(args.np), "--oversubscribe"] + cmd
        t0 = time.time()
        proc = subprocess.run(cmd, cwd=wd, env=mdval.mpi_env(), capture_output=True, text=True, timeout=1800)
        wall = time.time() - t0
        err = proc.stderr
        row = {"dt": dt, "steps": steps, "exit": proc.returncode, "seconds": round(wall, 2)}
        thermo = os.path.join(wd, "thermo.csv")
        text = open(thermo).read() if os.path.exists(thermo) else ""
        nan_in_outputs = "nan" in text.lower().replace("nan,", "").split("\n", 3)[-1] if text else False
        if proc.returncode == 0:
            s = json.load(open(os.path.join(wd, "summary.json")))
            T = s["thermo"]["T"]["mean"]
            pen = s.get("penetrations", {}).get("samples_with_penetration", 0)
            row.update(state="stable", T=T, penetrations=pen, particles=s.get("particles"))
            check(math.isfinite(T) and abs(T - 1.0) <= args.t_tol and pen == 0 and not nan_in_outputs,
                  f"dt {dt:g}: stable, T = {T:.4f} (within {args.t_tol:g} of kT), {pen} penetrations, no NaN")
        else:
            stop = [l for l in err.splitlines() if "run stopped at step" in l]
            cause = [l.strip() for l in err.splitlines() if l.startswith("mdpore") and "run stopped" not in l
                     and ("step" in l or "dt" in l)]
            row.update(state="unstable", stop=stop[0] if stop else None, cause=cause[:2])
            crashed = proc.returncode < 0 or proc.returncode > 2 and not stop
            check(bool(stop) and bool(cause) and "dt" in err and not crashed and not nan_in_outputs,
                  f"dt {dt:g}: stopped with a cause, the step and a dt to try (exit {proc.returncode}): "
                  f"{(cause[0] if cause else err.strip()[-200:])[:240]}")
        rows.append(row)
    stable = [r["dt"] for r in rows if r["state"] == "stable"]
    unstable = [r["dt"] for r in rows if r["state"] == "unstable"]
    check(bool(unstable), "the ladder goes past the stable limit (at least one unstable rung)")
    if stable and unstable and max(stable) > min(unstable):
        print(f"finding: dt {max(stable):g} ran stable above the unstable dt {min(unstable):g}")
    limit = {"largest_stable": max(stable) if stable else None, "smallest_unstable": min(unstable) if unstable else None}
    print(f"stable limit: largest stable dt {limit['largest_stable']}, smallest unstable {limit['smallest_unstable']}")
    res = {"image": f"sphere array c = 0.125, {cells}^3 cells of 6 rc (12^3 voxels of 0.5 rc each)",
           "g": 0.05, "simulated_time_tau": sim_time, "np": args.np, "rows": rows, "limit": limit,
           "failures": failures}
    mdval.write_json(os.path.join(args.out, tag + ".json"), res)
    with open(os.path.join(args.out, tag + ".md"), "w") as f:
        f.write(f"# dt ladder on a porous image ({res['image']}, backend {args.backend}, g = 0.05, {sim_time:g} tau per run, "
                f"{args.np} ranks)\n\n| dt | steps | state | T or stop | seconds |\n|---|---|---|---|---|\n")
        for r in rows:
            what = f"T = {r['T']:.4f}, {r['penetrations']} penetrations" if r["state"] == "stable" else \
                (r["cause"][0] if r.get("cause") else "") + "; " + (r.get("stop") or "")
            f.write(f"| {r['dt']:g} | {r['steps']} | {r['state']} | {what} | {r['seconds']} |\n")
        f.write(f"\nlargest stable dt {limit['largest_stable']}, smallest unstable {limit['smallest_unstable']}; "
                f"failures: {failures or 'none'}\n")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
