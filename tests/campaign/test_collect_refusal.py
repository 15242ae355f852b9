#!/usr/bin/env python3
"""ctest campaign_collect_refusal: `mdpore permeability --collect` on hand-made campaign folders (a
manifest and one summary.json per run, written here; nothing is simulated: seconds). The runs the
data cannot trust are left out and named, and a campaign whose runs define no Darcy range reports no
k, writes k null and exits 3 (campaign/campaign_checks.c, campaign_collect.c; docs/permeability.md
"What it does", steps 5 and 6).

- mixed: 5 healthy runs on q = (k / mu) G (one of them short of its target error) and 3 runs whose q
  is far off that line: a cavitated core (4.3 against the fill 6.2), a heated liquid (T = 1.2) and an
  unsteady flux. The 3 are left out (report: G, folder, measured value, reason; permeability.json:
  check, measured; the flow table: comments, not rows) and k is the 5 healthy runs' within 1%;
  exit 0. With --require-target the run short of its target is left out too.
- all_bad: 4 of 5 runs cavitated (cores 4.0-4.8): "no Darcy range", why and what to try, k null,
  no chosen law, exit 3; a flow table and fit from an earlier collect are removed.
- rejected: 5 healthy runs whose q is not monotone in G with 0.1% error bars (chi2/dof in the
  hundreds): "no Darcy range", no k and no chosen law in the report (mdpore fit is not run on
  them), the table marked, the range's k null in permeability.json, exit 3.
- edited: a healthy folder edited between emit and collect as a careless user or script might: a
  run line duplicated, a second viscosity line, an unknown key, nan or inf in the manifest, one
  summary's G, flux.axis or fluid fraction changed, two run folders swapped, a scene removed.
  Each is refused (exit 1, no permeability.json) by a message naming the manifest line or the run's
  folder, and the key (campaign/campaign_plan.c: the manifest reader; campaign_consistency.c).
"""
import json
import math
import os
import shutil
import subprocess
import sys

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "campaign_collect_refusal_out"))
MU, K, FILL = 5.0, 0.8, 6.2  # q = (K / MU) G on the healthy runs
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def run_summary(G, q, rel, core=6.03, T=1.004, steady=True, reached=True):
    return {
        "thermo": {"T": {"mean": T, "err": 0.001}},
        "pore_core_density": {"mean": core, "err": 0.01},
        "flux": {"axis": "x", "q": q, "q_err": rel * abs(q), "G": G, "relative_error": rel,
                 "fluid_fraction": 0.48,
                 "steady_from_step": 500, "steady": steady, "plateau": reached,
                 "target_error": 0.05, "reached": reached},
        "timing": {"loop_seconds": 1.0, "steps": 8000, "particles": 1000},
    }


def make_campaign(name, runs):
    """runs: (G, summary) per run; returns the folder and {G: run folder}."""
    folder = os.path.join(OUT, name)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    lines = ["# mdpore permeability campaign v1", "sample: " + name, "input: /none/" + name,
             "image: ", "porosity: 0.5", "rc_per_voxel: 0.5", "h_hydraulic: 4",
             "percolates: 1 1 1", "fluid_density: %g" % FILL, "viscosity: %g" % MU,
             "viscosity_source: --viscosity", "length_unit_m: 8.2e-10",
             "length_source: the mDPD water mapping", "temperature_K: 298.15", "target_error: 0.05",
             "np: 1", "kT: 1", "drive: body", "reservoir: 0", "boundary: periodic none none",
             "sides: periodic", "seam_continuity: 1 nan nan"]
    dirs = {}
    for i, (G, summary) in enumerate(runs):
        run = os.path.join(folder, "runs", "x-%02d" % i)
        os.makedirs(run)
        with open(os.path.join(run, "summary.json"), "w") as f:
            json.dump(summary, f)
        with open(os.path.join(run, "scene.yaml"), "w") as f:  # the header mdpore permeability writes
            f.write("# mdpore permeability run: axis x, body force g = %.15g per particle; folder = "
                    "FNV-1a 64 of the text below and 'mdpore test'\n" % (G / FILL))
        lines.append("run: x %.17g %s" % (G / FILL, run))  # g = G / n (particle mass 1)
        dirs[G] = run
    with open(os.path.join(folder, "campaign.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return folder, dirs


def collect(folder, *extra):
    p = subprocess.run([MDPORE, "permeability", "--collect", folder, *extra],
                       capture_output=True, text=True)
    report = p.stdout + p.stderr
    pj = os.path.join(folder, "permeability.json")
    data = json.load(open(pj))["axes"]["x"] if os.path.exists(pj) else None
    return p.returncode, report, data


def table_rows(folder):
    path = os.path.join(folder, "flow_x.csv")
    if not os.path.exists(path):
        return None, []
    text = open(path).read().splitlines()
    comments = [l for l in text if l.startswith("#")]
    rows = [l for l in text if l and not l.startswith("#")]
    return rows[1:], comments  # the header line is the first non-comment


def mixed():
    healthy = [0.1, 0.2, 0.3, 0.4, 0.5]
    runs = [(G, run_summary(G, K / MU * G * (1 + 0.003 * (-1) ** i), 0.01,
                            reached=(G != 0.3)))
            for i, G in enumerate(healthy)]
    runs += [(0.6, run_summary(0.6, 0.6 * K / MU * 0.5, 0.01, core=4.3)),
             (0.7, run_summary(0.7, 0.7 * K / MU * 1.6, 0.01, T=1.2)),
             (0.8, run_summary(0.8, 0.8 * K / MU * 0.3, 0.01, steady=False))]
    folder, dirs = make_campaign("mixed", runs)
    rc, report, ax = collect(folder)
    print(report)
    check(rc == 0, "mixed: exit 0 (got %d)" % rc)
    for G, word, value in ((0.6, "cavitated", "4.3"), (0.7, "heating", "1.2"),
                           (0.8, "no steady state", "8000")):
        line = [l for l in report.splitlines() if l.strip().startswith("left out: G = %g " % G)]
        check(len(line) == 1 and dirs[G] in line[0] and word in line[0] and value in line[0],
              "mixed: G = %g left out in the report with its folder, '%s' and %s" % (G, word, value))
    check("no Darcy range" not in report, "mixed: a Darcy range found")
    check(ax is not None and ax["k_defined"] and ax["rows"] == 5,
          "mixed: permeability.json: k defined over the 5 admissible rows")
    if ax:
        check(abs(ax["k_rc2"] / K - 1) < 0.01,
              "mixed: k = %.5g within 1%% of %g (the 3 bad rows would pull it far off)"
              % (ax["k_rc2"], K))
        check(ax["k_m2"] > 0 and abs(ax["k_nD"] / (ax["k_m2"] * 1e9 / 9.869233e-13) - 1) < 1e-3,
              "mixed: k in m^2 and nD")
        checks = {round(e["G"], 6): (e.get("check"), e.get("measured"), e.get("run")) for e in ax["left_out"]}
        check(checks == {0.6: ("cavitated", 4.3, dirs[0.6]), 0.7: ("heated", 1.2, dirs[0.7]),
                         0.8: ("unsteady", 8000, dirs[0.8])},
              "mixed: permeability.json left_out: check, measured value and folder of each")
        check(ax.get("runs_target_missed_kept") == 1, "mixed: the run short of its target kept, counted")
    rows, comments = table_rows(folder)
    check(rows is not None and len(rows) == 5, "mixed: the flow table holds the 5 admissible rows")
    check(sum("left out (" in c for c in comments) == 3,
          "mixed: the flow table names the 3 runs left out in its comments")
    check("missed their target" in report, "mixed: the report notes the run short of its target")

    rc, report, ax = collect(folder, "--require-target")
    check(rc == 0 and ax is not None and ax["rows"] == 4 and
          any(e.get("check") == "target_missed" and abs(e["G"] - 0.3) < 1e-9 for e in ax["left_out"]),
          "mixed --require-target: the run short of its target left out too, 4 rows remain")


def all_bad():
    cores = [6.03, 4.0, 4.4, 4.8, 4.2]
    runs = [(G, run_summary(G, K / MU * G, 0.01, core=n))
            for G, n in zip([0.82, 1.09, 1.45, 1.93, 2.57], cores)]
    folder, dirs = make_campaign("all_bad", runs)
    for stale in ("flow_x.csv", "fit_x.json"):  # an earlier collect's, with other tolerances
        with open(os.path.join(folder, stale), "w") as f:
            f.write("stale\n")
    rc, report, ax = collect(folder)
    print(report)
    check(rc == 3, "all_bad: exit 3 (got %d)" % rc)
    check("no Darcy range: k_xx is not defined by these runs" in report and
          "4 of 5 runs left out" in report, "all_bad: 'no Darcy range', and why")
    check("--rc-per-voxel" in report and "--velocity-range" in report and "--max-steps" in report,
          "all_bad: what to try (resolution, weaker forcing, longer runs)")
    check(sum("left out:" in l and "the liquid cavitated" in l for l in report.splitlines()) == 4,
          "all_bad: the 4 cavitated runs named as such")
    check("k_xx =" not in report and "chosen law" not in report,
          "all_bad: no k and no chosen law printed")
    check(ax is not None and ax["k_rc2"] is None and ax["k_nD"] is None and not ax["k_defined"] and
          "left out" in ax.get("k_undefined_why", "") and ax["chosen"] == "none" and
          ax["parameters"] == {}, "all_bad: permeability.json: k null, the reason, no law")
    check(not os.path.exists(os.path.join(folder, "flow_x.csv")) and
          not os.path.exists(os.path.join(folder, "fit_x.json")),
          "all_bad: the earlier collect's flow table and fit removed")


def rejected():
    # the reported symptom: q not monotone in G (lower at 0.82 than the line, higher at 1.45)
    Gs = [0.3, 0.55, 0.82, 1.09, 1.45]
    wobble = [1.0, 0.90, 1.12, 0.88, 1.10]
    runs = [(G, run_summary(G, K / MU * G * w, 0.001)) for G, w in zip(Gs, wobble)]
    folder, dirs = make_campaign("rejected", runs)
    rc, report, ax = collect(folder)
    print(report)
    check(rc == 3, "rejected: exit 3 (got %d)" % rc)
    check("no Darcy range: k_xx is not defined by these runs" in report and
          "do not fit a Darcy law" in report, "rejected: 'no Darcy range' with the chi2 reason")
    check("k_xx =" not in report and "chosen law" not in report and "+-" not in report and
          "chosen by" not in report, "rejected: no k, no error bar and no chosen law printed")
    rows, comments = table_rows(folder)
    check(rows is not None and len(rows) == 5 and any("no Darcy range" in c for c in comments) and
          not os.path.exists(os.path.join(folder, "fit_x.json")),
          "rejected: the flow table written and marked 'no Darcy range'; no law fitted to it")
    rng = ax.get("darcy_range", {}) if ax else {}
    check(ax is not None and ax["k_rc2"] is None and ax["k_rc2_all_rows"] is None and
          ax["chosen"] == "none" and rng.get("accepted") is False and rng.get("k_rc2") is None and
          rng.get("chi2_dof", 0) > rng.get("chi2_dof_max", math.inf),
          "rejected: permeability.json: k null everywhere, the range not accepted, chi2/dof above "
          "its bound")


def edited():
    Gs = [0.1, 0.2, 0.3, 0.4, 0.5]
    runs = [(G, run_summary(G, K / MU * G, 0.01)) for G in Gs]
    folder, dirs = make_campaign("edited_pristine", runs)
    rc, report, ax = collect(folder)
    check(rc == 0 and ax is not None and abs(ax["k_rc2"] / K - 1) < 0.01,
          "edited: the pristine folder collects (exit %d)" % rc)
    manifest = open(os.path.join(folder, "campaign.txt")).read()

    def variant(name, edit_manifest=None, edit_runs=None):
        dst = os.path.join(OUT, "edited_" + name)
        shutil.rmtree(dst, ignore_errors=True)
        shutil.copytree(folder, dst)
        for stale in ("permeability.json", "flow_x.csv", "fit_x.json", "flow_x.png"):
            if os.path.exists(os.path.join(dst, stale)):
                os.remove(os.path.join(dst, stale))
        text = edit_manifest(manifest) if edit_manifest else manifest
        text = text.replace(folder + "/", dst + "/")
        with open(os.path.join(dst, "campaign.txt"), "w") as f:
            f.write(text)
        run_dirs = {G: d.replace(folder + "/", dst + "/") for G, d in dirs.items()}
        if edit_runs:
            edit_runs(run_dirs)
        return dst, run_dirs

    def refused(name, dst, *words):
        rc, report, _ = collect(dst)
        missing = [w for w in words if w not in report]
        check(rc == 1 and not missing and
              not os.path.exists(os.path.join(dst, "permeability.json")),
              "edited %s: refused (exit %d), no permeability.json, the message names %s%s"
              % (name, rc, words, "" if not missing else " (missing %s in: %s)"
                 % (missing, report.strip()[-600:])))

    def summary_edit(G, change):
        def edit(run_dirs):
            path = os.path.join(run_dirs[G], "summary.json")
            data = json.load(open(path))
            change(data["flux"])
            json.dump(data, open(path, "w"))
        return edit

    run_lines = [l for l in manifest.splitlines() if l.startswith("run: ")]
    dst, rd = variant("duplicate_row", lambda t: t + run_lines[2] + "\n")
    refused("duplicate_row", dst, "key 'run'", "listed twice", rd[0.3])
    dst, rd = variant("second_viscosity", lambda t: t + "viscosity: 50\n")
    refused("second_viscosity", dst, "campaign.txt:", "key 'viscosity'", "given twice")
    dst, rd = variant("unknown_key", lambda t: t.replace("viscosity: ", "viscosty: ", 1))
    refused("unknown_key", dst, "key 'viscosty'", "not a key")
    dst, rd = variant("viscosity_nan", lambda t: t.replace("viscosity: %g" % MU, "viscosity: nan"))
    refused("viscosity_nan", dst, "key 'viscosity'", "finite", "nan")
    dst, rd = variant("fluid_density_inf",
                      lambda t: t.replace("fluid_density: %g" % FILL, "fluid_density: 1e400"))
    refused("fluid_density_inf", dst, "key 'fluid_density'", "finite")
    dst, rd = variant("g_inf", lambda t: t.replace(run_lines[1], "run: x inf " + run_lines[1].split()[3]))
    refused("g_inf", dst, "key 'run'", "finite")
    dst, rd = variant("summary_G", edit_runs=summary_edit(0.3, lambda f: f.update(G=f["G"] * 10)))
    refused("summary_G", dst, rd[0.3], "key 'flux.G'")
    dst, rd = variant("summary_axis", edit_runs=summary_edit(0.4, lambda f: f.update(axis="y")))
    refused("summary_axis", dst, rd[0.4], "key 'flux.axis'")
    dst, rd = variant("summary_fraction",
                      edit_runs=summary_edit(0.2, lambda f: f.update(fluid_fraction=0.31)))
    refused("summary_fraction", dst, rd[0.2], "key 'flux.fluid_fraction'")
    dst, rd = variant("fraction_above_porosity",
                      edit_runs=lambda r: [summary_edit(G, lambda f: f.update(fluid_fraction=0.9))(r)
                                           for G in Gs])
    refused("fraction_above_porosity", dst, rd[0.1], "key 'flux.fluid_fraction'", "porosity")

    def swap(run_dirs):
        a, b = run_dirs[0.1], run_dirs[0.5]
        os.rename(a, a + ".tmp")
        os.rename(b, a)
        os.rename(a + ".tmp", b)
    dst, rd = variant("swapped", edit_runs=swap)
    refused("swapped", dst, rd[0.1], rd[0.5], "key 'g'")
    dst, rd = variant("no_scene", edit_runs=lambda r: os.remove(os.path.join(r[0.2], "scene.yaml")))
    refused("no_scene", dst, rd[0.2], "scene.yaml")


def main():
    os.makedirs(OUT, exist_ok=True)
    mixed()
    all_bad()
    rejected()
    edited()
    print("%d failure(s)" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
