#!/usr/bin/env python3
"""PNG of an `mdpore couple` run: the blocks' Darcy permeability (a map: the middle layer of the
block grid normal to the smallest axis) and the loop's convergence (k_eff with its error per pass).
Usage: plot_couple.py WORKDIR/couple.json OUT.png"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    summary = json.load(open(sys.argv[1]))
    blocks = summary["blocks_final"]
    n = [int(v) for v in summary["blocks"]]
    k = np.full((n[2], n[1], n[0]), np.nan)
    for b in blocks:
        i, j, l = (int(v) for v in b["index"])
        k[l, j, i] = b["k_darcy_rc2"] if b["percolates"] else 0.0
    # show the two largest axes of the block grid, at the middle of the third
    thin = int(np.argmin(n))
    mid = n[thin] // 2
    layer = np.take(k, mid, axis=2 - thin)
    names = [a for a in "xyz" if a != "xyz"[thin]]
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10, 4))
    im = ax0.imshow(layer, origin="lower", cmap="viridis")
    fig.colorbar(im, ax=ax0, label="block k_Darcy (rc$^2$)")
    for (r, c), v in np.ndenumerate(layer):
        ax0.text(c, r, f"{v:.3g}", ha="center", va="center", color="w", fontsize=8)
    ax0.set_xlabel(f"block {names[0]}")
    ax0.set_ylabel(f"block {names[1]}")
    ax0.set_title(f"blocks ({'xyz'[thin]} layer {mid}), flow along {summary['axis']}")
    hist = summary["history"]
    p = [h["pass"] for h in hist]
    ke = [h["k_rc2"] for h in hist]
    err = [h["k_rc2_err"] or 0 for h in hist]
    ax1.errorbar(p, ke, yerr=err, marker="o", capsize=4)
    for h in hist:
        ax1.annotate(f"{h['new_runs']} new runs", (h["pass"], h["k_rc2"]), textcoords="offset points",
                     xytext=(4, 6), fontsize=8)
    ax1.set_xlabel("pass")
    ax1.set_ylabel("k_eff (rc$^2$)")
    state = "converged" if summary["converged"] else "not converged"
    ax1.set_title(f"loop: {state} after {summary['passes']} passes")
    ax1.set_xticks(p)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
