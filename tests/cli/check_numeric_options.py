#!/usr/bin/python3
"""ctest cli_numeric_options: every option of a command that takes a value, read from the command's
own --help-all (its option table and usage lines), gets nan, inf and 1e400 (as one element of a
list value: --gradients 0.1,nan, --box 10,nan,10, ...). The options of `image make` are read by one
parser for every kind: each is tried once, on a slit. Each must be refused: a non-zero exit within
20 s (no crash: exit < 128) and a message that names the option. Options whose value is a path, a
folder, a name or a command line (TEXT below) are left out: there any text is a valid value. An
option the table below names but --help-all no longer lists fails the test (the table went
stale).

usage: check_numeric_options.py MDPORE WORKDIR [COMMAND ...]   (COMMAND as in `mdpore COMMAND`;
       "image make" stands for each kind of its usage lines)"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

mdpore, work, commands = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), sys.argv[3:]
os.makedirs(work, exist_ok=True)
BAD = ["nan", "inf", "1e400"]
# values that are paths, folders, names or command lines: any text is valid there
TEXT = {"--workdir", "--emit-scenes", "--collect", "--template", "--phase-images", "--write-image",
        "--swof", "--png", "--pc-morph", "--mpiexec", "--sample", "--out", "--json",
        "--plot", "-o", "--centres", "--box-file", "--dataset", "--output-dir", "--restart"}
# list values: the bad number goes in as one element of an otherwise valid list
LIST = {"--saturations": "0.3,{}", "--gradients": "0.1,{}", "--velocity-range": "0.02,{}", "--box": "10,{},10",
        "--dims": "4x{}x4", "--crop": "0:{},:,:", "--pad": "x={}", "--voxel-size": "{}um"}
failures = []


def run(args, timeout=20):
    """(exit, output) of one call, with a TMPDIR of its own: Open MPI singletons started at once
    race on a shared session directory (open-mpi/ompi#8510: "A call to mkdir was unable to create
    the desired directory", an exit 1 that names no option)."""
    try:
        with tempfile.TemporaryDirectory() as tmp:
            p = subprocess.run([mdpore, *args], capture_output=True, text=True, timeout=timeout,
                               cwd=work, env=dict(os.environ, TMPDIR=tmp))
        return p.returncode, p.stdout + p.stderr
    except subprocess.TimeoutExpired:
        return "timeout", ""


def help_options(cmd):
    """(option, metavar) pairs of `mdpore CMD --help-all`: option-table lines and usage lines."""
    rc, text = run([*cmd.split(), "--help-all"])
    assert rc == 0, "mdpore %s --help-all: exit %s" % (cmd, rc)
    pairs = {}
    for line in text.splitlines():
        # an option table line: "  --opt VALUE   meaning" (a flag has two spaces or more after it)
        m = re.match(r"^\s+(--[a-z][\w-]*|-o) ([^\s-]\S*)", line)
        if m:
            pairs.setdefault(m.group(1), m.group(2))
        # usage lines: "--opt VALUE" with an upper-case VALUE
        for opt, meta in re.findall(r"(--[a-z][\w-]*|-o)\s(?:\[?)([A-Z][A-Za-z0-9,:|._\[\]]*)", line):
            pairs.setdefault(opt, meta)
    return text, pairs


def make_inputs():
    rc, out = run(["image", "make", "slit", "--width", "8", "--wall", "4", "--length", "12",
                   "--depth", "8", "-o", "slit.h5"])
    assert rc == 0, out
    with open(os.path.join(work, "slip.csv"), "w") as f:
        f.write("h,k,k_err\n4,1.6,0.02\n6,3.4,0.04\n8,5.9,0.06\n")
    here = os.path.dirname(os.path.abspath(__file__))
    shutil.copy(os.path.join(here, "..", "..", "cases", "upscale", "relperm_synthetic.csv"),
                os.path.join(work, "kr.csv"))
    with open(os.path.join(work, "table.csv"), "w") as f:
        f.write("pressure_gradient,darcy_velocity,darcy_velocity_stderr\n"
                "0.1,0.01,0.001\n0.2,0.02,0.001\n0.3,0.03,0.001\n0.4,0.04,0.001\n")
    with open(os.path.join(work, "centres.txt"), "w") as f:
        f.write("5 5 5\n")
    with open(os.path.join(work, "box.txt"), "w") as f:
        f.write("Lx:10 Ly:10 Lz:10\n")
    with open(os.path.join(work, "scene.yaml"), "w") as f:
        f.write("box: {hi: [4, 4, 4]}\nspecies: [{name: a}]\npairs: {a-a: {A: 25, gamma: 4.5}}\n"
                "effects: {dpd_conservative: , dpd_thermostat: }\n"
                "initial: {fill: [{species: a, density: 3}]}\nrun: {dt: 0.01, steps: 1}\n"
                "output: {summary: s.json, progress: false}\n")


# the command line each option is added to (valid on its own), per command
BASE = {
    "permeability": ["permeability", "slit.h5", "--axis", "x", "--emit-scenes", "emitted"],
    "slip": ["slip", "slip.csv", "--shape", "slit", "--no-plot", "--out", "slip_out"],
    "fit": ["fit", "table.csv", "--json", "fit_out.json"],
    "image": ["image", "info", "slit.h5"],
    "run": ["run", "--explain", "scene.yaml"],
    "build patches": ["build", "patches", "--out", "patches_out.h5"],
    "relperm": ["relperm", "slit.h5", "--axis", "x", "--rc-per-voxel", "1", "--emit-scenes",
                "relperm_emitted"],
    "image drainage": ["image", "drainage", "slit.h5", "--axis", "x", "--no-plot", "-o", "pc_out"],
    "fit relperm": ["fit", "relperm", "kr.csv", "--json", "kr_fit.json"],
    "darcy": None, "couple": None,  # no option takes a number (the config holds them)
}
MAKE = {"slit": ["--width", "8"], "cylinders": ["--cell", "10", "--c", "0.3"],
        "spheres": ["--cell", "10", "--c", "0.3"],
        "random-spheres": ["--size", "10", "--radius", "2", "--porosity", "0.5"],
        "sphere-file": ["--centres", "centres.txt", "--box", "10,10,10", "--radius", "2",
                        "--dx", "1"]}


def try_option(label, base, opt, meta):
    values = [LIST[opt].format(b) for b in BAD] if opt in LIST else BAD
    if opt == "--voxel-size":  # a plain number is valid too
        values += BAD
    for v in values:
        TRIES.append((label, base, opt, v))


TRIES = []  # collected, then run 4 at a time (each call mostly waits on MPI's start)


def run_tries():
    def one(t):
        label, base, opt, v = t
        rc, out = run(base + [opt, v])
        return t, rc, out
    with ThreadPoolExecutor(4) as pool:
        for (label, base, opt, v), rc, out in pool.map(one, TRIES):
            ok = rc != "timeout" and rc != 0 and rc < 128 and opt in out
            print("%s mdpore %s %s %s: exit %s%s" % ("ok  " if ok else "FAIL", " ".join(base), opt,
                                                    v, rc, "" if ok else ": " + out.strip()[-300:]))
            if not ok:
                failures.append("%s %s %s" % (label, opt, v))


def main():
    make_inputs()
    seen_list = set()
    for cmd in commands:
        text, pairs = help_options(cmd)
        if cmd == "image":
            usage = [l for l in text.splitlines() if "image make " in l]
            make_opts = {}
            for line in usage:
                for o, m in re.findall(r"(--[a-z][\w-]*)\s([A-Z][A-Za-z0-9,|]*)", line):
                    make_opts[o] = m
            numeric_make = [o for o in make_opts if o not in TEXT]
            for kind in MAKE:
                assert "make " + kind in text, "mdpore image --help-all: no 'make %s'" % kind
            valid = MAKE["slit"]
            for o in numeric_make + ["--voxel-size", "--seed"]:
                base = ["image", "make", "slit", *valid, "-o", "m_slit.h5"]
                if o in valid:  # the bad value replaces the valid one
                    i = valid.index(o)
                    base = ["image", "make", "slit", *valid[:i], *valid[i + 2:], "-o", "m_slit.h5"]
                try_option("image make", base, o, make_opts.get(o))
            reading = {o: m for o, m in pairs.items() if o not in make_opts or o == "--voxel-size"}
            pairs = reading
        base = BASE.get(cmd)
        numeric = [o for o in pairs if o not in TEXT and o != "--help"]
        if base is None:
            print("ok   mdpore %s: no option takes a value (%s)" % (cmd, sorted(pairs) or "none"))
            if numeric:
                failures.append("%s: options %s have no base command line here" % (cmd, numeric))
            continue
        for o in numeric:
            try_option(cmd, base, o, pairs[o])
        seen_list |= set(pairs)
    run_tries()
    stale = [o for o in LIST if o not in seen_list and o not in ("--box",)]
    if stale:
        failures.append("LIST names options no --help-all lists: %s" % stale)
    print("%d failure(s)%s" % (len(failures), "".join("\n  " + f for f in failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
