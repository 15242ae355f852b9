#!/usr/bin/env python3
"""`mdpore darcy` at the command line: units on config values and HDF5 datasets, shape and
axis-order checks, units on every output, and `--upscale` (tensor in m^2 and mD, 1 and 2 ranks).
Every refusal must exit non-zero with a message naming the config file, the key and what was
expected. Usage: darcy_units_cli.py MDPORE MPIEXEC WORKDIR"""
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

MD = 9.869233e-16
failures = []


def check(ok, what):
    print("%-4s %s" % ("ok" if ok else "FAIL", what))
    if not ok:
        failures.append(what)


def run(cmd, cwd):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True)


def config(body, name, work):
    with open(os.path.join(work, name), "w") as f:
        f.write(body)
    return name


BASE = """units: SI
grid: {cells: [4, 3], size: [SIZE]}
fluid: {viscosity: VISC}
boundary:
  x-: {pressure: P1}
  x+: {pressure: P2}
laws:
  LAWS
output: {json: OUT.json, hdf5: OUT.h5}
"""


def base(out, laws, size="1.0, 0.5", visc="1.0e-3", p1="2.0e6", p2="1.0e6", units="SI"):
    return (BASE.replace("SIZE", size).replace("VISC", visc).replace("P1", p1).replace("P2", p2)
            .replace("LAWS", laws).replace("OUT", "out_" + out).replace("units: SI", "units: " + units))


def keff(work, out, axis="x"):
    res = json.load(open(os.path.join(work, "out_" + out + ".json")))
    return res["effective_permeability"][axis]


def expect_error(work, mdpore, name, body, fragments, extra=()):
    config(body, name, work)
    r = run([mdpore, "darcy", name, "--quiet"] + list(extra), work)
    missing = [f for f in fragments if f not in r.stderr]
    first = r.stderr.strip().splitlines()[0] if r.stderr.strip() else "(no message)"
    check(r.returncode != 0 and not missing,
          "%s refused (rc=%d)%s | %s" % (name, r.returncode,
                                        " missing %s" % missing if missing else "", first))


def units_on_values(mdpore, work):
    config(base("plain", "uniform: {law: darcy, k: 9.869233e-15}"), "plain.yaml", work)
    config(base("units", "uniform: {law: darcy, k: 10 mD}", size="100 cm, 500 mm", visc="1 cP",
                p1="2 MPa", p2="10 bar"), "units.yaml", work)
    for name in ("plain", "units"):
        r = run([mdpore, "darcy", name + ".yaml"], work)
        check(r.returncode == 0, "%s.yaml runs (rc=%d) %s" % (name, r.returncode, r.stderr.strip()))
    k0, k1 = keff(work, "plain"), keff(work, "units")
    check(abs(k1 / (10 * MD) - 1) < 1e-9, "k: 10 mD gives k_eff = %.10g m^2 (10 mD = %.10g m^2)"
          % (k1, 10 * MD))
    check(abs(k1 / k0 - 1) < 1e-9, "units config == plain SI config (%.10g vs %.10g)" % (k1, k0))
    res = json.load(open(os.path.join(work, "out_units.json")))
    check(abs(res["effective_permeability_mD"]["x"] - 10) < 1e-8,
          "JSON effective_permeability_mD.x = %.10g" % res["effective_permeability_mD"]["x"])
    check(res["units"]["permeability"] == "m^2" and res["units"]["pressure"] == "Pa" and
          res["units"]["flow_rate"] == "m^2/s", "JSON units: %s" % res["units"])
    check(abs(res["pressure_max"] - 2e6) < 2e6 and res["pressure_min"] > 1e6 - 1,
          "pressures converted (2 MPa, 10 bar): [%.6g, %.6g] Pa" % (res["pressure_min"],
                                                                    res["pressure_max"]))
    r = run([mdpore, "darcy", "units.yaml"], work)
    check(" m^2 (" in r.stdout and " mD)" in r.stdout and " Pa" in r.stdout,
          "stdout states units: %s" % r.stdout.splitlines()[1].strip())
    with h5py.File(os.path.join(work, "out_units.h5"), "r") as h:
        got = {n: h[n].attrs.get("unit") for n in ("pressure", "flux_x", "block_gradient")}
        got = {n: v.decode() if isinstance(v, bytes) else v for n, v in got.items()}
        order = h["pressure"].attrs.get("axis_order")
        order = order.decode() if isinstance(order, bytes) else order
    check(got == {"pressure": "Pa", "flux_x": "m^2/s", "block_gradient": "Pa/m"} and order == "yx",
          "HDF5 unit attributes %s, axis_order %s" % (got, order))
    # a plain permeability that no rock has: a warning, not an error
    config(base("huge", "uniform: {law: darcy, k: 10}"), "huge.yaml", work)
    r = run([mdpore, "darcy", "huge.yaml", "--quiet"], work)
    check(r.returncode == 0 and "huge.yaml:8" in r.stderr and "'10 mD'" in r.stderr,
          "k: 10 (plain, SI) warns: %s" % r.stderr.strip())
    good = "uniform: {law: darcy, k: 10 mD}"
    expect_error(work, mdpore, "bad_unit.yaml", base("x", "uniform: {law: darcy, k: 10 md}"),
                 ["bad_unit.yaml:8", "'laws.uniform.k'", "unknown permeability unit 'md'",
                  "m^2, D, mD, uD, nD"])
    expect_error(work, mdpore, "reduced_in_si.yaml", base("x", "uniform: {law: darcy, k: 2 rc^2}"),
                 ["reduced_in_si.yaml:8", "'rc^2' is a reduced unit"])
    expect_error(work, mdpore, "si_in_reduced.yaml", base("x", good, units="reduced"),
                 ["si_in_reduced.yaml:8", "'mD' is a SI unit", "rc^2"])
    expect_error(work, mdpore, "bad_visc.yaml", base("x", good, visc="1 cp"),
                 ["bad_visc.yaml:3", "'fluid.viscosity'", "cP"])
    expect_error(work, mdpore, "bad_size.yaml", base("x", good, size="1 m, 2 parsecs"),
                 ["bad_size.yaml:2", "'grid.size[1]'", "unknown length unit"])
    expect_error(work, mdpore, "bad_pressure.yaml", base("x", good, p1="2 atm"),
                 ["bad_pressure.yaml:5", "'boundary.x-.pressure'", "MPa"])


def write_k(work, name, data, attrs):
    with h5py.File(os.path.join(work, name), "w") as h:
        d = h.create_dataset("k", data=data)
        for key, v in attrs.items():
            d.attrs[key] = v


def datasets(mdpore, work):
    rng = np.random.default_rng(4)
    k = np.exp(rng.normal(0, 1, (3, 4))) * 5.0  # (ny, nx), in mD
    write_k(work, "k_md.h5", k, {"unit": "mD"})
    write_k(work, "k_none.h5", k, {})
    write_k(work, "k_m2.h5", k * MD, {"unit": "m^2"})
    write_k(work, "k_T.h5", k.T, {"unit": "mD"})
    write_k(work, "k_xy.h5", k.T.copy(), {"unit": "mD", "axis_order": "xy"})
    write_k(work, "k_badorder.h5", k, {"unit": "mD", "axis_order": "xx"})
    write_k(work, "k_badunit.h5", k, {"unit": "millidarcy"})
    law = "hdf5: {file: FILE, dataset: k}"
    results = {}
    for name in ("k_md", "k_m2", "k_xy"):
        cfg = config(base(name, law.replace("FILE", name + ".h5")), name + ".yaml", work)
        r = run([mdpore, "darcy", cfg, "--quiet"], work)
        check(r.returncode == 0, "%s runs (rc=%d) %s" % (cfg, r.returncode, r.stderr.strip()))
        results[name] = keff(work, name)
    check(abs(results["k_m2"] / results["k_md"] - 1) < 1e-9,
          "dataset in mD == dataset in m^2 (%.10g, %.10g)" % (results["k_md"], results["k_m2"]))
    check(abs(results["k_xy"] / results["k_md"] - 1) < 1e-12,
          "dataset stored x slowest with axis_order 'xy' == C-order dataset (%.10g)"
          % results["k_xy"])
    cfg = config(base("none_unit", "hdf5: {file: k_none.h5, dataset: k, unit: mD}"),
                 "none_unit.yaml", work)
    r = run([mdpore, "darcy", cfg, "--quiet"], work)
    check(r.returncode == 0 and abs(keff(work, "none_unit") / results["k_md"] - 1) < 1e-12,
          "unit-less dataset accepted when the config states laws.hdf5.unit: mD")
    expect_error(work, mdpore, "no_unit.yaml", base("x", law.replace("FILE", "k_none.h5")),
                 ["no_unit.yaml:8", "'laws.hdf5.dataset'", "'unit' attribute", "k_none.h5",
                  "laws.hdf5.unit"])
    expect_error(work, mdpore, "unit_conflict.yaml",
                 base("x", "hdf5: {file: k_md.h5, dataset: k, unit: D}"),
                 ["unit_conflict.yaml:8", "'laws.hdf5.unit'", "says 'mD'", "got 'D'"])
    expect_error(work, mdpore, "bad_attr_unit.yaml", base("x", law.replace("FILE", "k_badunit.h5")),
                 ["bad_attr_unit.yaml:8", "'millidarcy'", "m^2, D, mD, uD, nD"])
    expect_error(work, mdpore, "transposed.yaml", base("x", law.replace("FILE", "k_T.h5")),
                 ["transposed.yaml:8", "'laws.hdf5.dataset'", "(ny, nx) = (3, 4)",
                  "got shape (4, 3)", "axis_order"])
    expect_error(work, mdpore, "bad_order.yaml", base("x", law.replace("FILE", "k_badorder.h5")),
                 ["bad_order.yaml:8", "axis_order", "'xx'", "'yx'"])
    expect_error(work, mdpore, "rank3.yaml",
                 base("x", law.replace("FILE", "k_md.h5")).replace("cells: [4, 3]",
                                                                   "cells: [4, 3, 2]")
                 .replace("size: [1.0, 0.5]", "size: [1.0, 0.5, 0.2]"),
                 ["rank3.yaml:8", "(nz, ny, nx) = (2, 3, 4)", "got shape (3, 4)"])
    # square grid: a transposition passes the shape check; only axis_order tells. The transposed
    # data read as C order gives another k_eff (what the attribute guards against).
    sq = np.exp(rng.normal(0, 1, (4, 4))) * 5.0
    write_k(work, "sq.h5", sq, {"unit": "mD"})
    write_k(work, "sq_T_plain.h5", sq.T.copy(), {"unit": "mD"})
    write_k(work, "sq_T_order.h5", sq.T.copy(), {"unit": "mD", "axis_order": "x,y"})
    out = {}
    for name in ("sq", "sq_T_plain", "sq_T_order"):
        cfg = config(base(name, law.replace("FILE", name + ".h5")).replace("cells: [4, 3]",
                                                                          "cells: [4, 4]"),
                     name + ".yaml", work)
        r = run([mdpore, "darcy", cfg, "--quiet"], work)
        check(r.returncode == 0, "%s runs" % cfg)
        out[name] = keff(work, name)
    check(abs(out["sq_T_order"] / out["sq"] - 1) < 1e-12 and abs(out["sq_T_plain"] / out["sq"] - 1)
          > 1e-3, "nx = ny: transposed data with axis_order 'x,y' == original (%.8g); without it "
          "k_eff differs (%.8g)" % (out["sq_T_order"], out["sq_T_plain"]))


UPS = """units: SI
grid: {cells: [6, 4, 3], size: [60 m, 40 m, 30 m]}
fluid: {viscosity: 1 cP}
laws:
  layers:
    axis: x
    list:
      - {cells: 2, law: darcy, k: 100 mD}
      - {cells: 3, law: darcy, k: 1 mD}
      - {cells: 1, law: darcy, k: 30 mD}
output: {json: OUT.json, hdf5: OUT.h5}
"""


def upscaling(mdpore, mpiexec, work):
    harm = 1.0 / ((2 / 100.0 + 3 / 1.0 + 1 / 30.0) / 6.0)
    arith = (2 * 100.0 + 3 * 1.0 + 30.0) / 6.0
    tens = {}
    for np_ in (1, 2):
        out = "ups%d" % np_
        config(UPS.replace("OUT", out), out + ".yaml", work)
        r = run([mpiexec, "-n", str(np_), "--oversubscribe", mdpore, "darcy", out + ".yaml",
                 "--upscale"], work)
        check(r.returncode == 0, "--upscale on %d rank(s) (rc=%d) %s" % (np_, r.returncode,
                                                                        r.stderr.strip()))
        if r.returncode:
            return
        if np_ == 1:
            check(all(w in r.stdout for w in ("fixed:", "linear:", "periodic:", "m^2", "mD",
                                              "no flow")),
                  "stdout names the families, their conditions and both units")
        res = json.load(open(os.path.join(work, out + ".json")))
        tens[np_] = {f: np.array([np.nan if v is None else v for v in res["permeability"][f][
            "tensor_mD"]]).reshape(3, 3) for f in ("fixed", "linear", "periodic")}
        m2 = np.array([np.nan if v is None else v for v in res["permeability"]["fixed"]["tensor"]])
        check(res["permeability_unit"] == "m^2" and
              np.nanmax(np.abs(m2 / MD / tens[np_]["fixed"].ravel() - 1)) < 1e-12,
              "JSON tensor in m^2 and tensor_mD agree")
        with h5py.File(os.path.join(work, out + ".h5"), "r") as h:
            u = h["permeability_periodic"].attrs["unit"]
            u = u.decode() if isinstance(u, bytes) else u
            check(u == "m^2" and h["permeability_periodic"].shape == (3, 3),
                  "HDF5 permeability_periodic (3, 3) with unit %s" % u)
    t = tens[1]
    for f in ("fixed", "periodic"):
        check(abs(t[f][0, 0] / harm - 1) < 1e-9 and abs(t[f][1, 1] / arith - 1) < 1e-9 and
              abs(t[f][2, 2] / arith - 1) < 1e-9,
              "%s: K_xx = harmonic %.8g (got %.8g), K_yy = K_zz = arithmetic %.8g (got %.8g)"
              % (f, harm, t[f][0, 0], arith, t[f][1, 1]))
    check(np.isnan(t["fixed"][0, 1]) and not np.isnan(t["periodic"][0, 1]),
          "fixed: off-diagonals null (not defined); periodic: defined")
    d = max(np.nanmax(np.abs(tens[2][f] - tens[1][f]) / np.nanmax(tens[1][f])) for f in tens[1])
    check(d < 1e-8, "np 2 vs np 1: max relative difference %.2e" % d)
    # the upscale key picks families; refusals
    config(UPS.replace("OUT", "onlyp") + "upscale: {conditions: [periodic]}\n", "onlyp.yaml", work)
    r = run([mdpore, "darcy", "onlyp.yaml", "--quiet"], work)
    res = json.load(open(os.path.join(work, "onlyp.json"))) if r.returncode == 0 else {}
    check(r.returncode == 0 and list(res.get("permeability", {})) == ["periodic"],
          "upscale: {conditions: [periodic]} gives the periodic tensor only")
    expect_error(work, mdpore, "ups_forch.yaml",
                 UPS.replace("OUT", "x").replace("{cells: 1, law: darcy, k: 30 mD}",
                                                 "{cells: 1, law: forchheimer, k: 30 mD, "
                                                 "beta: 1e6}").replace("1 cP}", "1 cP, density: "
                                                                               "1000}"),
                 ["ups_forch.yaml:5", "'laws'", "Darcy laws", "forchheimer"], ["--upscale"])
    expect_error(work, mdpore, "ups_source.yaml",
                 UPS.replace("OUT", "x") + "sources: [{block: [1, 1, 1], rate: 1e-6}]\n",
                 ["ups_source.yaml:12", "'sources'", "no sources"], ["--upscale"])
    expect_error(work, mdpore, "ups_bad.yaml",
                 UPS.replace("OUT", "x") + "upscale: {conditions: [wavy]}\n",
                 ["ups_bad.yaml:12", "'upscale.conditions[0]'", "wavy"])


def main():
    mdpore, mpiexec, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    units_on_values(mdpore, work)
    datasets(mdpore, work)
    upscaling(mdpore, mpiexec, work)
    print("%d failure(s)" % len(failures))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
