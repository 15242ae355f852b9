#!/usr/bin/python3
"""Validation of `mdpore couple` (docs/coupling.md).

(a) Layered images of two porous textures: simple-cubic sphere arrays (one 6 rc cell, 12^3 voxels of
    0.5 rc) at solid fractions c1 and c2, stacked along x (in series with the flow) and along y (in
    parallel). The loop's k_eff against the harmonic (series) and arithmetic (parallel) means of the
    blocks' own campaign permeabilities.
(c) The same layered images as a whole: a direct `mdpore permeability` campaign on the whole image
    and `mdpore foam` (continuum Stokes flow on the same voxels), against the loop's k_eff.
(b) A block whose law is non-Darcy by construction: the sphere array driven far beyond its
    calibrated range (mean pore velocity ~10x the ladder's top, Reynolds number of order 10), with
    `law: chosen`: pass 1 uses the law fitted on the linear-response ladder, the continuum gradient
    lies above the range, pass 2 adds a run there and refits; the answer of pass 2 should differ from
    pass 1 by more than its error, and the loop should converge.

Writes validation/coupling/results/{couple_validation.md,couple_validation.json,couple_validation.png}.
Exit 1 when a check fails: (a) k_eff equals the mean of the blocks within 1e-6 (the two-point scheme
is exact for layers), (c) the loop and the direct campaign agree within 3 combined standard errors
or 15% (cutting a sample into periodic blocks changes the flow at the block faces; say how much),
(b) the loop converges. Whether (b)'s second pass changes the answer is reported, not asserted: it
depends on whether inertia is resolved at that forcing.

Usage: validate_couple.py [--np N] [--max-steps S] [--target-error E] [--out DIR] [--skip-b]
                          [--launcher mpiexec|slurm]
With --launcher slurm nothing runs here: the loops use `launcher: slurm` and the direct campaigns
--emit-scenes, and the script writes OUT/pending_commands.txt (one run per line, the campaigns' own
command lines) and exits 3 while runs are pending; run those lines anywhere (a Slurm array, another
machine with the same paths), then call the script again: it collects what finished and goes on.
"""
import argparse
import json
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
MDPORE = os.environ.get("MDPORE", os.path.join(ROOT, "build", "bin", "mdpore"))


def run(args, cwd, log=None):
    t0 = time.time()
    p = subprocess.run([MDPORE, *args], cwd=cwd, capture_output=True, text=True)
    if log:
        with open(os.path.join(cwd, log), "w") as f:
            f.write(p.stdout + "\n" + p.stderr)
    return p, time.time() - t0


def couple_config(path, image, blocks, axis, opts, extra=""):
    with open(path, "w") as f:
        f.write(f"""launcher: {opts.launcher}
image: {image}
blocks: {blocks}
axis: {axis}
campaign: {{np: {opts.np}, max_steps: {opts.max_steps}, target_error: {opts.target_error},
           mpiexec: "mpiexec --oversubscribe"}}
{extra}""")
    return path


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--max-steps", type=int, default=20000)
    ap.add_argument("--target-error", type=float, default=0.03)
    ap.add_argument("--c", default="0.125,0.3", help="solid fractions of the two textures")
    ap.add_argument("--out", default=os.path.join(HERE, "work"))
    ap.add_argument("--skip-b", action="store_true")
    ap.add_argument("--launcher", choices=["mpiexec", "slurm"], default="mpiexec")
    opts = ap.parse_args()
    os.makedirs(opts.out, exist_ok=True)
    res_dir = os.path.join(HERE, "results")
    os.makedirs(res_dir, exist_ok=True)
    out = opts.out
    c1, c2 = (float(x) for x in opts.c.split(","))
    failures, results = [], {"c": [c1, c2], "np": opts.np, "max_steps": opts.max_steps,
                             "target_error": opts.target_error}
    pending = []  # command lines of unfinished runs (--launcher slurm)

    def unfinished(commands_file):
        out = []
        if os.path.exists(commands_file):
            for line in open(commands_file):
                d = line.split("'")[1] if line.startswith("cd '") else line.split()[1]
                if not os.path.exists(os.path.join(d, "summary.json")):
                    out.append(line.rstrip("\n"))
        return out

    def couple(case, cfg):
        p, t = run(["couple", cfg], out, f"{case}.couple.log")
        if p.returncode == 3:
            s = json.load(open(os.path.join(out, f"{case}.couple", "couple.json")))
            n = s["passes"] + 1
            pending.extend(unfinished(os.path.join(out, f"{case}.couple", f"pass_{n}", "commands.txt")))
            return None, p, t
        return json.load(open(os.path.join(out, f"{case}.couple", "couple.json"))), p, t

    def direct(case, image):
        # the voxel edge the couple config gives its blocks (0.5 rc), as mdpore couple passes it
        args = ["permeability", image, "--axis", "x", "--rc-per-voxel", "0.5", "--force", "--np", str(opts.np),
                "--max-steps", str(opts.max_steps),
                "--target-error", str(opts.target_error), "--mpiexec", "mpiexec --oversubscribe"]
        if opts.launcher == "slurm":
            p, t = run(args + ["--emit-scenes", f"{case}.direct"], out, f"{case}.direct.log")
            left = unfinished(os.path.join(out, f"{case}.direct", "commands.txt"))
            if left:
                pending.extend(left)
                return None, t
            p, t = run(["permeability", "--collect", f"{case}.direct"], out, f"{case}.direct.log")
        else:
            p, t = run(args + ["--workdir", f"{case}.direct"], out, f"{case}.direct.log")
        return json.load(open(os.path.join(out, f"{case}.direct", "permeability.json")))["axes"]["x"], t

    def check(cond, what):
        print(("ok   " if cond else "FAIL ") + what, flush=True)
        if not cond:
            failures.append(what)

    for name, c in (("t1.h5", c1), ("t2.h5", c2)):
        p, _ = run(["image", "make", "spheres", "--cell", "12", "--c", str(c), "--cells", "1", "-o", name], out)
        if p.returncode:
            sys.exit(p.stderr)
    # continuum limit of each texture alone (foam on the block images), for the decomposition error
    foam_blocks = []
    for name in ("t1.h5", "t2.h5"):
        p, _ = run(["foam", name, "--axis", "x"], out, f"foam_{name}.log")
        foam_blocks.append(json.loads(p.stdout)["permeability_voxel2"] * 0.5 ** 2 if p.returncode == 0 else None)
    results["foam_blocks"] = foam_blocks
    for name, axis in (("series.h5", "x"), ("parallel.h5", "y")):
        p, _ = run(["image", "stack", "t1.h5", "t2.h5", "--axis", axis, "-o", name], out)
        if p.returncode:
            sys.exit(p.stderr)

    # (a) + (c)
    for case, image, blocks, mean in (("series", "series.h5", "[2, 1, 1]", "harmonic"),
                                      ("parallel", "parallel.h5", "[1, 2, 1]", "arithmetic")):
        cfg = couple_config(os.path.join(out, f"{case}.yaml"), image, blocks, "x", opts)
        s, p, t = couple(case, cfg)
        d, td = direct(case, image)
        if s is None or d is None:
            continue
        ks = [b["k_darcy_rc2"] for b in s["blocks_final"]]
        ke = [b["k_darcy_rc2_err"] for b in s["blocks_final"]]
        m = 2 / (1 / ks[0] + 1 / ks[1]) if mean == "harmonic" else 0.5 * (ks[0] + ks[1])
        k, kerr = s["effective_permeability"]["k_rc2"], s["effective_permeability"]["k_rc2_err"]
        r = {"blocks_k": ks, "blocks_k_err": ke, "mean": mean, "mean_k": m, "k_loop": k, "k_loop_err": kerr,
             "passes": s["passes"], "converged": s["converged"], "seconds": t}
        check(p.returncode == 0 and s["converged"], f"(a) {case}: the loop converged (exit {p.returncode})")
        check(abs(k / m - 1) < 1e-6, f"(a) {case}: k_eff {k:.5g} = {mean} mean of the blocks {m:.5g}")
        # (c) direct campaign on the whole image
        r.update({"k_direct": d["k_rc2"], "k_direct_err": d["k_rc2_err"], "direct_seconds": td})
        sig = (kerr ** 2 + d["k_rc2_err"] ** 2) ** 0.5
        ratio = k / d["k_rc2"]
        check(abs(k - d["k_rc2"]) <= max(3 * sig, 0.15 * d["k_rc2"]),
              f"(c) {case}: loop {k:.4g} +- {kerr:.2g} vs direct campaign {d['k_rc2']:.4g} +- {d['k_rc2_err']:.2g} "
              f"(ratio {ratio:.3f})")
        p, t = run(["foam", image, "--axis", "x"], out, f"{case}.foam.log")
        if p.returncode == 0:
            f = json.loads(p.stdout)
            kf = f["permeability_voxel2"] * 0.5 ** 2
            r.update({"k_foam": kf, "foam_seconds": t})
            if None not in foam_blocks:
                fb = foam_blocks
                fm = 2 / (1 / fb[0] + 1 / fb[1]) if mean == "harmonic" else 0.5 * (fb[0] + fb[1])
                r.update({"foam_blocks_mean": fm})
                print(f"(c) {case}: foam {mean} mean of the blocks {fm:.4g} vs foam whole {kf:.4g}: the continuum's "
                      f"decomposition error {fm / kf:.3f}; mDPD loop / direct {k / d['k_rc2']:.3f}")
            print(f"(c) {case}: foam on the whole image {kf:.4g} rc^2; loop / foam {k / kf:.3f}; "
                  f"direct / foam {d['k_rc2'] / kf:.3f}")
        else:
            print(f"(c) {case}: mdpore foam not run: {p.stderr.strip()[-200:]}")
        results[case] = r

    # (b) one block driven far above its calibrated range, law: chosen
    if not opts.skip_b:
        # the ladder of block t1 (the same image as the series' first block): G = n g of its manifest
        man = os.path.join(out, "series.couple", "blocks", "b0_0_0", "campaign", "campaign.txt")
        dens = [float(l.split()[1]) for l in open(man) if l.startswith("fluid_density:")][0]
        ladder_top = max(dens * float(l.split()[2]) for l in open(man) if l.startswith("run: "))
        G = 10 * ladder_top
        cfg = couple_config(os.path.join(out, "nondarcy.yaml"), "t1.h5", "[1, 1, 1]", "x", opts,
                            f"law: chosen\ngradient: {G:.4g}\nloop: {{max_passes: 4}}\n")
        s, p, t = couple("nondarcy", cfg)
    if not opts.skip_b and s is not None:
        h = s["history"]
        r = {"gradient": G, "ladder_top": ladder_top, "history": h, "converged": s["converged"],
             "chosen": s["blocks_final"][0]["chosen_law"] if s["blocks_final"] else None, "seconds": t}
        check(s["converged"], f"(b) the loop converged after {s['passes']} passes (exit {p.returncode})")
        if len(h) >= 2:
            d = abs(h[1]["k_rc2"] - h[0]["k_rc2"])
            e = (h[1]["k_rc2_err"] ** 2 + h[0]["k_rc2_err"] ** 2) ** 0.5
            r["pass2_change_sigma"] = d / e if e else None
            print(f"(b) pass 1 k_eff {h[0]['k_rc2']:.4g} +- {h[0]['k_rc2_err']:.2g}, pass 2 {h[1]['k_rc2']:.4g} +- "
                  f"{h[1]['k_rc2_err']:.2g}: change {d / e if e else float('nan'):.2f} sigma; chosen law {r['chosen']}")
        results["nondarcy"] = r

    if pending:
        with open(os.path.join(out, "pending_commands.txt"), "w") as f:
            f.write("\n".join(pending) + "\n")
        print(f"{len(pending)} runs pending: {os.path.join(out, 'pending_commands.txt')} (run them, then call again)")
        sys.exit(3)
    results["failures"] = failures
    json.dump(results, open(os.path.join(res_dir, "couple_validation.json"), "w"), indent=1)
    with open(os.path.join(res_dir, "couple_validation.md"), "w") as f:
        f.write("# mdpore couple validation (validation/coupling/validate_couple.py)\n\n")
        f.write(f"textures: sphere arrays c = {c1}, {c2} (12^3 voxels of 0.5 rc each); np {opts.np}, "
                f"max_steps {opts.max_steps}, target_error {opts.target_error}\n\n")
        f.write("| case | blocks k (rc^2) | mean | loop k_eff | direct campaign | foam (whole image) | loop/direct "
                "| foam: blocks' mean / whole |\n")
        f.write("|---|---|---|---|---|---|---|---|\n")
        for case in ("series", "parallel"):
            r = results.get(case)
            if not r:
                continue
            f.write(f"| {case} | {r['blocks_k'][0]:.4g} +- {r['blocks_k_err'][0]:.2g}, {r['blocks_k'][1]:.4g} +- "
                    f"{r['blocks_k_err'][1]:.2g} | {r['mean']} {r['mean_k']:.4g} | {r['k_loop']:.4g} +- "
                    f"{r['k_loop_err']:.2g} | {r['k_direct']:.4g} +- {r['k_direct_err']:.2g} | "
                    f"{r.get('k_foam', float('nan')):.4g} | {r['k_loop'] / r['k_direct']:.3f} | "
                    f"{r.get('foam_blocks_mean', float('nan')) / r.get('k_foam', float('nan')):.3f} |\n")
        if "nondarcy" in results:
            r = results["nondarcy"]
            f.write(f"\n(b) one block at G = {r['gradient']:.4g} (10x the ladder's top {r['ladder_top']:.4g}), "
                    f"law: chosen, chosen law at the end: {r['chosen']}\n\n| pass | k_eff | err | new runs |\n|---|---|---|---|\n")
            for hh in r["history"]:
                f.write(f"| {hh['pass']} | {hh['k_rc2']:.4g} | {hh['k_rc2_err']:.2g} | {hh['new_runs']} |\n")
        f.write(f"\nfailures: {failures or 'none'}\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        xs = 0
        for case in ("series", "parallel"):
            r = results.get(case)
            if not r:
                continue
            vals = [("blocks' mean", r["mean_k"], 0), ("loop", r["k_loop"], r["k_loop_err"]),
                    ("direct mDPD", r["k_direct"], r["k_direct_err"])]
            if "k_foam" in r:
                vals.append(("foam", r["k_foam"], 0))
            for i, (lab, v, e) in enumerate(vals):
                ax.bar(xs + i * 0.2, v, 0.2, yerr=e, color=f"C{i}", label=lab if case == "series" else None)
            ax.text(xs + 0.3, max(v for _, v, _ in vals) * 1.05, case, ha="center")
            xs += 1.2
        ax.set_ylabel("k (rc$^2$)")
        ax.set_xticks([])
        ax.legend(fontsize=8)
        ax.set_title("layered sphere arrays: loop vs direct vs foam")
        fig.tight_layout()
        fig.savefig(os.path.join(res_dir, "couple_validation.png"), dpi=110)
    except ImportError:
        print("no matplotlib: no PNG")
    print(open(os.path.join(res_dir, "couple_validation.md")).read())
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
