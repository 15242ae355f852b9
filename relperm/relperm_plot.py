"""kr(Sw) of `mdpore relperm` with error bars: relperm_plot.py RELPERM.json OUT.png (docs/relperm.md)."""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    d = json.load(open(sys.argv[1]))
    rows = d["rows"]
    sw = [r["Sw"] for r in rows]
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    ax.errorbar(sw, [r["krw"] for r in rows], yerr=[r["krw_err"] or 0 for r in rows], fmt="o-", color="tab:blue",
                capsize=3, label="krw = q_w / q_w^(1)")
    ax.errorbar(sw, [r["kro"] for r in rows], yerr=[r["kro_err"] or 0 for r in rows], fmt="s-", color="tab:red",
                capsize=3, label="kro = q_o / q_o^(1)")
    if abs(d["M"] - 1) > 1e-12:
        ax.errorbar(sw, [r["kro_water_normalised"] for r in rows],
                    yerr=[r["kro_water_normalised_err"] or 0 for r in rows], fmt="^--", color="tab:orange",
                    capsize=3, label="M q_o / q_w^(1)")
    ax.set_xlim(0, 1)
    ax.set_ylim(bottom=0)
    ax.set_xlabel("Sw (particle counts)")
    ax.set_ylabel("relative permeability")
    ax.set_title(f"{d['sample']}: {d['wetting']}-wet, phases {d['mode']}, M = {d['M']:.3g}, axis {d['axis']}",
                 fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
