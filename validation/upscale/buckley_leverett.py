#!/usr/bin/env python3
"""`mdpore darcy` two-phase (IMPES) against the Buckley-Leverett solution on a 1-D homogeneous column.

Water (mu_w) displaces oil (mu_o) at a set total rate Q through a column of length L, cross-section A,
porosity phi; Corey laws krw = S^nw, kro = (1 - S)^no (swc = sor = 0 unless given), no capillary
pressure, no gravity. With f_w(S) = (krw/mu_w) / (krw/mu_w + kro/mu_o):
  * rarefaction behind the front: x(S, t) = f_w'(S) Q t / (phi A) for S_f <= S <= 1 - sor;
  * shock (Welge tangent from the initial saturation S_i): (f_w(S_f) - f_w(S_i)) / (S_f - S_i) =
    f_w'(S_f), front at x_f = f_w'(S_f) Q t / (phi A). For nw = no = 2, S_i = swc = sor = 0 and
    M = mu_o / mu_w the tangent condition reduces to (1 + 1/M) S_f^2 = 1/M, so S_f = 1 / sqrt(1 + M)
    and f_w'(S_f) = f_w(S_f) / S_f = (1 + sqrt(1 + M)) / 2 (both checked against the numerical
    tangent below, which is what the comparison uses).
Measured: the front (where the numerical profile crosses (S_f + S_i) / 2, searched from the outlet)
against x_f, and the mean and largest |S - S_exact| over the blocks with x < 0.9 x_f (the
rarefaction, away from the smeared shock).

Usage: buckley_leverett.py --mdpore build/bin/mdpore [--quick] [--outdir DIR]
  full: M = 1 and 5 at 200 and 400 blocks, front within 2 %, profile mean error within 0.02;
  --quick (ctest): M = 2 at 200 blocks, front within 3 %.
Writes DIR/buckley_leverett.{md,csv} and DIR/buckley_leverett.png (full run), the configs and CSVs
of each run under DIR/runs/; exits 1 when a check fails."""
import argparse
import csv
import math
import os
import subprocess
import sys

import numpy as np

L, A_DEPTH, PHI, RATE = 1.0, 0.01, 0.2, 1.0e-5  # m, m (2D: unit depth), -, m^2/s (per unit depth)
MU_W = 1.0e-3
FRONT_AT = 0.7  # the front stands at 0.7 L at the end time


def fw(s, m, nw=2.0, no=2.0):
    lw, lo = s**nw / MU_W, (1.0 - s)**no / (m * MU_W)
    return lw / (lw + lo)


def dfw(s, m, nw=2.0, no=2.0, h=1e-7):
    return (fw(np.minimum(s + h, 1.0), m, nw, no) - fw(np.maximum(s - h, 0.0), m, nw, no)) / \
        (np.minimum(s + h, 1.0) - np.maximum(s - h, 0.0))


def shock(m, s_i=0.0):
    """Welge tangent from s_i: the largest chord slope (f(S) - f(s_i)) / (S - s_i)."""
    s = np.linspace(s_i + 1e-6, 1.0, 2000001)
    slope = (fw(s, m) - fw(s_i, m)) / (s - s_i)
    j = int(np.argmax(slope))
    return s[j], slope[j]


def exact_profile(x, t, m, s_f):
    """S(x, t): rarefaction x / (Q t / (phi A)) = f'(S) on [s_f, 1], 0 ahead of the front."""
    area = A_DEPTH  # cross-section of the 2D column per unit depth
    xi = x * PHI * area / (RATE * t)
    out = np.zeros_like(x)
    s_grid = np.linspace(s_f, 1.0, 200001)
    d = dfw(s_grid, m)  # decreasing from f'(s_f) to 0
    behind = xi < d[0]
    out[behind] = np.interp(xi[behind], d[::-1], s_grid[::-1])
    return out


def run_case(mdpore, outdir, m, n):
    s_f, slope = shock(m)
    t_end = FRONT_AT * L * PHI * A_DEPTH / (slope * RATE)
    name = f"bl_M{m:g}_n{n}"
    outdir = os.path.join(outdir, "runs")  # configs and CSVs of each run
    os.makedirs(outdir, exist_ok=True)
    cfg = os.path.join(outdir, name + ".yaml")
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
  relperm: {{corey: {{nw: 2, no: 2, swc: 0, sor: 0}}}}
  initial_saturation: 0.0
  injection: {{face: x-, rate: {RATE}}}
  end_time: {t_end!r}
  output_times: [{t_end / 2!r}, {t_end!r}]
  output: {{profiles: {name}_profiles.csv, history: {name}_history.csv}}
""")
    r = subprocess.run([mdpore, "darcy", cfg], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"mdpore darcy failed on {cfg} (exit {r.returncode}):\n{r.stdout}{r.stderr}")
    rows = [row for row in csv.DictReader(
        line for line in open(os.path.join(outdir, name + "_profiles.csv")) if not line.startswith("#"))]
    t = np.array([float(row["time"]) for row in rows])
    last = np.isclose(t, t_end, rtol=1e-9)
    x = np.array([float(row["x"]) for row in rows])[last]
    s = np.array([float(row["sw"]) for row in rows])[last]
    x_f = slope * RATE * t_end / (PHI * A_DEPTH)
    level = 0.5 * s_f  # midway between S_f and S_i = 0
    j = np.nonzero(s > level)[0].max()  # last block above the level, from the outlet side
    x_num = x[j] + (x[j + 1] - x[j]) * (s[j] - level) / (s[j] - s[j + 1])
    behind = x < 0.9 * x_f
    err = np.abs(s[behind] - exact_profile(x[behind], t_end, m, s_f))
    steps = sum(1 for line in open(os.path.join(outdir, name + "_history.csv"))
                if line[0].isdigit())
    return dict(M=m, n=n, S_f=s_f, dfw_Sf=slope, t_end=t_end, x_f_exact=x_f, x_f_num=x_num,
                front_rel_err=(x_num - x_f) / x_f, profile_mean_err=float(err.mean()),
                profile_max_err=float(err.max()), steps=steps, x=x, s=s)


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ms = sorted({r["M"] for r in results})
    fig, axes = plt.subplots(1, len(ms), figsize=(5.5 * len(ms), 4), squeeze=False)
    for ax, m in zip(axes[0], ms):
        sub = [r for r in results if r["M"] == m]
        xx = np.linspace(0, L, 2001)
        ax.plot(xx, exact_profile(xx, sub[0]["t_end"], m, sub[0]["S_f"]), "k-", lw=2,
                label="Buckley-Leverett")
        for r in sub:
            ax.plot(r["x"], r["s"], "--", label=f"IMPES, {r['n']} blocks")
        ax.set(title=f"M = mu_o/mu_w = {m:g}, t = {sub[0]['t_end']:.4g} s", xlabel="x (m)",
               ylabel="water saturation")
        ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mdpore", required=True)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--outdir", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                     "..", "results", "buckley_leverett"))
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    # the closed form for Corey-2, swc = sor = 0 against the numerical tangent
    for m in (1.0, 2.0, 5.0):
        s_f, slope = shock(m)
        if abs(s_f - 1.0 / math.sqrt(1.0 + m)) > 1e-5 or \
                abs(slope - 0.5 * (1.0 + math.sqrt(1.0 + m))) > 1e-5:
            sys.exit(f"tangent ({s_f}, {slope}) != (1/sqrt(1+M), (1+sqrt(1+M))/2) for M = {m}")
    cases = [(2.0, 200)] if a.quick else [(1.0, 200), (1.0, 400), (5.0, 200), (5.0, 400)]
    front_tol, profile_tol = (0.03, None) if a.quick else (0.02, 0.02)
    results = [run_case(a.mdpore, a.outdir, m, n) for m, n in cases]
    keys = ["M", "n", "S_f", "dfw_Sf", "t_end", "x_f_exact", "x_f_num", "front_rel_err",
            "profile_mean_err", "profile_max_err", "steps"]
    with open(os.path.join(a.outdir, "buckley_leverett.csv"), "w") as f:
        f.write(",".join(keys) + "\n")
        for r in results:
            f.write(",".join(f"{r[k]:.6g}" for k in keys) + "\n")
    fails = []
    with open(os.path.join(a.outdir, "buckley_leverett.md"), "w") as f:
        f.write("| M | blocks | S_f | x_f exact (m) | x_f IMPES (m) | front error | "
                "mean abs(S - S_BL), x < 0.9 x_f | max | steps |\n|---|---|---|---|---|---|---|---|---|\n")
        for r in results:
            f.write(f"| {r['M']:g} | {r['n']} | {r['S_f']:.4f} | {r['x_f_exact']:.4f} | "
                    f"{r['x_f_num']:.4f} | {100 * r['front_rel_err']:+.2f} % | "
                    f"{r['profile_mean_err']:.4f} | {r['profile_max_err']:.4f} | {r['steps']} |\n")
            if abs(r["front_rel_err"]) > front_tol:
                fails.append(f"M = {r['M']:g}, {r['n']} blocks: front {r['x_f_num']:.4f} m vs "
                             f"{r['x_f_exact']:.4f} m ({100 * r['front_rel_err']:+.2f} %, limit "
                             f"{100 * front_tol:g} %)")
            if profile_tol and r["profile_mean_err"] > profile_tol:
                fails.append(f"M = {r['M']:g}, {r['n']} blocks: profile mean error "
                             f"{r['profile_mean_err']:.4f} > {profile_tol}")
    print(open(os.path.join(a.outdir, "buckley_leverett.md")).read())
    if not a.quick:
        plot(results, os.path.join(a.outdir, "buckley_leverett.png"))
    for msg in fails:
        print("FAIL:", msg)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
