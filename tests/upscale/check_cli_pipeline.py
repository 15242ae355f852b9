#!/usr/bin/env python3
"""End to end: `mdpore fit` on the example table (synthetic Forchheimer data, truth k = 0.05,
beta = 60) must choose Forchheimer and recover k and beta within 2 standard errors, write a PNG; then
`mdpore darcy` on a config that uses the fit must give the same result with 1 and 2 MPI ranks.
Usage: check_cli_pipeline.py MDPORE MPIEXEC CASES_DIR WORKDIR"""
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np


def run(cmd, cwd):
    r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)
    print("$", " ".join(cmd), "-> rc", r.returncode)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        sys.exit(1)
    return r


def main():
    mdpore, mpiexec, cases, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    shutil.copytree(cases, work)
    run([mdpore, "fit", "shale_forcing_sweep.csv", "--plot", "fit.png"], work)
    fit = json.load(open(os.path.join(work, "shale_forcing_sweep.csv.fit.json")))
    failures = 0
    forch = [m for m in fit["models"] if m["law"] == "forchheimer"][0]
    for name, truth in (("k", 0.05), ("beta", 60.0)):
        p = forch["parameters"][name]
        z = (p["value"] - truth) / p["stderr"]
        print("forchheimer %s = %.4g +- %.2g (truth %g, z = %.2f)" % (name, p["value"], p["stderr"],
                                                                     truth, z))
        failures += abs(z) > 2
    print("chosen:", fit["chosen"])
    failures += fit["chosen"] != "forchheimer"
    failures += not os.path.getsize(os.path.join(work, "fit.png")) > 1000
    results = {}
    for np_ in (1, 2):
        run([mpiexec, "-n", str(np_), "--oversubscribe", mdpore, "darcy", "from_fit_3d.yaml", "--quiet"],
            work)
        with h5py.File(os.path.join(work, "from_fit_3d.h5"), "r") as h:
            results[np_] = (h["pressure"][...], h["block_gradient"][...])
        summary = json.load(open(os.path.join(work, "from_fit_3d.json")))
        print("np=%d k_eff_x = %.10g mass balance %.1e" % (
            np_, summary["effective_permeability"]["x"], summary["mass_balance_relative_error"]))
        failures += not summary["solver"]["converged"] or summary["mass_balance_relative_error"] > 1e-8
    dp = np.max(np.abs(results[1][0] - results[2][0])) / 40.0
    dg = np.max(np.abs(results[1][1] - results[2][1])) / (40.0 / 120.0)
    print("np1 vs np2: max pressure difference %.2e, max gradient difference %.2e (relative to the "
          "applied drop / gradient)" % (dp, dg))
    failures += not (dp < 1e-9 and dg < 1e-8)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
