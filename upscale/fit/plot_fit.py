#!/usr/bin/env python3
"""Plot a `mdpore fit` JSON: data with error bars, every fitted law, and normalised residuals.
Usage: plot_fit.py FIT.json OUT.png   (needs matplotlib; uses the Agg backend)."""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_fit.py FIT.json OUT.png")
    with open(sys.argv[1]) as f:
        fit = json.load(f)
    d = fit["data"]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1.4]})
    top.errorbar(d["G"], d["q"], yerr=d["sigma"], fmt="ko", ms=4, capsize=2, label="data")
    for m in fit["models"]:
        if not m.get("ok"):
            continue
        chosen = m["law"] == fit.get("chosen")
        label = "%s (chi2/dof %.3g%s)" % (m["law"], m["chi2_dof"], ", chosen" if chosen else "")
        line, = top.plot(m["curve"]["G"], m["curve"]["q"], lw=2.5 if chosen else 1.2, label=label)
        bottom.plot(d["G"], m["normalised_residuals"], "o-", ms=3, color=line.get_color())
    units = fit["unit_system"]
    top.set_ylabel("Darcy velocity q (%s)" % ("m/s" if units == "SI" else "reduced"))
    top.set_title("%s, axis %s" % (fit["sample"], fit["axis"]))
    top.legend(fontsize=8)
    bottom.axhline(0, color="gray", lw=0.8)
    bottom.set_ylabel("(q - fit) / sigma")
    bottom.set_xlabel("driving gradient G = -dp/dx (%s)" % ("Pa/m" if units == "SI" else "reduced"))
    fig.tight_layout()
    tmp = sys.argv[2] + ".tmp.png"
    fig.savefig(tmp, dpi=120)
    os.replace(tmp, sys.argv[2])  # atomic


if __name__ == "__main__":
    main()
