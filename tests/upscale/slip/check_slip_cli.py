#!/usr/bin/env python3
"""ctest upscale_slip_cli: `mdpore slip` at the command line (docs/permeability.md, "Slip and apparent
permeability"): a CSV and campaign JSON inputs, the outputs (CSV, JSON, PNG when matplotlib is there),
`mdpore fit slip` as an alias, one point (chi2 undefined, said), and bad inputs refused with exit 1
(exit 2 for usage) and a message naming the file, the key and what was expected.
Usage: check_slip_cli.py MDPORE WORKDIR"""
import json
import os
import subprocess
import sys

EXE, WD = sys.argv[1], sys.argv[2]
os.makedirs(WD, exist_ok=True)
os.chdir(WD)
failures = []


def mdpore(*args):
    return subprocess.run([EXE, *args], capture_output=True, text=True)


def expect(args, code, fragments, what):
    p = mdpore(*args)
    msg = p.stdout + p.stderr
    ok = p.returncode == code and all(f in msg for f in fragments)
    print(f"{'ok  ' if ok else 'FAIL'} {what}: exit {p.returncode}: {msg.strip().splitlines()[-1] if msg.strip() else ''}")
    if not ok:
        failures.append(f"{what}: expected exit {code} and {fragments}, got {p.returncode}: {msg}")
    return p


def write(name, text):
    with open(name, "w") as f:
        f.write(text)
    return name


def k_slit(h, b, phi):  # k = phi h^2/12 (1 + 6 b/h)
    return phi * h * h / 12 * (1 + 6 * b / h)


# -- a good CSV (exact navier data, b = -0.25, 1% errors) ------------------------------------------
rows = "".join(f"slit,{h},{k_slit(h, -0.25, 0.5):.10g},{0.01 * k_slit(h, -0.25, 0.5):.6g},0.5\n"
               for h in (4, 6, 8, 12))
good = write("slits.csv", "# synthetic\nshape,h,k,k_err,porosity\n" + rows)
p = expect([ "slip", good, "--out", "out_csv"], 0, ["b = -0.2500", "chi2/dof"], "CSV input")
with open("out_csv.json") as f:
    j = json.load(f)
if abs(j["fit"]["b"] + 0.25) > 1e-9 or j["shape"] != "slit" or len(j["points"]) != 4:
    failures.append(f"CSV input: JSON b = {j['fit']['b']}, shape {j['shape']}")
with open("out_csv.csv") as f:
    lines = f.read().splitlines()
if not lines[1].startswith("shape,h,k,k_err,porosity,k_noslip,k_over_k_noslip") or len(lines) != 6:
    failures.append(f"trend CSV: {lines[:2]}")
try:
    import matplotlib  # noqa: F401
    if not os.path.exists("out_csv.png"):
        failures.append("no out_csv.png although matplotlib is installed")
except ImportError:
    print("matplotlib missing: PNG not checked")
expect(["fit", "slip", good, "--model", "shift", "--out", "out_alias", "--no-plot"], 0,
       ["shift model", "b = "], "mdpore fit slip (alias), shift model")
expect(["slip", good, "--free-scale", "--out", "out_free", "--no-plot"], 0, ["a = 1.0000"], "free scale")

# -- campaign JSON inputs ---------------------------------------------------------------------------
for h in (4, 8):
    os.makedirs(f"camp{h}", exist_ok=True)
    phi = h / (h + 4)
    k = k_slit(h, -0.2, phi)
    write(f"camp{h}/permeability.json", json.dumps({
        "format": "mdpore-permeability", "version": 1, "porosity": phi, "units": {"rc_m": 8.2e-10},
        "axes": {"x": {"k_rc2": k, "k_rc2_err": 0.02 * k}}}))
    write(f"camp{h}/campaign.txt", f"porosity: {phi}\nrc_per_voxel: 0.5\nh_hydraulic: {h}\n")
p = expect(["slip", "--shape", "slit", "camp4/permeability.json", "camp8/permeability.json@8", "--out",
            "out_json", "--no-plot"], 0, ["b = -0.2000", " m\n"], "permeability.json inputs (slit, h from campaign.txt and @8)")
expect(["slip", "--shape", "tube", "camp4/permeability.json", "--no-plot", "--out", "x"], 1,
       ["camp4/permeability.json", "@R", "tube radius"], "tube JSON without @R")
expect(["slip", "camp4/permeability.json@4", "--no-plot", "--out", "x"], 1, ["no pore shape", "--shape"],
       "JSON without --shape")
expect(["slip", "--shape", "slit", "camp4/permeability.json", "--axis", "y", "--no-plot", "--out", "x"], 1,
       ["camp4/permeability.json", "axes.y"], "missing axis")
write("notperm.json", json.dumps({"format": "mdpore-fit"}))
expect(["slip", "--shape", "slit", "notperm.json@4", "--no-plot", "--out", "x"], 1,
       ["notperm.json", "format", "mdpore-permeability"], "wrong JSON format")

# -- one point --------------------------------------------------------------------------------------
one = write("one.csv", "shape,h,k,k_err\ntube,3,%.10g,0.01\n" % (9 / 8 * (1 + 4 * -0.3 / 3)))
expect(["slip", one, "--out", "out_one", "--no-plot"], 0, ["b = -0.3000", "chi2/dof undefined", "1 point(s)"],
       "one point")

# -- bad inputs -------------------------------------------------------------------------------------
H = "shape,h,k,k_err\n"
bad = [
    ("unknown shape", write("b1.csv", H + "cube,4,0.5,0.01\n"), [], 1,
     ["b1.csv:2", "column 'shape'", "slit or tube", "'cube'"]),
    ("mixed shapes", write("b2.csv", H + "slit,4,0.5,0.01\ntube,2,0.3,0.01\n"), [], 1,
     ["b2.csv:3", "expected slit", "one shape per fit"]),
    ("h <= 0", write("b3.csv", H + "slit,4,0.5,0.01\nslit,0,0.5,0.01\n"), [], 1,
     ["b3.csv:3", "key 'h'", "pore size > 0", "got 0"]),
    ("non-finite k", write("b4.csv", H + "slit,4,nan,0.01\n"), [], 1, ["b4.csv:2", "key 'k'", "finite"]),
    ("negative error", write("b5.csv", H + "slit,4,0.5,-0.01\n"), [], 1,
     ["b5.csv:2", "key 'k_err'", "positive standard error", "-0.01"]),
    ("not a number", write("b6.csv", H + "slit,4,abc,0.01\n"), [], 1,
     ["b6.csv:2", "column 'k'", "expected a number", "'abc'"]),
    ("missing column", write("b7.csv", "shape,h,k\nslit,4,0.5\n"), [], 1,
     ["b7.csv:1", "expected a column 'k_err'"]),
    ("fewer points than parameters", write("b8.csv", H + "slit,4,0.5,0.01\n"), ["--free-scale"], 1,
     ["1 point(s) for 2 parameter(s)", "at least 2"]),
    ("no data rows", write("b9.csv", H), [], 1, ["b9.csv", "no data rows"]),
    ("flow table", write("b10.csv", "# mdpore flow table v1\n# sample: s\n"), [], 1,
     ["b10.csv", "flow table", "permeability.json"]),
    ("missing file", "nowhere.csv", [], 1, ["nowhere.csv", "cannot open"]),
    ("porosity > 1", write("b11.csv", "h,k,k_err,porosity\n4,0.5,0.01,2\n"), ["--shape", "slit"], 1,
     ["b11.csv:2", "key 'porosity'", "(0, 1]"]),
]
for what, path, extra, code, frags in bad:
    expect(["slip", path, "--no-plot", "--out", "x"] + extra, code, frags, what)
expect(["slip", good, "--shape", "cube"], 2, ["--shape", "slit or tube", "'cube'"], "unknown --shape")
expect(["slip", good, "--model", "klinkenberg"], 2, ["--model", "navier or shift"], "unknown --model")
expect(["slip"], 2, ["no INPUT"], "no input")

print("pass" if not failures else "FAIL:\n" + "\n".join(failures))
sys.exit(1 if failures else 0)
