#!/usr/bin/env python3
"""Plot a `mdpore image drainage` CSV (pc_morph.csv): Pc(Sw) as computed (2 gamma cos / r) and
with the wall depletion interpretation (r - 1.15 rc), and the Leverett J curve when present.
Usage: plot_pc_morph.py pc_morph.csv OUT.png   (needs matplotlib; uses the Agg backend)."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def column(rows, name):
    return [float(r[name]) if r[name] != "" else float("nan") for r in rows]


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_pc_morph.py pc_morph.csv OUT.png")
    with open(sys.argv[1]) as f:
        comments = []
        lines = []
        for line in f:
            (comments if line.startswith("#") else lines).append(line)
    rows = list(csv.DictReader(lines))
    if not rows:
        sys.exit("plot_pc_morph.py: %s has no rows" % sys.argv[1])
    sw = column(rows, "Sw")
    has_j = any(r["J"] != "" for r in rows)
    fig, axes = plt.subplots(1, 2 if has_j else 1, figsize=(11 if has_j else 6.5, 4.8))
    ax = axes[0] if has_j else axes
    ax.step(sw, column(rows, "pc"), where="post", color="C0", label="pc = 2 gamma cos / r")
    ax.step(sw, column(rows, "pc_depleted"), where="post", color="C1", ls="--",
            label="pc_depleted = 2 gamma cos / (r - 1.15 rc) (interpretation)")
    ax.set_xlabel("wetting saturation Sw")
    ax.set_ylabel("capillary pressure (kT/rc^3)")
    ax.set_xlim(0, 1)
    ax.set_yscale("log")
    title = comments[0].lstrip("# ").split(":", 1)[-1].strip() if comments else ""
    ax.set_title(title[:80], fontsize=9)
    ax.legend(fontsize=8)
    if has_j:
        axes[1].step(sw, column(rows, "J"), where="post", color="C2")
        axes[1].set_xlabel("wetting saturation Sw")
        axes[1].set_ylabel("Leverett J = pc sqrt(k/phi) / (gamma cos)")
        axes[1].set_xlim(0, 1)
        axes[1].set_yscale("log")
    fig.tight_layout()
    tmp = sys.argv[2] + ".tmp.png"
    fig.savefig(tmp, dpi=120)
    os.replace(tmp, sys.argv[2])  # atomic


if __name__ == "__main__":
    main()
