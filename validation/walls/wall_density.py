#!/usr/bin/env python3
"""Slip against the wall patch density (docs/walls.md section 16): body-force Poiseuille flow in
image slits (validation/walls/slit_poiseuille.py) at several geometry.wall_density values, one table
and one PNG of the slip lengths, the centre velocity against the no-slip prediction with the bulk
viscosity mu_ref, the pore fluid's density and layering.

  wall_density.py run WORK [--densities 8 6.2 5 4] [--widths 4 8 12] [--steps N] [--boundary B]
      slit_poiseuille.py --no-bulk --wall-density W per density (runs in WORK/wdW, reused when
      the same scene is there), then the summary;
  wall_density.py collect CSV [CSV ...]
      the summary of slit_poiseuille.py result tables already made (each CSV's wall density is
      read from its name, slit_poiseuille*_wdW.csv, 8 without a suffix).
Writes validation/results/walls/wall_density.{md,csv,png} (or --outdir). Nothing is checked here:
the slit script checks each run (penetrations, temperature, near-wall density); this summary is
the curve a user reads to choose a wall density. Run with /usr/bin/python3.
"""
import argparse
import csv
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))


def wall_density_of(path):
    m = re.search(r"_wd([0-9.]+)\.csv$", os.path.basename(path))
    return float(m.group(1)) if m else 8.0


def boundary_of(path):
    return "wall_boundary+bounce_back" if "wall_boundary" in os.path.basename(path) else "bounce_back"


def read_rows(paths):
    rows = []
    for p in paths:
        with open(p) as f:
            for r in csv.DictReader(f):
                f2 = {k: (float(v) if v not in ("", None) and re.fullmatch(r"[-+0-9.eE]+", v) else v)
                      for k, v in r.items()}
                f2["wall_density"], f2["boundary"], f2["source"] = wall_density_of(p), boundary_of(p), p
                rows.append(f2)
    rows.sort(key=lambda r: (r["boundary"], -r["wall_density"], r["h"]))
    return rows


def summary(rows, outdir, command):
    os.makedirs(outdir, exist_ok=True)
    cols = ["boundary", "wall_density", "h", "steps", "n_centre", "u_c", "u_c_err", "u_pred", "b_lo_A", "b_hi_A",
            "b_lo_A_err", "b_lo_C", "b_hi_C", "b_lo_D", "b_hi_D", "b_lo_D_err", "mu_C", "mu_C_err", "n_contact_lo",
            "n_contact_hi", "n_near_lo", "n_near_hi", "n_bin_maxdev", "T_thermal", "penetrations"]
    with open(os.path.join(outdir, "wall_density.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    lines = ["# Slip against the wall patch density (image slits, body-force Poiseuille)", "",
             f"Command: `{command}`. Each row is one `validation/walls/slit_poiseuille.py` run (box 6 x (h + 4) x 4 rc, "
             "mDPD A = -40, B = 25, gamma = 4.5, fluid 6.2 per rc^3 of pore, dt 0.01, 2 ranks) at "
             "`geometry.wall_density` W; its own table is the source column. Slip b (rc) per wall, lower / upper: "
             "fit A = parabola with mu = mu_ref = 5.41 (the campaign's default viscosity) and free zeros, fit C = "
             "free parabola over all fluid bins, fit D = free parabola over the bins more than 0.5 rc from the "
             "faces; b < 0: the flow vanishes inside the fluid. u_c / no-slip = centre velocity over "
             "n g h^2 / (8 mu_ref).", "",
             "| boundary | W | h | steps | n centre | u_c / no-slip | b fit A | b fit C | b fit D | mu fit C | "
             "contact layer / n | 0.5-1.5 rc / n | max bin dev. | T thermal | penetrations |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(
            f"| {r['boundary']} | {r['wall_density']:g} | {r['h']:g} | {int(r['steps'])} | {r['n_centre']:.3f} | "
            f"{r['u_c'] / r['u_pred']:.3f} +- {r['u_c_err'] / r['u_pred']:.3f} | "
            f"{r['b_lo_A']:+.3f} / {r['b_hi_A']:+.3f} (+- {r['b_lo_A_err']:.3f}) | {r['b_lo_C']:+.3f} / {r['b_hi_C']:+.3f} | "
            f"{r['b_lo_D']:+.3f} / {r['b_hi_D']:+.3f} (+- {r['b_lo_D_err']:.3f}) | {r['mu_C']:.2f} +- {r['mu_C_err']:.2f} | "
            f"{r['n_contact_lo'] / r['n_centre']:.2f} / {r['n_contact_hi'] / r['n_centre']:.2f} | "
            f"{r['n_near_lo'] / r['n_centre']:.3f} / {r['n_near_hi'] / r['n_centre']:.3f} | "
            f"{100 * r['n_bin_maxdev']:.1f}% | {r['T_thermal']:.4f} | {int(r['penetrations'])} |")
    open(os.path.join(outdir, "wall_density.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (a0, a1) = plt.subplots(1, 2, figsize=(10, 4))
        for i, (bnd, h) in enumerate(sorted({(r["boundary"], r["h"]) for r in rows})):
            sel = [r for r in rows if r["boundary"] == bnd and r["h"] == h]
            W = [r["wall_density"] for r in sel]
            mk = "o" if bnd == "bounce_back" else "^"
            a0.errorbar(W, [(r["b_lo_A"] + r["b_hi_A"]) / 2 for r in sel], yerr=[r["b_lo_A_err"] / 2 ** 0.5 for r in sel],
                        fmt=mk + "-", color=f"C{i}", label=f"{bnd}, h = {h:g}")
            a1.errorbar(W, [r["u_c"] / r["u_pred"] for r in sel], yerr=[r["u_c_err"] / r["u_pred"] for r in sel],
                        fmt=mk + "-", color=f"C{i}", label=f"{bnd}, h = {h:g}")
        a0.axhspan(-0.1, 0.1, color="0.9")
        a0.set_xlabel("wall density W (particles per rc^3)")
        a0.set_ylabel("slip b, fit A (mean of both walls, rc)")
        a1.axhline(1.0, color="0.5", lw=0.8)
        a1.set_xlabel("wall density W (particles per rc^3)")
        a1.set_ylabel("u_c / no-slip u_c (mu 5.41)")
        a0.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(outdir, "wall_density.png"), dpi=120)
    except ImportError:
        pass


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("stage", choices=["run", "collect"])
    ap.add_argument("args", nargs="+", help="run: WORK; collect: CSV files")
    ap.add_argument("--densities", type=float, nargs="+", default=[8.0, 6.2, 5.0, 4.0])
    ap.add_argument("--widths", nargs="+", default=["4", "8", "12"])
    ap.add_argument("--steps", type=int, default=60000)
    ap.add_argument("--boundary", default="bounce_back")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--outdir", default=os.path.join(ROOT, "validation", "results", "walls"))
    a = ap.parse_args()
    if a.stage == "collect":
        summary(read_rows(a.args), a.outdir, "/usr/bin/python3 validation/walls/wall_density.py collect " +
                " ".join(os.path.relpath(p, ROOT) if p.startswith(ROOT) else os.path.basename(p) for p in a.args))
        return 0
    work, csvs = os.path.abspath(a.args[0]), []
    for W in a.densities:
        out = os.path.join(work, f"wd{W:g}", "out")
        cmd = [sys.executable, os.path.join(HERE, "slit_poiseuille.py"), "--widths", *a.widths, "--steps",
               str(a.steps), "--no-bulk", "--reuse", "--np", str(a.np), "--boundary", a.boundary,
               "--wall-density", str(W), "--workdir", os.path.join(work, f"wd{W:g}"), "--outdir", out]
        print(" ".join(cmd), flush=True)
        subprocess.run(cmd, check=False)  # a failed check is in its table; the summary shows it
        csvs += [os.path.join(out, f) for f in sorted(os.listdir(out)) if f.endswith(".csv")]
    summary(read_rows(csvs), a.outdir, "/usr/bin/python3 validation/walls/wall_density.py run WORK --densities " +
            " ".join(f"{W:g}" for W in a.densities) + f" --widths {' '.join(a.widths)} --steps {a.steps} "
            f"--boundary {a.boundary}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
