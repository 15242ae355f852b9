#!/usr/bin/python3
"""Hard geometries and forcings on 1, 2 and 4 ranks (docs/stability.md).

Cases (images made here, standard mDPD water scene, bounce_back walls, dt 0.01, body force along x):
  strong_forcing   sphere array c = 0.125 (one 6 rc cell) at g = 0.05, 0.5 and 2 (mean pore velocity
                   from ~0.3 to far beyond linear response);
  thin_walls       a stack of slits separated by one-voxel-thick walls (0.5 rc);
  thin_throats     a channel whose middle narrows to a one-voxel-wide throat;
  dead_ends        a through channel with a dead-end branch and an isolated cavity, isolated_pores:
                   fill (fluid in both);
  dense_pack       random spheres at porosity 0.25.
Each case runs --steps steps on every rank count of --ranks. Counted over all runs: particles lost
(the engine's count check stops a run that loses one), penetrations (summary), NaN (thermo and
summary), unexplained stops (a non-zero exit without "run stopped at step" and a cause) and crashes
(killed by a signal). A run the engine stops with a message is reported with it (a clear stop is
allowed, silence is not). Exit 1 when any count is not 0, or when a run that ends normally has T
beyond --t-tol of kT (silent heating; default 0.5, the temperature guard's tolerance: T here is the
thermo's, the mean flow removed, so the non-uniform part of a strong flow counts as heat).

Writes validation/stability/results/hard_cases{,_quick}.{md,json}.
Usage: hard_cases.py [--quick] [--ranks 1,2,4] [--steps N] [--out DIR]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "engine"))
sys.path.insert(0, os.path.join(HERE, "..", "walls"))
import mdval  # noqa: E402
from common import image_scene, write_raw_image  # noqa: E402

VOXEL = 0.5  # rc per voxel


def make_images(work, exe):
    """{case: (image path, box in rc, extra geometry keys)}"""
    out = {}
    p = os.path.join(work, "spheres.h5")
    subprocess.run([exe, "image", "make", "spheres", "--cell", "12", "--c", "0.125", "--cells", "1", "-o", p],
                   check=True, capture_output=True)
    out["spheres"] = (p, [6.0] * 3, {})
    # slits of 5 voxels separated by one-voxel walls along y: 12 x 24 x 8 voxels
    lab = np.zeros((12, 24, 8), np.uint8)
    lab[:, ::6, :] = 1
    out["thin_walls"] = (write_raw_image(os.path.join(work, "thin_walls.raw"), lab), [6.0, 12.0, 4.0], {})
    # a 6 x 6 voxel channel along x narrowing to 1 x 1 voxel over its middle 4 voxels: 16 x 10 x 10
    lab = np.ones((16, 10, 10), np.uint8)
    lab[:, 2:8, 2:8] = 0
    lab[6:10, 2:8, 2:8] = 1
    lab[6:10, 5, 5] = 0
    out["thin_throats"] = (write_raw_image(os.path.join(work, "thin_throats.raw"), lab), [8.0, 5.0, 5.0], {})
    # a through channel (4 x 4 voxels) along x, a dead-end branch along y, an isolated 4^3 cavity
    lab = np.ones((16, 16, 16), np.uint8)
    lab[:, 2:6, 2:6] = 0
    lab[6:10, 6:12, 2:6] = 0
    lab[10:14, 10:14, 10:14] = 0
    out["dead_ends"] = (write_raw_image(os.path.join(work, "dead_ends.raw"), lab), [8.0] * 3,
                        {"isolated_pores": "fill"})
    p = os.path.join(work, "dense.h5")
    subprocess.run([exe, "image", "make", "random-spheres", "--size", "16", "--radius", "3", "--porosity", "0.25",
                    "--seed", "3", "-o", p], check=True, capture_output=True)
    out["dense_pack"] = (p, [8.0] * 3, {})
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--backend", choices=("cpu", "cuda"), default="cpu",
                    help="the engine backend of every run (cuda: all ranks share the visible GPUs)")
    ap.add_argument("--ranks", default="1,2,4")
    ap.add_argument("--steps", type=int, default=None)
    ap.add_argument("--t-tol", type=float, default=0.5,
                    help="a run that ends with |T - kT| > t_tol kT was silently heated (default: the "
                         "temperature guard's own tolerance, docs/scene-format.md)")
    ap.add_argument("--out", default=os.environ.get("MDPORE_VALIDATION_OUT", os.path.join(HERE, "results")))
    args = ap.parse_args()
    tag = ("hard_cases_quick" if args.quick else "hard_cases") + ("_cuda" if args.backend == "cuda" else "")
    work = os.path.join(args.out, tag)
    os.makedirs(work, exist_ok=True)
    steps = args.steps or (1500 if args.quick else 20000)  # > the temperature guard's 1000-step window
    exe = mdval.mdpore_binary()
    images = make_images(work, exe)
    cases = [("strong_forcing g=0.05", "spheres", 0.05), ("strong_forcing g=0.5", "spheres", 0.5),
             ("strong_forcing g=2", "spheres", 2.0), ("thin_walls", "thin_walls", 0.1),
             ("thin_throats", "thin_throats", 0.1), ("dead_ends", "dead_ends", 0.1),
             ("dense_pack", "dense_pack", 0.1)]
    counts = {"runs": 0, "stable": 0, "clear_stops": 0, "lost": 0, "penetrations": 0, "nan": 0,
              "unexplained_stops": 0, "crashes": 0, "heated": 0}
    rows = []
    for name, img, g in cases:
        image, box, extra = images[img]
        for np_ranks in (int(x) for x in args.ranks.split(",")):
            scene = image_scene(name.replace(" ", "_").replace("=", ""), box, image,
                                os.path.join(work, "patches-e0.5-d8-s7.h5"), steps=steps, seed=5, patch_seed=7,
                                g=[g, 0.0, 0.0], thermo_every=max(1, steps // 20), rc_per_voxel=VOXEL)
            scene["geometry"].update(extra)
            wd = os.path.join(work, f"{name.replace(' ', '_').replace('=', '')}_np{np_ranks}")
            os.makedirs(wd, exist_ok=True)
            with open(os.path.join(wd, "scene.yaml"), "w") as f:
                yaml.safe_dump(scene, f, sort_keys=False)
            cmd = [exe, "run", "scene.yaml", "--backend", args.backend]
            if np_ranks > 1:
                cmd = ["mpiexec", "-n", str(np_ranks), "--oversubscribe"] + cmd
            t0 = time.time()
            proc = subprocess.run(cmd, cwd=wd, env=mdval.mpi_env(), capture_output=True, text=True, timeout=1800)
            counts["runs"] += 1
            row = {"case": name, "ranks": np_ranks, "exit": proc.returncode, "seconds": round(time.time() - t0, 2)}
            thermo = os.path.join(wd, "thermo.csv")
            body = [l for l in (open(thermo).read().splitlines() if os.path.exists(thermo) else []) if l and l[0] != "#"]
            nan = any("nan" in l.lower() or "inf" in l.lower() for l in body[1:])
            if proc.returncode == 0:
                s = json.load(open(os.path.join(wd, "summary.json")))
                T = s["thermo"]["T"]["mean"]
                pen = s.get("penetrations", {}).get("samples_with_penetration", 0)
                nan = nan or not math.isfinite(T)
                counts["stable"] += 1
                counts["penetrations"] += pen
                hot = not (abs(T - 1.0) <= args.t_tol)
                counts["heated"] += hot
                row.update(state="ran", T=T, penetrations=pen, particles=s.get("particles"))
                print(f"{name:24s} np {np_ranks}: ran, T = {T:.4f}, penetrations {pen}, {row['seconds']} s", flush=True)
            elif proc.returncode < 0:
                counts["crashes"] += 1
                row.update(state="crash")
                print(f"{name:24s} np {np_ranks}: CRASH (signal {-proc.returncode})", flush=True)
            else:
                stop = [l for l in proc.stderr.splitlines() if "run stopped at step" in l]
                cause = [l.strip() for l in proc.stderr.splitlines() if l.startswith("mdpore") and "run stopped" not in l]
                lost = "lost" in proc.stderr or "count changed" in proc.stderr
                counts["lost"] += lost
                if stop and cause:
                    counts["clear_stops"] += 1
                    row.update(state="stopped", message=cause[0][:300])
                    print(f"{name:24s} np {np_ranks}: stopped: {cause[0][:200]}", flush=True)
                else:
                    counts["unexplained_stops"] += 1
                    row.update(state="unexplained", stderr=proc.stderr[-400:])
                    print(f"{name:24s} np {np_ranks}: UNEXPLAINED exit {proc.returncode}: {proc.stderr.strip()[-300:]}",
                          flush=True)
            counts["nan"] += nan
            rows.append(row)
    bad = {k: counts[k] for k in ("lost", "penetrations", "nan", "unexplained_stops", "crashes", "heated") if counts[k]}
    print("counts: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
    mdval.write_json(os.path.join(args.out, tag + ".json"), {"steps": steps, "counts": counts, "rows": rows})
    with open(os.path.join(args.out, tag + ".md"), "w") as f:
        f.write(f"# Hard cases ({steps} steps, dt 0.01, ranks {args.ranks}, backend {args.backend})\n\n| case | ranks | result | s |\n"
                "|---|---|---|---|\n")
        for r in rows:
            what = (f"ran, T = {r['T']:.4f}, {r['penetrations']} penetrations" if r["state"] == "ran"
                    else r.get("message") or r["state"])
            f.write(f"| {r['case']} | {r['ranks']} | {what} | {r['seconds']} |\n")
        f.write("\ncounts: " + ", ".join(f"{k} {v}" for k, v in counts.items()) + "\n")
    if bad:
        print(f"FAIL: {bad}")
        sys.exit(1)
    print("all counts 0: no particle lost, no penetration, no NaN, no unexplained stop, no crash, no silent heating")


if __name__ == "__main__":
    main()
