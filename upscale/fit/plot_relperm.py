#!/usr/bin/env python3
"""Plot a `mdpore fit relperm` JSON: krw and kro with error bars, the fitted Corey and LET laws, the
SWOF rows when exported, and the normalised residuals of the chosen law.
Usage: plot_relperm.py FIT.json OUT.png   (needs numpy and matplotlib; uses the Agg backend)."""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_relperm.py FIT.json OUT.png")
    with open(sys.argv[1]) as f:
        fit = json.load(f)
    d, curves, chosen = fit["data"], fit["curves"], fit["choice"]["law"]
    sw = np.array(d["sw"], float)
    nan = float("nan")
    col = {k: np.array([nan if v is None else v for v in d[k]], float)
           for k in ("krw", "krw_err", "kro", "kro_err")}
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7.5), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1]})
    top.errorbar(sw, col["krw"], yerr=col["krw_err"], fmt="o", color="C0", label="krw (data)")
    top.errorbar(sw, col["kro"], yerr=col["kro_err"], fmt="s", color="C3", label="kro (data)")
    style = {"corey": "-", "let": "--"}
    for law in ("corey", "let"):
        if law not in curves:
            continue
        c = curves[law]
        accepted = [f.get("accepted", True) for f in fit.get("fits", []) if f["law"] == law]
        tag = law + (" (chosen)" if law == chosen else "" if all(accepted) else " (refused)")
        top.plot(curves["sw"], c["krw"], style[law], color="C0", label=f"krw {tag}")
        top.plot(curves["sw"], c["kro"], style[law], color="C3", label=f"kro {tag}")
    if "swof" in fit:
        s = fit["swof"]
        top.plot(s["sw"], s["krw"], "k.", ms=4, label="SWOF rows")
        top.plot(s["sw"], s["krow"], "k.", ms=4)
    top.set_ylabel("relative permeability")
    top.set_title(f"{fit['table']}: chosen {chosen}" if chosen else
                  f"{fit['table']}: no law accepted (SWOF = the measured points)", fontsize=9)
    top.legend(fontsize=8)
    if chosen in curves:
        c = curves[chosen]
        for key, mark, color in (("krw", "o", "C0"), ("kro", "s", "C3")):
            model = np.interp(sw, curves["sw"], c[key])
            res = (col[key] - model) / col[key + "_err"]
            bottom.plot(sw, res, mark, color=color, label=key)
        bottom.axhline(0, color="k", lw=0.8)
        bottom.set_ylabel("(data - law) / err")
        bottom.legend(fontsize=8)
    else:
        bottom.text(0.5, 0.5, "no accepted law: no residuals", ha="center", va="center",
                    transform=bottom.transAxes)
    bottom.set_xlabel("Sw")
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
