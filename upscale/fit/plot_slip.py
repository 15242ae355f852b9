#!/usr/bin/env python3
"""Plot a `mdpore slip` JSON: k / k_noslip against the pore size with the fitted apparent-permeability
model and its 1-sigma band, and the normalised residuals.
Usage: plot_slip.py SLIP.json OUT.png   (needs matplotlib; uses the Agg backend)."""
import json
import os
import sys

try:
    import matplotlib
except ImportError:
    sys.exit("plot_slip.py: matplotlib is not installed")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_slip.py SLIP.json OUT.png")
    with open(sys.argv[1]) as f:
        d = json.load(f)
    fit, pts, cur = d["fit"], d["points"], d["curve"]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(6.5, 6.5), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1.2]})
    h = [p["h"] for p in pts]
    top.errorbar(h, [p["ratio"] for p in pts], yerr=[p["ratio_err"] for p in pts], fmt="ko", ms=5,
                 capsize=3, label="k / k_noslip (data)")
    lo = [m - e for m, e in zip(cur["model"], cur["model_err"])]
    hi = [m + e for m, e in zip(cur["model"], cur["model_err"])]
    err = fit["b_err"]
    label = "%s: b = %.3f ± %.3f rc" % (d["form"], fit["b"], err)
    if d["free_scale"]:
        label += ", a = %.3f ± %.3f" % (fit["a"], fit["a_err"])
    label += (", chi2/dof %.2g" % fit["chi2_dof"]) if fit["chi2_dof"] is not None else ", chi2 undefined"
    top.plot(cur["h"], cur["model"], "C0-", label=label)
    top.fill_between(cur["h"], lo, hi, color="C0", alpha=0.2, lw=0)
    top.axhline(1.0, color="gray", lw=0.8, ls="--", label="no slip")
    top.set_xlim(0, max(cur["h"]) * 1.02)
    top.set_ylabel("k / k_noslip")
    top.set_title("apparent permeability, %s (%s)" % (d["shape"], d["size"]), fontsize=10)
    top.legend(fontsize=7)
    bottom.axhline(0, color="gray", lw=0.8)
    bottom.plot(h, [p["normalised_residual"] for p in pts], "ko")
    bottom.set_ylabel("(data - model) / err")
    bottom.set_xlabel("%s (rc)" % d["size"])
    fig.tight_layout()
    tmp = sys.argv[2] + ".tmp.png"
    fig.savefig(tmp, dpi=120)
    os.replace(tmp, sys.argv[2])  # atomic


if __name__ == "__main__":
    main()
