#!/usr/bin/env python3
"""`mdpore fit relperm`: a law is a result only when each phase follows it within its errors
(docs/relperm.md section 5, "When no law fits").
  accept: a table drawn from a Corey law with Gaussian noise of its stated errors (seeded): Corey
          is accepted (krw and kro chi2/dof within 1 + 3 sqrt(2/dof)), every parameter within 3 of
          its standard errors of the law the data came from, the SWOF is the law's grid.
  refuse: tables no law fits: a krw bump far outside its error bars (the rows scatter beyond
          them), a monotone staircase with small errors (the law's shape does not follow it),
          and a table without error columns (chi2 cannot be judged). Each: exit 0, the report
          names chi2/dof and the reason and prints no law parameters, the SWOF is the measured
          points (monotone, end rows at Sw = 0 and 1), said so in its header; --law corey on the
          bump exits 3 and writes no SWOF; --law corey --force exports the law, flagged; --force
          without --law is a usage error (exit 2).
Usage: check_relperm_fit_policy.py MDPORE WORKDIR accept|refuse"""
import json
import math
import os
import random
import subprocess
import sys

TRUTH = {"swc": 0.12, "sor": 0.18, "krw_max": 0.45, "nw": 2.6, "kro_max": 0.9, "no": 1.9}
SW = [0.20 + 0.05 * i for i in range(12)]  # 0.20 .. 0.75


def corey(sw):
    se = min(max((sw - TRUTH["swc"]) / (1 - TRUTH["swc"] - TRUTH["sor"]), 0.0), 1.0)
    return TRUTH["krw_max"] * se ** TRUTH["nw"], TRUTH["kro_max"] * (1 - se) ** TRUTH["no"]


def err_of(kr):
    return 0.02 * kr + 0.003


def write_table(path, rows, errors=True):
    with open(path, "w") as f:
        f.write("# synthetic table of check_relperm_fit_policy.py\n")
        f.write("Sw,krw,krw_err,kro,kro_err\n" if errors else "Sw,krw,kro\n")
        for sw, krw, ew, kro, eo in rows:
            f.write(f"{sw:.6f},{krw:.8f},{ew:.8f},{kro:.8f},{eo:.8f}\n" if errors
                    else f"{sw:.6f},{krw:.8f},{kro:.8f}\n")


def noisy_rows(seed):
    rnd = random.Random(seed)
    rows = []
    for sw in SW:
        w, o = corey(sw)
        ew, eo = err_of(w), err_of(o)
        rows.append((sw, w + rnd.gauss(0, ew), ew, o + rnd.gauss(0, eo), eo))
    return rows


def run(args, expect_rc, what):
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != expect_rc:
        sys.exit(f"FAIL {what}: exit {r.returncode}, expected {expect_rc}: {' '.join(args)}\n"
                 f"{r.stdout}{r.stderr}")
    return r.stdout + r.stderr


def read_swof(path):
    text = open(path).read()
    head, body = text.split("\nSWOF\n", 1)
    rows = []
    for line in body.splitlines():
        s = line.strip()
        if s == "/":
            break
        if s and not s.startswith("--"):
            rows.append([float(v) for v in s.split()])
    return head, rows


def check_monotone(path, rows):
    sw, krw, krow = ([r[k] for r in rows] for k in range(3))
    if not (all(len(r) == 4 for r in rows) and all(b > a for a, b in zip(sw, sw[1:]))
            and all(b >= a for a, b in zip(krw, krw[1:])) and all(b <= a for a, b in zip(krow, krow[1:]))
            and krw[0] == 0 and krow[-1] == 0 and all(0 <= v <= 1 for v in krw + krow)
            and 0 <= sw[0] and sw[-1] <= 1):
        sys.exit(f"FAIL {path}: SWOF rows not valid (4 columns, Sw increasing in [0, 1], krw "
                 f"non-decreasing from 0, krow non-increasing to 0, kr in [0, 1]): {rows}")


def accept(mdpore, work):
    table = os.path.join(work, "corey_noise.csv")
    write_table(table, noisy_rows(20261129))
    swof, js = table + ".swof", table + ".json"
    out = run([mdpore, "fit", "relperm", table, "--swof", swof, "--json", js], 0, "accept")
    fit = json.load(open(js))
    if fit["choice"]["law"] != "corey":
        sys.exit(f"FAIL accept: law {fit['choice']['law']}, expected corey:\n{out}")
    cf = [f for f in fit["fits"] if f["law"] == "corey"][0]
    for ph in ("krw", "kro"):
        c = cf["check"][ph]
        if c["verdict"] != "passes" or not c["chi2_dof"] <= c["chi2_dof_max"]:
            sys.exit(f"FAIL accept: {ph} check {c}")
        print(f"accept: {c['text']}")
    for name, truth in TRUTH.items():
        p = cf["params"][name]
        z = abs(p["value"] - truth) / p["se_inflated"] if p["se_inflated"] > 0 else math.inf
        print(f"accept: {name} = {p['value']:.4g} +- {p['se_inflated']:.2g} (truth {truth}, "
              f"{z:.2f} errors)")
        if not z <= 3:
            sys.exit(f"FAIL accept: {name} {p['value']} +- {p['se_inflated']} is {z:.1f} errors "
                     f"from {truth}")
    head, rows = read_swof(swof)
    check_monotone(swof, rows)
    if "MEASURED POINTS" in head or "law: corey:" not in head:
        sys.exit(f"FAIL accept: the SWOF is not the accepted law's grid:\n{head}")
    if "krw_max" not in out:
        sys.exit(f"FAIL accept: the accepted law's parameters are not printed:\n{out}")


def refused_case(mdpore, work, name, rows, errors, reasons):
    table = os.path.join(work, name + ".csv")
    write_table(table, rows, errors)
    swof, js = table + ".swof", table + ".json"
    out = run([mdpore, "fit", "relperm", table, "--swof", swof, "--json", js], 0, name)
    fit = json.load(open(js))
    missing = [s for s in ["no law", *reasons] if s not in out.lower() and s not in out]
    if fit["choice"]["law"] is not None or missing:
        sys.exit(f"FAIL {name}: law {fit['choice']['law']} (expected none), report lacks "
                 f"{missing}:\n{out}")
    for p in ("krw_max", "kro_max", " nw ", " Lw "):
        if p in out:
            sys.exit(f"FAIL {name}: the report prints the refused law's parameter '{p}':\n{out}")
    head, srows = read_swof(swof)
    check_monotone(swof, srows)
    if "THE MEASURED POINTS, NOT A LAW" not in head or fit["swof"]["points"] != "measured_no_law":
        sys.exit(f"FAIL {name}: the SWOF header does not say it is the measured points:\n{head}")
    # the measured Sw are rows, with end rows at Sw = 0 (krw 0) and 1 (krow 0)
    sws = [r[0] for r in srows]
    if sws[0] != 0.0 or sws[-1] != 1.0 or any(min(abs(s - r[0]) for s in sws) > 1e-6 for r in rows):
        sys.exit(f"FAIL {name}: SWOF Sw {sws}: expected 0, the measured Sw, 1")
    print(f"{name}: no law; " + "; ".join(l for l in out.splitlines() if l.startswith("result:"))[:600])
    return table


def refuse(mdpore, work):
    base = noisy_rows(20261129)
    bump = [list(r) for r in base]
    bump[5][1] += 0.25  # krw at Sw 0.45: 0.06 -> 0.31 against an error of 0.004, then back down
    table = refused_case(mdpore, work, "bump", [tuple(r) for r in bump], True,
                         ["chi2/dof", "the rows scatter beyond their error bars"])
    # --law corey: refused, exit 3, no SWOF; --force takes it, flagged
    swof = os.path.join(work, "bump_law.swof")
    if os.path.exists(swof):
        os.remove(swof)  # from an earlier run of this test
    out = run([mdpore, "fit", "relperm", table, "--law", "corey", "--swof", swof, "--quiet"], 3,
              "--law corey on the bump")
    if "--law corey refused" not in out or "chi2/dof" not in out or os.path.exists(swof):
        sys.exit(f"FAIL --law corey on the bump: expected a refusal naming chi2/dof and no SWOF:\n{out}")
    out = run([mdpore, "fit", "relperm", table, "--law", "corey", "--force", "--swof", swof], 0,
              "--law corey --force")
    head, srows = read_swof(swof)
    check_monotone(swof, srows)
    if "--force" not in head or "REFUSED" not in out or "krw_max" not in out:
        sys.exit(f"FAIL --force: the SWOF header or the report does not flag the forced law:\n{out}\n{head}")
    out = run([mdpore, "fit", "relperm", table, "--force"], 2, "--force without --law")
    if "--force: expected with --law" not in out:
        sys.exit(f"FAIL --force without --law: {out}")
    stairs = []
    for i, sw in enumerate(SW):  # monotone plateaus: 0, 0.3, 0.8 (krw) with errors of 0.003
        w = 0.0 if i < 4 else 0.3 if i < 8 else 0.8
        o = 0.9 if i < 4 else 0.5 if i < 8 else 0.05
        stairs.append((sw, w, 0.003, o, 0.003))
    refused_case(mdpore, work, "staircase", stairs, True,
                 ["chi2/dof", "the law's shape does not follow the data"])
    refused_case(mdpore, work, "no_errors", base, False, ["chi2 cannot be judged"])


def main():
    if len(sys.argv) != 4 or sys.argv[3] not in ("accept", "refuse"):
        sys.exit(__doc__)
    mdpore, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    (accept if sys.argv[3] == "accept" else refuse)(mdpore, work)
    print("pass")


if __name__ == "__main__":
    main()
