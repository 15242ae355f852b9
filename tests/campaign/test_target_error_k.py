#!/usr/bin/python3
"""ctest campaign_target_error_k: `mdpore permeability --target-error-k E`, the campaign-level stop.

The slit of test_permeability.py at its depth halved (`mdpore image make slit --width 8 --wall 4
--length 12 --depth 4`, rc_per_voxel 0.5: h = 4 rc, period H = 8 rc, k = h^3 / (12 H) = 0.667 rc^2
with the campaign's no-slip walls), 3 body forces, 1 rank, round 1 of ROUND steps per run (450 particles), --max-steps 1200, so a budget
of 3 x 1200 steps: E = 5% is out of reach of round 1 (q errors of 10-15%), met within the budget or
not. The pore core of so short a
window is noisy (a few hundred particles: +-3% between runs at rest), so --density-tolerance is 0.1
here: the test is of the stopping rule, not of the density check.

Asserted:
 1. refused, naming the options: --target-error-k with --emit-scenes, --target-error, --drive
    pressure, --collect; --round-steps without --target-error-k; a budget below the first round;
 2. the campaign, killed (SIGTERM) once it has planned round 2, is run again: round 1's runs are
    reused (none runs afresh) and the campaign goes on; it either reaches the target (the relative error of the Darcy range's k in
    permeability.json at most E, "target met") or stops at its step budget saying so, having spent
    at most the budget; more than one round ran, and the later rounds continued runs (never
    restarted them: "continued from step" on stderr);
 3. k agrees with h^3 / (12 H) within 10% + 2 sigma (the bound of test_permeability.py);
 4. the report and permeability.json's campaign_stop: the steps of every run in each round adding up
    to the run's steps, the shares of var(k) of the Darcy range's runs adding up to 1;
 5. a continued run is the uninterrupted run: its flux.csv is byte-identical to that of the same
    scene run afresh for the same total steps;
 6. the same command again reruns nothing: every run reused, every summary untouched, the same k.
"""
import glob
import json
import os
import shutil
import signal
import subprocess
import sys
import time

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "campaign_target_error_k_out"))
ROUND = "600"
TARGET = "0.05"
GRADIENTS = "0.06,0.1,0.14"
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def mdpore(*args, cwd=OUT):
    return subprocess.run([MDPORE, *args], capture_output=True, text=True, cwd=cwd)


def refused(args, needle, what):
    p = mdpore(*args)
    check(p.returncode == 2 and needle in p.stderr,
          f"{what}: exit {p.returncode}, stderr names '{needle}'" +
          ("" if needle in p.stderr else f" (got: {p.stderr.strip()[:300]})"))


def campaign_args(wd):
    return [MDPORE, "permeability", "slit.h5", "--axis", "x", "--gradients", GRADIENTS, "--np", "1",
            "--target-error-k", TARGET, "--round-steps", ROUND, "--max-steps", "1200",
            "--density-tolerance", "0.1", "--workdir", wd]


def campaign(wd):
    return subprocess.run(campaign_args(wd), capture_output=True, text=True, cwd=OUT)


def campaign_killed_in_round_2(wd):
    """Starts the campaign and sends it SIGTERM once it has planned round 2 (its runs then go)."""
    err = open(os.path.join(OUT, "killed.err"), "w")
    p = subprocess.Popen(campaign_args(wd), stdout=subprocess.PIPE, stderr=err, text=True, cwd=OUT)
    planned = False
    for line in p.stdout:
        if line.startswith("round 2:") and "continued" in line:
            planned = True
            time.sleep(0.3)  # round 2's first continuation under way
            p.send_signal(signal.SIGTERM)
            break
    p.wait()
    err.close()
    return planned


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    os.environ.setdefault("MDPORE_CACHE_DIR", os.path.join(OUT, "cache"))
    p = mdpore("image", "make", "slit", "--width", "8", "--wall", "4", "--length", "12", "--depth", "4",
               "-o", "slit.h5")
    if p.returncode:
        sys.exit("image make failed: " + p.stderr)

    # 1. refusals
    base = ["permeability", "slit.h5", "--axis", "x", "--target-error-k", "0.05"]
    refused(base + ["--emit-scenes", "em"], "--target-error-k: not supported with --emit-scenes", "with --emit-scenes")
    refused(base + ["--target-error", "0.05"], "not supported with --target-error", "with --target-error")
    refused(base + ["--drive", "pressure"], "not supported with --drive pressure", "with --drive pressure")
    refused(["permeability", "--collect", "x", "--target-error-k", "0.05"], "not supported with --collect",
            "with --collect")
    refused(["permeability", "slit.h5", "--axis", "x", "--round-steps", "100"],
            "--round-steps: applies with --target-error-k", "--round-steps alone")
    refused(base + ["--target-error-k", "1.5"], "--target-error-k: expected a relative error of k", "E >= 1")
    p = mdpore(*base, "--gradients", GRADIENTS, "--round-steps", "1000", "--budget-steps", "2000",
               "--workdir", "small")
    check(p.returncode == 2 and "--budget-steps 2000: expected at least the first round" in p.stderr and
          "usable run" not in p.stderr,
          f"a budget below the first round refused ({p.returncode}: {p.stderr.strip()[-200:]})")

    # 2. the campaign, killed once round 1 is done and round 2 planned, then run again: round 1's
    # runs reused, round 2 brought to its recorded steps, the campaign goes on from there
    wd = os.path.join(OUT, "camp")
    planned = campaign_killed_in_round_2(wd)
    ledger = open(os.path.join(wd, "rounds.txt")).read() if os.path.exists(os.path.join(wd, "rounds.txt")) else ""
    round1 = [l.split()[3] for l in ledger.splitlines() if l.startswith("round 1 ")]
    check(planned and len(round1) == 3 and "round 2 " in ledger,
          "the campaign killed after planning round 2: rounds.txt records rounds 1 and 2")
    p = campaign(wd)
    check(all(f"reused {d}" in p.stderr for d in round1) and p.stderr.count("running in") == 0,
          "resumed: round 1's runs reused, none run afresh")
    print(p.stdout[-3000:])
    check(p.returncode == 0, f"campaign exit 0 ({p.returncode}; {p.stderr.strip()[-400:]})")
    res = json.load(open(os.path.join(wd, "permeability.json"))) if os.path.exists(
        os.path.join(wd, "permeability.json")) else {}
    ax = res.get("axes", {}).get("x", {})
    stop = res.get("campaign_stop", {})
    k, k_err = ax.get("k_rc2") or float("nan"), ax.get("k_rc2_err") or float("nan")
    met = stop.get("axes", {}).get("x", {}).get("met")
    rel = k_err / k
    if met:
        check(rel <= float(TARGET) * (1 + 1e-9) and "target met" in p.stdout,
              f"target met: k relative error {rel:.4f} <= {TARGET}")
    else:
        check("step budget is spent" in p.stdout and stop.get("steps", 1e99) <= stop.get("budget_steps", 0),
              f"target not met: stopped at the budget ({stop.get('steps')} of {stop.get('budget_steps')}) saying so")
    rounds = stop.get("rounds", [])
    killed_err = open(os.path.join(OUT, "killed.err")).read()
    check(len(rounds) >= 2 and "continued from step" in p.stderr + killed_err,
          f"{len(rounds)} rounds; the later ones continued runs from their checkpoints")

    # 3. k against the slit
    h, H = 4.0, 8.0
    k_noslip = h ** 3 / (12 * H)
    print(f"k = {k:.4f} +- {k_err:.4f} rc^2 ({100 * rel:.2f}%); h^3/(12 H) = {k_noslip:.4f}; "
          f"k / k_noslip = {k / k_noslip:.3f} +- {k_err / k_noslip:.3f}")
    check(abs(k / k_noslip - 1) <= 0.10 + 2 * k_err / k_noslip,
          f"k = {k:.4f} +- {k_err:.4f} recovers h^3 / (12 H) = {k_noslip:.4f} within 10% + 2 sigma")

    # 4. the steps per round and the error budget
    runs = stop.get("runs", [])
    sums = [sum(r["steps_per_round"]) == r["steps"] for r in runs]
    summaries = {r["run"]: json.load(open(os.path.join(r["run"], "summary.json"))) for r in runs}
    check(len(runs) == 3 and all(sums) and
          all(summaries[r["run"]]["last_step"] == r["steps"] for r in runs),
          "each run's steps per round add up to the step its summary reached")
    shares = [r["share_of_var_k"] for r in runs if r["share_of_var_k"] is not None]
    check(len(shares) >= 2 and abs(sum(shares) - 1) < 1e-9, f"shares of var(k) add up to 1: {shares}")
    check("share" in p.stdout and "stopping on the error of k" in p.stdout, "the report gives the rounds and shares")

    # 5. a continued run is the uninterrupted one
    cont = sorted((r for r in runs if len([s for s in r["steps_per_round"] if s > 0]) >= 2),
                  key=lambda r: r["steps"])
    if cont:
        r = cont[0]  # the shortest: the cheapest to run again
        fresh = os.path.join(OUT, "fresh")
        os.makedirs(fresh)
        shutil.copy(os.path.join(r["run"], "scene.yaml"), fresh)
        q = mdpore("run", "--steps", str(r["steps"]), "scene.yaml", cwd=fresh)
        a = open(os.path.join(r["run"], "flux.csv"), "rb").read()
        b = open(os.path.join(fresh, "flux.csv"), "rb").read() if q.returncode == 0 else b""
        check(a == b and len(a) > 0,
              f"the run continued over {r['steps_per_round']} steps has the flux series of one run of "
              f"{r['steps']} steps, byte for byte")
    else:
        check(False, "a run continued in a later round")

    # 6. resume after the end reruns nothing
    mtimes = {d: os.stat(os.path.join(d, "summary.json")).st_mtime_ns for d in summaries}
    p2 = campaign(wd)
    res2 = json.load(open(os.path.join(wd, "permeability.json")))
    check(p2.returncode == 0 and "running in" not in p2.stderr and "continued from" not in p2.stderr and
          all(os.stat(os.path.join(d, "summary.json")).st_mtime_ns == t for d, t in mtimes.items()),
          "the finished campaign again: nothing rerun, every summary untouched")
    check(res2["axes"]["x"]["k_rc2"] == k and len(res2["campaign_stop"]["rounds"]) == len(rounds),
          "the same k and the same rounds")
    check(not glob.glob(os.path.join(wd, "runs", "*", "checkpoint_*.h5")),
          "no checkpoint link left behind by a finished continuation")
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")


main()
