#!/usr/bin/env python3
"""`mdpore fit relperm` at the command line:
  * bad tables, options and Pc curves are refused (exit 1, or 2 for a usage error) with a message
    naming the file, the line, the column and the value;
  * a synthetic Corey table (validation/upscale/relperm_synth.py, seeded noise): Corey chosen, every
    parameter within 3 of its (inflated) standard errors of the law the data were drawn from;
  * the SWOF export: Sw strictly increasing, krw non-decreasing from 0, krow non-increasing to 0,
    every kr in [0, 1]; a table whose oil kr exceeds 1 (kro_max = 1.25) has exactly the rows where
    the law exceeds 1 clipped and listed in the header; the measured-points variant is monotone;
    Pcow from a pc_morph.csv in Pa (bar = Pa / 1e5) and in reduced units (x kT/rc^3 from rc_m);
  * the exported tables are read by `mdpore darcy`'s two-phase solve (exit 0).
Usage: check_relperm_fit_cli.py MDPORE WORKDIR"""
import json
import math
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SYNTH = os.path.join(HERE, "..", "..", "validation", "upscale", "relperm_synth.py")
TRUTH = [0.12, 0.18, 0.45, 2.6, 0.9, 1.9]
HEADER = "Sw,Sw_err,krw,krw_err,kro,kro_err,Ca,Snw_connected,Snw_disconnected,pc,pc_err\n"
ROWS = ["0.2,0.002,0.0006,0.003,0.70,0.017,1e-3,0.8,0,,\n",
        "0.3,0.002,0.013,0.003,0.50,0.013,1e-3,0.7,0,,\n",
        "0.4,0.002,0.040,0.004,0.33,0.010,1e-3,0.6,0,,\n",
        "0.5,0.002,0.090,0.005,0.20,0.007,1e-3,0.5,0,,\n",
        "0.6,0.002,0.170,0.006,0.10,0.005,1e-3,0.4,0,,\n",
        "0.7,0.002,0.280,0.009,0.03,0.004,1e-3,0.3,0,,\n",
        "0.78,0.002,0.390,0.011,0.005,0.003,1e-3,0.22,0,,\n"]
GOOD = "# rc_m: 8.2e-10\n" + HEADER + "".join(ROWS)  # data rows start on line 3


def table_with(i, new_row):
    lines = GOOD.splitlines(keepends=True)
    lines[2 + i] = new_row
    return "".join(lines)


BAD_TABLES = [  # (name, content, expected fragments)
    ("nan_krw.csv", table_with(2, "0.4,0.002,nan,0.004,0.33,0.010,1e-3,0.6,0,,\n"),
     ["nan_krw.csv:5", "column 'krw'", "finite", "nan"]),
    ("inf_sw.csv", table_with(1, "inf,0.002,0.013,0.003,0.50,0.013,1e-3,0.7,0,,\n"),
     ["inf_sw.csv:4", "column 'Sw'", "finite", "inf"]),
    ("word.csv", table_with(3, "0.5,0.002,0.090,0.005,lots,0.007,1e-3,0.5,0,,\n"),
     ["word.csv:6", "column 'kro'", "expected a number", "'lots'"]),
    ("negative_kr.csv", table_with(4, "0.6,0.002,0.170,0.006,-0.05,0.005,1e-3,0.4,0,,\n"),
     ["negative_kr.csv:7", "column 'kro'", ">= 0", "-0.05", "10.0 errors below 0"]),
    ("negative_no_err.csv", table_with(4, "0.6,0.002,-0.01,,0.10,0.005,1e-3,0.4,0,,\n"),
     ["negative_no_err.csv:7", "column 'krw'", ">= 0", "-0.01", "no standard error"]),
    ("negative_err.csv", table_with(0, "0.2,0.002,0.0006,-0.003,0.70,0.017,1e-3,0.8,0,,\n"),
     ["negative_err.csv:3", "column 'krw_err'", ">= 0", "-0.003"]),
    ("sw_above_one.csv", table_with(6, "1.2,0.002,0.390,0.011,0.005,0.003,1e-3,0.22,0,,\n"),
     ["sw_above_one.csv:9", "column 'Sw'", "[0, 1]", "1.2"]),
    ("unsorted.csv", table_with(3, "0.35,0.002,0.090,0.005,0.20,0.007,1e-3,0.5,0,,\n"),
     ["unsorted.csv:6", "column 'Sw'", "sorted", "0.35 after 0.4"]),
    ("short_row.csv", table_with(2, "0.4,0.002,0.040,0.004,0.33\n"),
     ["short_row.csv:5", "expected 11", "(got 5)"]),
    ("no_kro.csv", GOOD.replace("kro,kro_err", "k_oil,kro_err"),
     ["no_kro.csv:2", "header", "'kro'"]),
    ("no_rows.csv", "# rc_m: 8.2e-10\n" + HEADER,
     ["no_rows.csv", "expected rows after the header"]),
]
# too few rows for the law asked for: --law corey refused (exit 3), naming why
FEW_ROWS = ("few_rows.csv", "# rc_m: 8.2e-10\n" + HEADER + "".join(ROWS[:3]),
            ["few_rows.csv", "--law corey refused", "6 kr points",
             "cannot fit the 6 free parameters of the corey law"])


def run(args, expect_rc=0, what=""):
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != expect_rc:
        sys.exit(f"FAIL {what}: exit {r.returncode}, expected {expect_rc}: {' '.join(args)}\n"
                 f"{r.stdout}{r.stderr}")
    return r.stdout + r.stderr


def read_swof(path):
    text = open(path).read()
    body = text.split("\nSWOF\n", 1)
    if len(body) != 2:
        sys.exit(f"FAIL: {path}: no SWOF keyword line")
    rows = []
    for line in body[1].splitlines():
        s = line.strip()
        if s.startswith("--") or not s:
            continue
        if s == "/":
            break
        rows.append([float(v) for v in s.split()])
    if not text.rstrip().endswith("/"):
        sys.exit(f"FAIL: {path}: not closed by '/'")
    return text, rows


def check_swof_shape(path, rows):
    sw, krw, krow = [r[0] for r in rows], [r[1] for r in rows], [r[2] for r in rows]
    ok = (all(b > a for a, b in zip(sw, sw[1:])) and all(b >= a for a, b in zip(krw, krw[1:]))
          and all(b <= a for a, b in zip(krow, krow[1:])) and krw[0] == 0.0 and krow[-1] == 0.0
          and all(0.0 <= v <= 1.0 for v in krw + krow) and all(len(r) == 4 for r in rows))
    if not ok:
        sys.exit(f"FAIL: {path}: rows not strictly increasing in Sw, monotone in kr with krw = 0 "
                 "first and krow = 0 last, kr in [0, 1]")


DARCY = """units: SI
grid: {{cells: [40, 1], size: [1.0, 0.01]}}
boundary:
  x-: {{pressure: 2.0e5}}
  x+: {{pressure: 1.0e5}}
laws:
  uniform: {{law: darcy, k: 1 D}}
twophase:
  mu_w: 1.0e-3
  mu_o: 2.0e-3
  porosity: 0.2
  relperm: {{table: {swof}}}
  injection: {{face: x-, rate: 1.0e-5}}
  end_time: 40
  output: {{history: {swof}.history.csv}}
"""


def darcy_reads(mdpore, work, swof):
    cfg = os.path.join(work, os.path.basename(swof) + ".yaml")
    with open(cfg, "w") as f:
        f.write(DARCY.format(swof=os.path.basename(swof)))
    run([mdpore, "darcy", cfg], 0, f"mdpore darcy on {swof}")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    mdpore, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    # refusals
    for name, content, frags in BAD_TABLES:
        path = os.path.join(work, name)
        with open(path, "w") as f:
            f.write(content)
        out = run([mdpore, "fit", "relperm", path, "--quiet"], 1, name)
        missing = [s for s in frags if s not in out]
        if missing:
            sys.exit(f"FAIL {name}: message lacks {missing}:\n{out}")
    name, content, frags = FEW_ROWS
    path = os.path.join(work, name)
    with open(path, "w") as f:
        f.write(content)
    out = run([mdpore, "fit", "relperm", path, "--law", "corey", "--quiet"], 3, name)
    missing = [s for s in frags if s not in out]
    if missing:
        sys.exit(f"FAIL {name}: message lacks {missing}:\n{out}")
    good = os.path.join(work, "good.csv")
    with open(good, "w") as f:
        f.write(GOOD)
    out = run([mdpore, "fit", "relperm", good, "--law", "brooks"], 2, "--law brooks")
    if "--law: expected auto, corey or let (got 'brooks')" not in out:
        sys.exit(f"FAIL --law brooks: {out}")
    out = run([mdpore, "fit", "relperm", good, "--swof", good], 1, "--swof over the table")
    if "would overwrite" not in out:
        sys.exit(f"FAIL --swof over the table: {out}")
    bad_pc = os.path.join(work, "bad_pc.csv")
    with open(bad_pc, "w") as f:
        f.write("# pc\nradius_vox,Sw,Snw\n4,0.5,0.5\n3,0.3,0.7\n")
    out = run([mdpore, "fit", "relperm", good, "--swof", os.path.join(work, "x.swof"),
               "--pc-morph", bad_pc, "--quiet"], 1, "pc without a pc column")
    if "bad_pc.csv:2" not in out or "'pc_Pa' or 'pc'" not in out:
        sys.exit(f"FAIL bad pc_morph: {out}")
    # noise-level negative kr (within 3 errors) and a point without an error are accepted
    lenient = os.path.join(work, "lenient.csv")
    with open(lenient, "w") as f:
        f.write(table_with(0, "0.2,0.002,-0.004,0.003,0.70,,1e-3,0.8,0,,\n"))
    out = run([mdpore, "fit", "relperm", lenient], 0, "lenient table")
    if "left out (no error to weight them): 0 krw and 1 kro point(s)" not in out:
        sys.exit(f"FAIL lenient table: the point without an error is not reported left out:\n{out}")
    print(f"refusals: {len(BAD_TABLES)} bad tables, a bad option, an output over the input, "
          "a bad Pc curve; noise-level negative kr accepted")

    # recovery of a synthetic Corey table
    synth = os.path.join(work, "synthetic.csv")
    run([sys.executable, SYNTH, synth, "--rows", "16"], 0, "relperm_synth.py")
    swof, js = os.path.join(work, "synthetic.swof"), os.path.join(work, "synthetic.fit.json")
    run([mdpore, "fit", "relperm", synth, "--swof", swof, "--json", js, "--quiet"], 0, "fit")
    fit = json.load(open(js))
    if fit["choice"]["law"] != "corey":
        sys.exit(f"FAIL: Corey data, {fit['choice']['law']} chosen: {fit['choice']['test']}")
    corey = [f for f in fit["fits"] if f["law"] == "corey"][0]
    for name, true in zip(["swc", "sor", "krw_max", "nw", "kro_max", "no"], TRUTH):
        p = corey["params"][name]
        z = (p["value"] - true) / p["se_inflated"]
        print(f"  {name:8s} true {true:<6g} fitted {p['value']:.4g} +- {p['se_inflated']:.2g} "
              f"({z:+.2f} sigma)")
        if abs(z) > 3.0 or p["at_bound"]:
            sys.exit(f"FAIL: {name} = {p['value']:.4g} +- {p['se_inflated']:.2g}, true {true}")
    text, rows = read_swof(swof)
    check_swof_shape(swof, rows)
    for frag in ["source: " + synth, "law: corey:", "units: METRIC", "Pcow: 0 on every row",
                 "kr > 1 policy: kr is clipped to 1 (none was above 1 here)"]:
        if frag not in text:
            sys.exit(f"FAIL: {swof} header lacks '{frag}'")
    darcy_reads(mdpore, work, swof)
    print(f"synthetic Corey table: parameters within 3 sigma, {len(rows)} SWOF rows, read by darcy")

    # kr > 1: the clipped rows are those where the fitted law exceeds 1, listed in the header
    lub = os.path.join(work, "lubricated.csv")
    run([sys.executable, SYNTH, lub, "--rows", "16", "--corey", "0.12", "0.18", "0.45", "2.6",
         "1.25", "1.9"], 0, "relperm_synth.py")
    swof_l, js_l = os.path.join(work, "lubricated.swof"), os.path.join(work, "lubricated.json")
    pc_pa = os.path.join(work, "pc_morph_pa.csv")
    with open(pc_pa, "w") as f:  # drainage order (decreasing Sw), Pc falls with Sw
        f.write("# test curve\nradius_vox,radius_rc,Sw,Snw,pc,pc_Pa\n")
        for k, sw in enumerate([0.9, 0.7, 0.5, 0.3, 0.15]):
            f.write(f"{10 - k},{5 - k / 2},{sw},{1 - sw},{0.1 * (k + 1)},{2.0e4 * (k + 1)}\n")
    run([mdpore, "fit", "relperm", lub, "--swof", swof_l, "--json", js_l, "--pc-morph", pc_pa,
         "--quiet"], 0, "lubricated fit")
    fit_l = json.load(open(js_l))
    law = [f for f in fit_l["fits"] if f["law"] == fit_l["choice"]["law"]][0]
    text, rows = read_swof(swof_l)
    check_swof_shape(swof_l, rows)
    listed = re.findall(r"--\s+row (\d+): Sw = ([0-9.]+)\s+krw [0-9.e+-]+ -> [0-9.e+-]+\s+krow "
                        r"([0-9.e+-]+) -> 1", text)
    over = fit_l["swof"]["clipped_rows"]
    if not (over > 0 and len(listed) == over and all(float(k) > 1.0 for _, _, k in listed)):
        sys.exit(f"FAIL: {swof_l}: {over} clipped rows reported, {len(listed)} listed:\n{text}")
    if law["params"]["kro_max"]["value"] <= 1.0:
        sys.exit("FAIL: lubricated table fitted kro_max <= 1")
    for r in rows:  # Pcow in bar from pc_Pa, interpolated in Sw, constant beyond the ends
        sws, pcs = [0.15, 0.3, 0.5, 0.7, 0.9], [1.0e5, 0.8e5, 0.6e5, 0.4e5, 0.2e5]
        want = min(max(r[0], sws[0]), sws[-1])
        for i in range(4):
            if sws[i] <= want <= sws[i + 1]:
                want = pcs[i] + (pcs[i + 1] - pcs[i]) * (want - sws[i]) / (sws[i + 1] - sws[i])
                break
        if abs(r[3] - want / 1e5) > 1e-6:
            sys.exit(f"FAIL: {swof_l}: Pcow {r[3]} at Sw = {r[0]}, expected {want / 1e5} bar")
    darcy_reads(mdpore, work, swof_l)
    print(f"kro_max = 1.25: {over} rows clipped and listed (peak "
          f"{fit_l['swof']['kr_peak_unclipped']:.3f}), Pcow in bar from pc_Pa, read by darcy")

    # reduced Pc (pc_Pa empty, as mdpore image drainage writes it without a voxel size):
    # x kT/rc^3, rc = 8.2e-10 m, T = 298 K; the Sw = 1 rows below the entry pressure merge into one
    pc_red = os.path.join(work, "pc_morph_reduced.csv")
    with open(pc_red, "w") as f:
        f.write("# pc_Pa: empty\nstep,radius_vox,radius_rc,Sw,Snw,trapped,nw_spans,pc,pc_depleted,"
                "pc_Pa,pc_depleted_Pa,J\n")
        for k, (sw, pc) in enumerate([(1.0, 0.05), (1.0, 0.08), (0.8, 0.1), (0.2, 0.5)]):
            f.write(f"{k},{4 - k},{2 - k / 2},{sw},{1 - sw},0,0,{pc},,,,\n")
    # rc stated in words, as mdpore relperm's definitions line does, instead of "# rc_m: ..."
    synth_words = os.path.join(work, "synthetic_rc_words.csv")
    with open(synth_words, "w") as f:
        f.write(open(synth).read().replace(
            "# rc_m: 8.2e-10", "# G = n g = 0.06 (body force g = 0.01); rc = 8.2e-10 m; "
            "rc_per_voxel 0.5"))
    swof_r = os.path.join(work, "reduced.swof")
    run([mdpore, "fit", "relperm", synth_words, "--swof", swof_r, "--pc-morph", pc_red,
         "--swof-points", "measured", "--quiet"], 0, "measured + reduced pc")
    text, rows = read_swof(swof_r)
    check_swof_shape(swof_r, rows)
    scale = 1.380649e-23 * 298 / (8.2e-10) ** 3 / 1e5  # bar per reduced pressure unit
    first = min(max(rows[0][0], 0.2), 0.8)
    want = (0.5 + (0.1 - 0.5) * (first - 0.2) / 0.6) * scale
    # the header's comment lines wrap at a width that depends on the paths they name: the phrases
    # are searched with its line breaks joined
    flat = text.replace("\n-- ", " ")
    if (not math.isclose(rows[0][3], want, rel_tol=1e-6) or "rows: the 16 measured points" not in flat
            or not math.isclose(rows[-1][3], 0.08 * scale, rel_tol=1e-6)
            or "1 row(s) of equal Sw merged" not in flat):
        sys.exit(f"FAIL: {swof_r}: first Pcow {rows[0][3]}, expected {want} bar\n{text}")
    darcy_reads(mdpore, work, swof_r)
    print(f"measured points: {len(rows)} monotone rows; reduced Pc x {scale:.4g} bar; read by darcy")
    print("passed")


if __name__ == "__main__":
    main()
