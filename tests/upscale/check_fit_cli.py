#!/usr/bin/env python3
"""`mdpore fit` at the command line:
* the seeded Darcy table cases/upscale/darcy_forcing_sweep.csv: Forchheimer's beta is at its bound 0,
  flagged in the text and the JSON ("at_bound": true), and Darcy is chosen;
* degenerate tables (one row, one gradient, gradients equal up to rounding, all fluxes equal, no flux)
  and duplicated metadata keys are refused with exit code 1 and a message naming the file and what
  was expected, and no JSON is written;
* nothing printed or written ever contains nan or inf.
Usage: check_fit_cli.py MDPORE CASES_DIR WORKDIR"""
import json
import os
import re
import shutil
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
GOOD = "1e6,1e-9,1e-11,1000\n2e6,2.1e-9,1e-11,1000\n3e6,2.9e-9,1e-11,1000\n4e6,4e-9,1e-11,1000\n"

TWO_PAR = "the threshold, forchheimer and power laws have 2 parameters"
REFUSED = [  # (name, content, extra arguments, expected fragments of the message)
    ("one_row.csv", HEAD + COLS + "1e6,1e-9,1e-11,1000\n", [],
     ["one_row.csv:", "1 data row,", "at least 3"]),
    ("one_gradient.csv", HEAD + COLS + "1e6,1e-9,1e-11,1000\n1e6,1.02e-9,1e-11,1000\n"
     "1e6,0.99e-9,1e-11,1000\n1e6,1.01e-9,1e-11,1000\n", [],
     ["one_gradient.csv: one gradient", "|G| = 1e+06", TWO_PAR,
      "expected at least 2 distinct gradients", "--models darcy"]),
    ("zero_variance.csv", HEAD + COLS + "1e6,1e-9,1e-11,1000\n1.0000000000000002e6,1.02e-9,1e-11,1000\n"
     "1.0000000000000005e6,0.99e-9,1e-11,1000\n", [],
     ["zero_variance.csv: zero variance in the pressure_gradient column", TWO_PAR,
      "expected at least 2 gradients that differ by more than 1e-09 relative"]),
    ("equal_flux.csv", HEAD + COLS + "1e6,1e-9,1e-11,1000\n2e6,1e-9,1e-11,1000\n"
     "3e6,1e-9,1e-11,1000\n4e6,1e-9,1e-11,1000\n", [],
     ["equal_flux.csv: all 4 darcy_velocity values are equal (q = 1e-09)",
      "expected fluxes that change with pressure_gradient"]),
    ("equal_flux_darcy.csv", HEAD + COLS + "1e6,1e-9,1e-11,1000\n2e6,1e-9,1e-11,1000\n", ["--models", "darcy"],
     ["equal_flux_darcy.csv: all 2 darcy_velocity values are equal"]),
    ("no_flux.csv", HEAD + COLS + "1e6,0,1e-11,1000\n2e6,0,1e-11,1000\n3e6,0,1e-11,1000\n", [],
     ["no_flux.csv: every darcy_velocity value is 0", "expected fluxes that change"]),
    ("no_gradient.csv", HEAD + COLS + "0,1e-9,1e-11,1000\n0,2e-9,1e-11,1000\n0,3e-9,1e-11,1000\n", [],
     ["no_gradient.csv: every pressure_gradient value is 0", "expected at least 2 distinct non-zero"]),
    ("dup_key.csv", HEAD + "# viscosity: 4e-3\n" + COLS + GOOD, [],
     ["dup_key.csv:7: key 'viscosity' given again (first at line 5)"]),
    ("dup_key_rows.csv", HEAD + COLS + "1e6,1e-9,1e-11,1000\n# density : 10\n" + GOOD, [],
     ["dup_key_rows.csv:9: key 'density' given again (first at line 6)"]),
]
ACCEPTED = [  # (name, content, extra arguments): must fit, exit 0
    ("one_gradient_darcy.csv", REFUSED[1][1], ["--models", "darcy"]),
    ("good.csv", HEAD + COLS + GOOD, []),
]

NONFINITE = re.compile(r"nan|inf", re.IGNORECASE)


def run(mdpore, args, cwd):
    return subprocess.run([mdpore, "fit"] + args, cwd=cwd, capture_output=True, text=True)


def main():
    mdpore, cases, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    failures = 0

    def check(ok, what):
        nonlocal failures
        failures += not ok
        print("%-4s %s" % ("ok" if ok else "FAIL", what))

    # at its bound: beta of the Darcy table
    shutil.copy(os.path.join(cases, "darcy_forcing_sweep.csv"), work)
    r = run(mdpore, ["darcy_forcing_sweep.csv"], work)
    print(r.stdout + r.stderr)
    check(r.returncode == 0, "darcy_forcing_sweep.csv: exit 0 (got %d)" % r.returncode)
    check("beta = 0 (at its bound >= 0: the data do not support this term)" in r.stdout,
          "text: beta flagged at its bound")
    check("not eligible: beta at its bound" in r.stdout, "text: forchheimer not eligible, and why")
    check("chosen by BIC: darcy" in r.stdout, "text: darcy chosen")
    check(not NONFINITE.search(r.stdout + r.stderr), "text: no nan or inf")
    path = os.path.join(work, "darcy_forcing_sweep.csv.fit.json")
    text = open(path).read() if os.path.exists(path) else ""
    check(not NONFINITE.search(text), "JSON: no nan or inf")
    fit = json.loads(text) if text else {"models": []}
    forch = [m for m in fit["models"] if m["law"] == "forchheimer"]
    beta = forch[0]["parameters"]["beta"] if forch and "parameters" in forch[0] else {}
    check(beta.get("at_bound") is True and beta.get("bound") == 0 and
          beta.get("bound_side") == "lower", "JSON: beta at_bound true, bound 0, lower")
    check(all(p["at_bound"] is False for m in fit["models"] if m["law"] != "forchheimer"
              for p in m["parameters"].values()), "JSON: no other parameter at a bound")
    check(forch and forch[0].get("eligible") is False and "darcy" in forch[0].get("not_eligible_why", ""),
          "JSON: forchheimer not eligible, naming darcy")
    check(fit.get("chosen") == "darcy", "JSON: chosen darcy (got %s)" % fit.get("chosen"))

    for name, content, extra, expected in REFUSED:
        with open(os.path.join(work, name), "w") as f:
            f.write(content)
        r = run(mdpore, [name] + extra, work)
        out = r.stdout + r.stderr
        missing = [e for e in expected if e not in r.stderr]
        json_written = os.path.exists(os.path.join(work, name + ".fit.json"))
        msg = r.stderr.strip().splitlines()[0] if r.stderr.strip() else "(no message)"
        check(r.returncode == 1 and not missing and not NONFINITE.search(out) and not json_written,
              "%s refused: rc=%d%s%s | %s" % (name, r.returncode,
                                             (" missing " + str(missing)) if missing else "",
                                             " (wrote a JSON)" if json_written else "", msg))

    for name, content, extra in ACCEPTED:
        with open(os.path.join(work, name), "w") as f:
            f.write(content)
        r = run(mdpore, [name] + extra, work)
        path = os.path.join(work, name + ".fit.json")
        text = open(path).read() if os.path.exists(path) else ""
        check(r.returncode == 0 and text and not NONFINITE.search(r.stdout + r.stderr + text),
              "%s %s: fitted, no nan or inf (rc=%d) %s" % (name, " ".join(extra), r.returncode,
                                                         r.stderr.strip()))
    # an output that names the input is refused and the table is left as it was
    before = open(os.path.join(work, "darcy_forcing_sweep.csv")).read()
    for extra in (["--json", "darcy_forcing_sweep.csv"], ["--json", "./darcy_forcing_sweep.csv"],
                  ["--json", "same.json", "--plot", "same.json"]):
        r = run(mdpore, ["darcy_forcing_sweep.csv"] + extra, work)
        after = open(os.path.join(work, "darcy_forcing_sweep.csv")).read()
        check(r.returncode == 1 and extra[1] in r.stderr and "--json" in r.stderr and after == before,
              "%s refused, table unchanged: rc=%d | %s" % (" ".join(extra), r.returncode, r.stderr.strip()))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
