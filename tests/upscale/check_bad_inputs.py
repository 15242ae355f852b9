#!/usr/bin/env python3
"""Bad tables and configs must fail with a non-zero exit and a message naming the file, the row/line
and the column/key. Usage: check_bad_inputs.py MDPORE WORKDIR"""
import os
import subprocess
import sys

HEAD = """# sample: s
# axis: x
# unit_system: SI
# length_unit: m
# viscosity: 1e-3
# density: 1000
"""
COLS = "pressure_gradient,darcy_velocity,darcy_velocity_stderr,run_length\n"
ROWS = "1e6,1e-9,1e-11,1000\n2e6,2e-9,1e-11,1000\n3e6,3e-9,1e-11,1000\n"

TABLES = [  # (name, content, expected fragments of the message)
    ("missing_col.csv", HEAD + "pressure_gradient,darcy_velocity,run_length\n1,1,1\n",
     ["missing_col.csv:7", "darcy_velocity_stderr"]),
    ("non_numeric.csv", HEAD + COLS + "1e6,1e-9,1e-11,1000\n2e6,abc,1e-11,1000\n",
     ["non_numeric.csv:9", "column 2 'darcy_velocity'", "'abc'"]),
    ("negative_err.csv", HEAD + COLS + ROWS + "4e6,4e-9,-1e-11,1000\n",
     ["negative_err.csv:11", "column 3 'darcy_velocity_stderr'", "positive"]),
    ("too_few.csv", HEAD + COLS + "1e6,1e-9,1e-11,1000\n2e6,2e-9,1e-11,1000\n",
     ["too_few.csv", "2 data rows", "at least 3"]),
    ("no_viscosity.csv", HEAD.replace("# viscosity: 1e-3\n", "") + COLS + ROWS,
     ["no_viscosity.csv", "viscosity"]),
    ("bad_units.csv", HEAD.replace("SI", "imperial") + COLS + ROWS,
     ["bad_units.csv:3", "unit_system", "imperial"]),
    ("ragged.csv", HEAD + COLS + "1e6,1e-9,1e-11\n", ["ragged.csv:8", "expected 4"]),
]

GOOD_CFG = """units: SI
grid: {cells: [4, 3], size: [1.0, 1.0]}
fluid: {viscosity: 1.0e-3, density: 1000}
boundary:
  x-: {pressure: 2.0}
  x+: {pressure: 1.0}
laws:
  uniform: {law: darcy, k: 1.0e-15}
output: {json: out.json}
"""
CONFIGS = [
    ("unknown_key.yaml", GOOD_CFG.replace("fluid: {", "fluid: {viscosty: 1, "),
     ["unknown_key.yaml:3", "viscosty"]),
    ("bad_number.yaml", GOOD_CFG.replace("k: 1.0e-15", "k: lots"),
     ["bad_number.yaml:8", "'laws.uniform.k'", "lots"]),
    ("bad_law.yaml", GOOD_CFG.replace("law: darcy", "law: magic"), ["bad_law.yaml:8", "magic"]),
    ("neg_k.yaml", GOOD_CFG.replace("k: 1.0e-15", "k: -1.0e-15"), ["neg_k.yaml:8", "k > 0"]),
    ("no_boundary.yaml", GOOD_CFG.replace("  x-: {pressure: 2.0}\n  x+: {pressure: 1.0}\n", "  {}\n"),
     ["no_boundary.yaml", "fixed pressure"]),
    ("bad_layers.yaml", GOOD_CFG.replace(
        "  uniform: {law: darcy, k: 1.0e-15}",
        "  layers: {axis: x, list: [{cells: 3, law: darcy, k: 1.0e-15}]}"),
     ["bad_layers.yaml:8", "cover 3 cells", "4"]),
    ("bad_cells.yaml", GOOD_CFG.replace("cells: [4, 3]", "cells: [4, 0]"),
     ["bad_cells.yaml:2", "cells", "positive integer"]),
    ("missing_fit.yaml", GOOD_CFG.replace("{law: darcy, k: 1.0e-15}", "{fit: nowhere.fit.json}"),
     ["missing_fit.yaml:8", "nowhere.fit.json", "cannot open"]),
    ("diag_missing_axis.yaml", GOOD_CFG.replace("{law: darcy, k: 1.0e-15}",
                                                "{x: {law: darcy, k: 1.0e-15}}"),
     ["diag_missing_axis.yaml:8", "'laws.uniform.y'", "a law along each of x and y"]),
    ("diag_z_in_2d.yaml", GOOD_CFG.replace(
        "{law: darcy, k: 1.0e-15}",
        "{x: {law: darcy, k: 1.0e-15}, y: {law: darcy, k: 1.0e-15}, z: {law: darcy, k: 1.0e-15}}"),
     ["diag_z_in_2d.yaml:8", "'laws.uniform.z'", "unknown key"]),
    ("diag_mixed.yaml", GOOD_CFG.replace("{law: darcy, k: 1.0e-15}",
                                         "{law: darcy, k: 1.0e-15, y: {law: darcy, k: 1.0e-15}}"),
     ["diag_mixed.yaml:8", "'laws.uniform.law'", "unknown key", "x, y"]),
    ("diag_bad_k.yaml", GOOD_CFG.replace(
        "{law: darcy, k: 1.0e-15}",
        "{x: {law: darcy, k: 1.0e-15}, y: {law: darcy, k: -2}}"),
     ["diag_bad_k.yaml:8", "'laws.uniform.y'", "k > 0"]),
    ("yaml_syntax.yaml", GOOD_CFG.replace("grid: {", "grid: {{"), ["yaml_syntax.yaml", "syntax"]),
]


def run(cmd, cwd):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)


def main():
    mdpore, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    failures = 0
    cases = [("fit", n, c, e) for n, c, e in TABLES] + [("darcy", n, c, e) for n, c, e in CONFIGS]
    for cmd, name, content, expected in cases:
        with open(os.path.join(work, name), "w") as f:
            f.write(content)
        r = run([mdpore, cmd, name], work)
        msg = r.stderr.strip().splitlines()[0] if r.stderr.strip() else "(no message)"
        missing = [e for e in expected if e not in r.stderr]
        ok = r.returncode != 0 and not missing
        failures += not ok
        print("%-4s %-18s rc=%d %s | %s" % ("ok" if ok else "FAIL", name, r.returncode,
                                           ("missing " + str(missing)) if missing else "", msg))
    # the good config must pass (guards against a check that rejects everything)
    with open(os.path.join(work, "good.yaml"), "w") as f:
        f.write(GOOD_CFG)
    r = run([mdpore, "darcy", "good.yaml", "--quiet"], work)
    print("%-4s good.yaml rc=%d %s" % ("ok" if r.returncode == 0 else "FAIL", r.returncode, r.stderr))
    failures += r.returncode != 0
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
