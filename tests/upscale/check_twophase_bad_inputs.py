#!/usr/bin/env python3
"""`mdpore darcy` with a `twophase:` block: bad relative-permeability tables and keys must fail with
exit code 1 and a message naming the file, the line and the key or column; a good config must run.
Usage: check_twophase_bad_inputs.py MDPORE WORKDIR"""
import os
import subprocess
import sys

GOOD_TABLE = """-- Sw krw kro Pc (Eclipse SWOF order)
0.0 0.0 1.0 0.0
0.5 0.25 0.25 0.0
1.0 1.0 0.0 0.0
"""
TABLES = [  # (name, content, expected fragments of the message)
    ("kr_above_one.swof", GOOD_TABLE.replace("0.5 0.25 0.25", "0.5 1.25 0.25"),
     ["kr_above_one.swof:3", "column 2 'krw'", "[0, 1]", "1.25"]),
    ("sw_not_monotone.swof", GOOD_TABLE.replace("0.5 0.25 0.25", "0.0 0.25 0.25"),
     ["sw_not_monotone.swof:3", "'Sw'", "strictly increasing"]),
    ("sw_outside.swof", GOOD_TABLE.replace("1.0 1.0 0.0", "1.2 1.0 0.0"),
     ["sw_outside.swof:4", "'Sw'", "1.2"]),
    ("kro_rising.swof", GOOD_TABLE.replace("0.0 0.0 1.0", "0.0 0.0 0.5").replace("0.5 0.25 0.25", "0.5 0.25 0.8"),
     ["kro_rising.swof:3", "'kro'", "non-increasing"]),
    ("not_numbers.swof", GOOD_TABLE.replace("0.5 0.25 0.25", "0.5 lots 0.25"),
     ["not_numbers.swof:3", "'lots'"]),
]

CFG = """units: SI
grid: {cells: [20, 1], size: [1.0, 0.01]}
boundary:
  x-: {pressure: 2.0e5}
  x+: {pressure: 1.0e5}
laws:
  uniform: {law: darcy, k: 1 D}
twophase:
  mu_w: 1.0e-3
  mu_o: 2.0e-3
  porosity: 0.2
  relperm: RELPERM
  injection: {face: x-, rate: 1.0e-5}
  end_time: 20
  output_times: [10, 20]
  output: {history: h.csv}
"""
COREY = "{corey: {nw: 2, no: 2, swc: 0.1, sor: 0.1}}"
CONFIGS = [  # (name, content, expected fragments)
    ("bad_corey.yaml", CFG.replace("RELPERM", COREY.replace("sor: 0.1", "sor: 0.95")),
     ["bad_corey.yaml:12", "'twophase.relperm.corey.sor'", "0.95"]),
    ("bad_krmax.yaml", CFG.replace("RELPERM", COREY.replace("}}", ", krw_max: 1.5}}")),
     ["bad_krmax.yaml:12", "'twophase.relperm.corey.krw_max'", "(0, 1]", "1.5"]),
    ("bad_initial.yaml", CFG.replace("RELPERM", COREY).replace("  porosity", "  initial_saturation: -0.1\n  porosity"),
     ["bad_initial.yaml:11", "'twophase.initial_saturation'", "-0.1"]),
    ("bad_face.yaml", CFG.replace("RELPERM", COREY).replace("face: x-", "face: y-"),
     ["bad_face.yaml:13", "'twophase.injection.face'", "no-flow"]),
    ("bad_times.yaml", CFG.replace("RELPERM", COREY).replace("[10, 20]", "[10, 30]"),
     ["bad_times.yaml:15", "'twophase.output_times[1]'", "30"]),
    ("bad_fluid.yaml", CFG.replace("RELPERM", COREY).replace("laws:", "fluid: {viscosity: 1e-3}\nlaws:"),
     ["bad_fluid.yaml:6", "'fluid'", "mu_w"]),
    ("bad_mu.yaml", CFG.replace("RELPERM", COREY).replace("mu_o: 2.0e-3", "mu_o: 0"),
     ["bad_mu.yaml:10", "'twophase.mu_o'", "> 0"]),
    # an end time far beyond the work it can take: refused after the first pressure solve
    ("bad_end_time.yaml", CFG.replace("RELPERM", COREY).replace("end_time: 20", "end_time: 1.0e12"),
     ["bad_end_time.yaml", "'twophase.end_time'", "CFL steps"]),
]


def expect_failure(mdpore, cfg, fragments, failures):
    r = subprocess.run([mdpore, "darcy", cfg], capture_output=True, text=True)
    msg = r.stdout + r.stderr
    if r.returncode != 1 or any(f not in msg for f in fragments):
        failures.append(f"{os.path.basename(cfg)}: exit {r.returncode}, expected 1 and {fragments}, "
                        f"got:\n{msg}")


def main():
    mdpore, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    failures = []
    for name, content, fragments in TABLES:
        with open(os.path.join(work, name), "w") as f:
            f.write(content)
        cfg = os.path.join(work, name + ".yaml")
        with open(cfg, "w") as f:
            f.write(CFG.replace("RELPERM", "{table: %s}" % name))
        expect_failure(mdpore, cfg, fragments + ["'twophase.relperm.table'"], failures)
    for name, content, fragments in CONFIGS:
        cfg = os.path.join(work, name)
        with open(cfg, "w") as f:
            f.write(content)
        expect_failure(mdpore, cfg, fragments, failures)
    # the good table runs, and its Pc column draws a note
    with open(os.path.join(work, "good.swof"), "w") as f:
        f.write(GOOD_TABLE.replace("1.0 0.0 0.0\n", "1.0 0.0 5.0\n", 1))
    cfg = os.path.join(work, "good.yaml")
    with open(cfg, "w") as f:
        f.write(CFG.replace("RELPERM", "{table: good.swof}"))
    r = subprocess.run([mdpore, "darcy", cfg], capture_output=True, text=True)
    if r.returncode != 0 or "not used" not in r.stderr:
        failures.append(f"good.yaml: exit {r.returncode}, expected 0 and a note on Pc, got:\n"
                        f"{r.stdout}{r.stderr}")
    for f in failures:
        print("FAIL:", f)
    print(f"{len(TABLES) + len(CONFIGS) + 1 - len(failures)} of {len(TABLES) + len(CONFIGS) + 1} "
          "checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
