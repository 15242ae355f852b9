#!/usr/bin/python3
"""CPU throughput of the engine: bulk mDPD fluid (A = -40, B = 25, rd = 0.75, gamma = 4.5, rho = 6.2).

Prints particle-steps per second (MPS = millions of them) of the step loop for each rank count and
generator of the pair random numbers (dpd_thermostat's rng), and the ratio to the first row measured in
the same invocation. Not a test: run by hand (bench/README.md).
  bench/cpu_bulk.py [--L 12] [--steps 500] [--ranks 1,2] [--threads 1] [--rng philox,fast]
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "validation", "engine"))
import mdval  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--L", type=float, default=12.0)
    ap.add_argument("--steps", type=int, default=500)
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--rng", default="philox", help="comma-separated generators: philox, philox2x32, fast")
    ap.add_argument("--out", default=os.path.join(mdval.ROOT, "out", "bench"))
    args = ap.parse_args()
    os.environ["OMP_NUM_THREADS"] = str(args.threads)
    box = [args.L] * 3
    rows = []
    for rng in args.rng.split(","):
        effects = {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {"rng": rng}}
        for r in (int(x) for x in args.ranks.split(",")):
            scene = mdval.mdpd_scene("bench_bulk", box, [mdval.fill_box(box, 6.2)], steps=args.steps,
                                     thermo_every=args.steps, effects=effects)
            wd = os.path.join(args.out, f"bulk_np{r}_{rng}")
            mdval.run(scene, wd, r)
            with open(os.path.join(wd, "summary.json")) as f:
                timing = json.load(f)["timing"]
            rows.append((rng, r, timing["particles"], timing["particle_steps_per_second"]))
    base = rows[0][3]
    print(f"{'rng':>10} {'ranks':>5} {'threads':>7} {'particles':>9} {'MPS':>8} {'ratio':>6} {'MPS/core':>8}")
    for rng, r, n, pps in rows:
        print(f"{rng:>10} {r:>5} {args.threads:>7} {n:>9} {pps / 1e6:>8.3f} {pps / base:>6.2f} "
              f"{pps / 1e6 / (r * args.threads):>8.3f}")


if __name__ == "__main__":
    main()
