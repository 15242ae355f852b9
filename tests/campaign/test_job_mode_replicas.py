#!/usr/bin/python3
"""ctest campaign_job_mode_replicas: `mdpore permeability --jobs N --job-mode replicas`, the runs at
once stepped in one process (campaign/campaign_replicas.c, mdpore run --replicas), on the CPU.

The 8 x 6 x 4 slit of the campaign tests (rc_per_voxel 1, flow along x, ~1050 particles per run),
3 gradients of STEPS steps on 1 rank each, OMP_NUM_THREADS=1. Asserted:
 1. --job-mode x refused naming the option and the words it takes (exit 2);
 2. the same campaign at --jobs 3 as processes (the reference) and as replicas, each in its own
    folder: every run's q the same bits, the flow tables the same bytes but for the folders' names;
 3. replicas: the three runs went in one process (one "runs at once in one process" line), every
    run's run.log is that process's log (one file, three links);
 4. the replicas campaign run again reuses every run and starts no process.
"""
import json
import os
import re
import shutil
import subprocess
import sys

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "campaign_job_mode_out"))
IMAGE = os.environ["MDPORE_TEST_IMAGE"]
STEPS = os.environ.get("MDPORE_TEST_STEPS", "400")
ENV = dict(os.environ, OMP_NUM_THREADS="1", MDPORE_CACHE_DIR=os.path.join(OUT, "cache"))
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def campaign(wd, *more):
    return subprocess.run([MDPORE, "permeability", IMAGE, "--axis", "x", "--gradients",
                           "0.1,0.2,0.3", "--max-steps", STEPS, "--np", "1", "--jobs", "3",
                           "--workdir", wd, *more], capture_output=True, text=True, cwd=OUT,
                          env=ENV)


def run_dirs(wd):
    man = os.path.join(OUT, wd, "campaign.txt")
    return [l.split()[3] for l in open(man) if l.startswith("run: ")] if os.path.exists(man) else []


def q_values(wd):
    out = []
    for d in run_dirs(wd):
        s = os.path.join(d, "summary.json")
        out.append(json.load(open(s)).get("flux", {}).get("q") if os.path.exists(s) else None)
    return out


def table(wd):
    p = os.path.join(OUT, wd, "flow_x.csv")
    if not os.path.exists(p):
        return None
    return re.sub(r"runs/x-[0-9a-f]+", "RUN", open(p).read().replace(os.path.join(OUT, wd), "WD"))


shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)

p = campaign("bad", "--job-mode", "x")
check(p.returncode == 2 and "--job-mode" in p.stderr and "process or replicas" in p.stderr,
      f"--job-mode x refused (exit {p.returncode}: {p.stderr.strip()[-160:]})")

p = campaign("proc")
check(p.returncode == 0, f"process mode: exit 0 ({p.stderr[-300:] if p.returncode else ''})")
r = campaign("rep", "--job-mode", "replicas")
check(r.returncode == 0, f"replicas mode: exit 0 ({r.stderr[-300:] if r.returncode else ''})")
qp, qr = q_values("proc"), q_values("rep")
check(len(qp) == 3 and None not in qp and qp == qr, f"every run's q the same bits: {qp} / {qr}")
check(table("proc") is not None and table("proc") == table("rep"),
      "the flow tables the same bytes but for the folders' names")
check(r.stderr.count("3 runs at once in one process") == 1, "the three runs in one process")
inodes = {os.stat(os.path.join(d, "run.log")).st_ino for d in run_dirs("rep")}
check(len(inodes) == 1, f"every run's run.log is the batch's log ({len(inodes)} file(s))")

again = campaign("rep", "--job-mode", "replicas")
check(again.returncode == 0 and again.stderr.count("reused") == 3 and
      "in one process" not in again.stderr, "run again: every run reused, no process started")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all checks passed")
