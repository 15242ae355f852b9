#!/usr/bin/env python3
"""The continuum check of the SWOF export: a synthetic relperm.csv (validation/upscale/
relperm_synth.py, a Corey law with seeded noise) is fitted and exported by `mdpore fit relperm
--swof`, the SWOF table runs through `mdpore darcy`'s two-phase (IMPES) solve of a 1-D column, and
the water front is compared with the Buckley-Leverett solution of the same table.

Buckley-Leverett of the table: f_w(S) = (krw/mu_w) / (krw/mu_w + krow/mu_o) with krw and krow
interpolated linearly between the SWOF rows (as mdpore darcy does); the shock is the Welge tangent
from the initial saturation S_i (the table's first Sw, where krw = 0): the largest chord slope
(f_w(S) - f_w(S_i)) / (S - S_i), at S_f, and the front stands at x_f = slope Q t / (phi A). For a
Corey-2 law with swc = sor = 0 the tangent is S_f = 1/sqrt(1 + M), f_w'(S_f) = (1 + sqrt(1 + M))/2
(M = mu_o/mu_w); case "corey2" checks the table's tangent against that closed form.

Measured: the numerical front (where the profile crosses (S_f + S_i)/2, searched from the outlet)
against x_f of the table, at 200 and 400 blocks; also listed: the tangent of the law the data were
drawn from (how far fit + export move the shock).

Usage: relperm_swof_bl.py --mdpore build/bin/mdpore [--outdir DIR] [--plot]
Checks: front within 2 % of the table's x_f at both grid sizes; corey2: |S_f - 1/sqrt(1+M)| < 0.01.
Writes DIR/relperm_swof_bl.{md,csv} (and .png with --plot), the tables, SWOF files, configs and
profiles under DIR/runs/; exits 1 when a check fails."""
import argparse
import csv
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
L, A_DEPTH, PHI, RATE, MU_W = 1.0, 0.01, 0.2, 1.0e-5, 1.0e-3
FRONT_AT = 0.7
# name, Corey truth (swc sor krw_max nw kro_max no), Sw range of the data, M = mu_o / mu_w
CASES = [
    ("corey2", [0.0, 0.0, 1.0, 2.0, 1.0, 2.0], [0.05, 0.95], 1.0),
    ("synthetic", [0.12, 0.18, 0.45, 2.6, 0.9, 1.9], [0.2, 0.78], 2.0),
]
BLOCKS = (200, 400)
FRONT_TOL = 0.02


def read_swof(path):
    rows = []
    for line in open(path):
        s = line.strip()
        if not s or s.startswith("--") or s.startswith("SWOF"):
            continue
        if s.startswith("/"):
            break
        rows.append([float(v) for v in s.split()[:4]])
    return np.array(rows)


def fw_table(tab, m):
    def f(s):
        krw = np.interp(s, tab[:, 0], tab[:, 1])
        kro = np.interp(s, tab[:, 0], tab[:, 2])
        lw, lo = krw / MU_W, kro / (m * MU_W)
        return lw / (lw + lo)
    return f


def fw_corey(p, m):
    swc, sor, a, nw, b, no = p

    def f(s):
        se = np.clip((s - swc) / (1 - swc - sor), 0, 1)
        lw, lo = a * se**nw / MU_W, b * (1 - se)**no / (m * MU_W)
        return lw / (lw + lo)
    return f


def welge(f, s_i, s_max):
    s = np.linspace(s_i + 1e-7, s_max, 2000001)
    slope = (f(s) - f(s_i)) / (s - s_i)
    j = int(np.argmax(slope))
    return s[j], slope[j]


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed (exit {r.returncode}):\n{r.stdout}{r.stderr}")
    return r.stdout


def darcy_front(mdpore, outdir, name, swof, m, n, s_i, s_f, slope):
    t_end = FRONT_AT * L * PHI * A_DEPTH / (slope * RATE)
    cfg = os.path.join(outdir, f"{name}_n{n}.yaml")
    with open(cfg, "w") as f:
        f.write(f"""units: SI
grid: {{cells: [{n}, 1], size: [{L}, {A_DEPTH}]}}
boundary:
  x-: {{pressure: 2.0e5}}
  x+: {{pressure: 1.0e5}}
laws:
  uniform: {{law: darcy, k: 1 D}}
twophase:
  mu_w: {MU_W}
  mu_o: {m * MU_W}
  porosity: {PHI}
  relperm: {{table: {os.path.basename(swof)}}}
  injection: {{face: x-, rate: {RATE}}}
  end_time: {t_end!r}
  output: {{profiles: {name}_n{n}_profiles.csv}}
""")
    run([mdpore, "darcy", cfg])
    rows = list(csv.DictReader(line for line in open(os.path.join(outdir, f"{name}_n{n}_profiles.csv"))
                               if not line.startswith("#")))
    t = np.array([float(r["time"]) for r in rows])
    last = np.isclose(t, t_end, rtol=1e-9)
    x = np.array([float(r["x"]) for r in rows])[last]
    s = np.array([float(r["sw"]) for r in rows])[last]
    level = 0.5 * (s_f + s_i)
    j = np.nonzero(s > level)[0].max()
    x_num = x[j] + (x[j + 1] - x[j]) * (s[j] - level) / (s[j] - s[j + 1])
    x_f = slope * RATE * t_end / (PHI * A_DEPTH)
    return x_f, x_num, t_end, x, s


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mdpore", required=True)
    ap.add_argument("--outdir", default=os.path.join(HERE, "..", "results", "relperm_swof"))
    ap.add_argument("--plot", action="store_true")
    a = ap.parse_args()
    runs = os.path.join(a.outdir, "runs")  # tables, SWOF files, configs and profiles of each run
    os.makedirs(runs, exist_ok=True)
    results, fails, profiles, exact = [], [], {}, {}
    for name, truth, sw_range, m in CASES:
        table = os.path.join(runs, f"{name}_relperm.csv")
        swof = os.path.join(runs, f"{name}.swof")
        run([sys.executable, os.path.join(HERE, "relperm_synth.py"), table, "--rows", "16",
             "--sw-range", *map(str, sw_range), "--corey", *map(str, truth)])
        run([a.mdpore, "fit", "relperm", table, "--swof", swof, "--json",
             os.path.join(runs, f"{name}.fit.json"), "--quiet"])
        tab = read_swof(swof)
        s_i = tab[0, 0]
        s_f, slope = welge(fw_table(tab, m), s_i, tab[-1, 0])
        exact[name] = (fw_table(tab, m), tab[-1, 0])
        s_f_true, slope_true = welge(fw_corey(truth, m), truth[0], 1.0 - truth[1])
        if name == "corey2":
            closed = 1.0 / math.sqrt(1.0 + m)
            if abs(s_f - closed) > 0.01:
                fails.append(f"{name}: table tangent S_f = {s_f:.4f}, closed form {closed:.4f}")
        for n in BLOCKS:
            x_f, x_num, t_end, x, s = darcy_front(a.mdpore, runs, name, swof, m, n, s_i, s_f, slope)
            err = (x_num - x_f) / x_f
            results.append(dict(case=name, M=m, n=n, rows=len(tab), S_i=s_i, S_f=s_f, dfw=slope,
                                S_f_truth=s_f_true, dfw_truth=slope_true, x_f=x_f, x_num=x_num,
                                front_rel_err=err))
            profiles[(name, n)] = (x, s, t_end)
            if abs(err) > FRONT_TOL:
                fails.append(f"{name}, {n} blocks: front {x_num:.4f} m vs {x_f:.4f} m "
                             f"({100 * err:+.2f} %, limit {100 * FRONT_TOL:g} %)")
    keys = list(results[0].keys())
    with open(os.path.join(a.outdir, "relperm_swof_bl.csv"), "w") as f:
        f.write(",".join(keys) + "\n")
        for r in results:
            f.write(",".join(str(r[k]) if isinstance(r[k], str) else f"{r[k]:.6g}" for k in keys)
                    + "\n")
    md = os.path.join(a.outdir, "relperm_swof_bl.md")
    with open(md, "w") as f:
        f.write("| case | M | blocks | SWOF rows | S_i | S_f (table) | f_w'(S_f) | S_f (true law) | "
                "x_f table (m) | x_f IMPES (m) | front error |\n"
                "|---|---|---|---|---|---|---|---|---|---|---|\n")
        for r in results:
            f.write(f"| {r['case']} | {r['M']:g} | {r['n']} | {r['rows']} | {r['S_i']:.4f} | "
                    f"{r['S_f']:.4f} | {r['dfw']:.4f} | {r['S_f_truth']:.4f} | {r['x_f']:.4f} | "
                    f"{r['x_num']:.4f} | {100 * r['front_rel_err']:+.2f} % |\n")
    print(open(md).read())
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, len(CASES), figsize=(5.5 * len(CASES), 4), squeeze=False)
        for ax, (name, truth, _, m) in zip(axes[0], CASES):
            for n in BLOCKS:
                x, s, t_end = profiles[(name, n)]
                ax.plot(x, s, "-", label=f"IMPES, {n} blocks")
            sub = [r for r in results if r["case"] == name]
            f, s_f, t_end = exact[name][0], sub[0]["S_f"], profiles[(name, BLOCKS[0])][2]
            s_grid = np.linspace(s_f, exact[name][1], 4001)
            x_bl = np.gradient(f(s_grid), s_grid) * RATE * t_end / (PHI * A_DEPTH)
            # the rarefaction from the inlet (S_max, x = 0) to the shock, then the initial state
            ax.plot(np.append(x_bl[::-1], [sub[0]["x_f"], sub[0]["x_f"], L]),
                    np.append(s_grid[::-1], [s_f, sub[0]["S_i"], sub[0]["S_i"]]), "k--", lw=1.2,
                    label="Buckley-Leverett of the table")
            ax.set(title=f"{name}: M = {m:g}", xlabel="x (m)", ylabel="water saturation")
            ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(a.outdir, "relperm_swof_bl.png"), dpi=110)
    for msg in fails:
        print("FAIL:", msg)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
