#!/usr/bin/python3
"""ctest guard_faults: the NaN and lost-particle guards triggered on purpose, on
1 and 2 ranks, through the test-only fault hook MDPORE_TEST_FAULT=KIND:STEP:ID (meso/run/run_fault.h:
read once at the start of mdpore run; particle ID is damaged just before step STEP on its rank).

A healthy run of tests/engine/scenes/guard_faults.yaml cannot reach these guards on demand (a
blow-up trips the displacement guard first), so each case damages particle 7 before step 20:
  nan_velocity  v_x = NaN             -> "non-finite velocity or position"
  nan_position  x_x = NaN             -> the same (before the fix of this test's commit the drift
                                         check saw only the displacement: on 1 rank the NaN was
                                         reported as a lost particle, on 2 ranks it stayed
                                         silently on its rank and the run ended with exit 0)
  jump          x_x += 3 box lengths  -> "particle lost: 1 particle(s) ... farther than a
                                         neighbouring subdomain" (migration, 2 ranks: the collective)
  remove        dropped from storage  -> "the global particle count changed from 288 to 287"
                                         (the collective count check)
Asserted per case and rank count: exit != 0; stderr names the cause, the particle (id 7, except
the count check, which cannot know it), step 20 and what to try, and ends the run with "mdpore: run
stopped at step 20"; the thermo CSV holds steps 0..19 only, every value finite; no summary.json
(no NaN reaches the outputs). Also: the same scene without a fault runs to the end (exit 0,
summary written), and a malformed MDPORE_TEST_FAULT is refused.

With BACKEND cuda (ctest cuda_guard_faults; 2 ranks share the GPUs there are; skipped, exit 77,
printing why, without one): the same cases through the device write of the hook (sim_fault_write),
which exercise the CUDA kick-drift kernel's checks: the non-finite position/velocity test after the
wall effects (a NaN position with a finite velocity), the loss of a particle farther than two box
lengths (1 rank: the device wrap) and, on 2 ranks, that the drift's record wins over the host
migration's loss of the same particle. `remove` is refused on CUDA (the particles live in device
arrays; asserted). Not run on a GPU yet when written (no GPU on the machine it was written on).
Usage: test_guard_faults.py MDPORE "MPIEXEC FLAGS" SCENE WORKDIR [cpu|cuda]
"""
import json
import math
import os
import shutil
import subprocess
import sys

mdpore, mpi, scene, work = sys.argv[1:5]
BACKEND = sys.argv[5] if len(sys.argv) > 5 else "cpu"
failures = []


def check(cond, what, detail=""):
    print(("ok   " if cond else "FAIL ") + what + ("" if cond or not detail else f"\n     {detail}"), flush=True)
    if not cond:
        failures.append(what)


def run(np_, fault, out):
    env = dict(os.environ)
    env.pop("MDPORE_TEST_FAULT", None)
    if fault:
        env["MDPORE_TEST_FAULT"] = fault
    cmd = (mpi.split() + ["-n", str(np_)] if np_ > 1 else []) + [mdpore, "run", "--backend", BACKEND,
                                                                 "--output-dir", out, scene]
    return subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=300)


def thermo_rows(out):
    rows = []
    for line in open(os.path.join(out, "thermo.csv")):
        cells = line.strip().split(",")
        try:
            rows.append([float(c) for c in cells])
        except ValueError:
            continue  # the header
    return rows


CASES = {
    "nan_velocity": ["particle 7 at (nan", "non-finite velocity or position (NaN or Inf)",
                     "try run.dt <= "],
    "nan_position": ["particle 7 at (nan", "non-finite velocity or position (NaN or Inf)",
                     "try run.dt <= "],
    "jump": ["particle lost: 1 particle(s) left the box through a non-periodic face or moved farther "
             "than a neighbouring subdomain", "first: particle 7 at (", "Try walls on the non-periodic faces"],
    "remove": ["particle lost: the global particle count changed from 288 to 287", "try a smaller dt"],
}


def main():
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    if BACKEND == "cuda":
        probe = subprocess.run([mdpore, "run", "--backend", "cuda", "--explain", scene], capture_output=True, text=True)
        if probe.returncode:
            print("skipped: no GPU (" + probe.stderr.strip().split("available: ")[-1] + ")")
            sys.exit(77)
    for np_ in (1, 2):
        out = os.path.join(work, f"clean_np{np_}")
        p = run(np_, None, out)
        check(p.returncode == 0 and os.path.exists(os.path.join(out, "summary.json"))
              and "run stopped" not in p.stderr, f"np {np_}: no fault: the run ends cleanly", p.stderr[-500:])
        for kind, parts in CASES.items():
            out = os.path.join(work, f"{kind}_np{np_}")
            p = run(np_, f"{kind}:20:7", out)
            err = p.stderr
            what = f"np {np_} {kind}"
            if BACKEND == "cuda" and kind == "remove":
                check(p.returncode != 0 and "MDPORE_TEST_FAULT=remove works on the cpu backend only" in err,
                      f"{what}: refused on the CUDA backend", err[-400:])
                continue
            check(p.returncode != 0, f"{what}: non-zero exit ({p.returncode})")
            missing = [s for s in parts + ["mdpore: step 20: ", "mdpore: run stopped at step 20"] if s not in err]
            check(not missing, f"{what}: the message names cause, particle, step and advice",
                  f"missing {missing} in: {err[-1200:]}")
            if kind != "remove":  # the collective count check prints once, on rank 0
                check("(rank " in err, f"{what}: the rank that saw it is named")
            rows = thermo_rows(out)
            finite = all(math.isfinite(v) for r in rows for v in r)
            check(finite and rows and int(rows[-1][0]) == 19,
                  f"{what}: thermo.csv ends at step 19, every value finite",
                  f"last step {rows[-1][0] if rows else None}, finite {finite}")
            check(not os.path.exists(os.path.join(out, "summary.json")), f"{what}: no summary.json written")
    p = run(1, "nan:20", os.path.join(work, "bad"))
    check(p.returncode != 0 and "MDPORE_TEST_FAULT='nan:20': expected KIND:STEP:ID" in p.stderr,
          "malformed MDPORE_TEST_FAULT refused", p.stderr[-400:])


if __name__ == "__main__":
    main()
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")
