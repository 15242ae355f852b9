#!/usr/bin/python3
"""ctest campaign_jobs: `mdpore permeability --jobs N`, several runs of a campaign at once (CPU).

The slit of test_permeability.py (`mdpore image make slit --width 8 --wall 4 --length 12 --depth 8`,
rc_per_voxel 0.5, flow along x), 5 gradients of <= STEPS steps on 1 rank each.

Asserted:
 1. --jobs 0, -1 and x refused naming the option (exit 2); campaign.jobs: 0 in an `mdpore couple`
    config refused naming the key;
 2. a campaign at --jobs 1 in a fresh folder and a fresh wall-patch cache (the reference), then the
    same campaign at --jobs 2 in another fresh folder and cache, with this test holding the lock of
    the cache's wall patch database while it starts: both running runs wait (run.log says so), none
    builds it and none finishes while the lock is held; once released one run builds it, the other
    reads it ("built by the other process"), and the cache holds that one database, byte-identical
    to the reference's;
 3. the --jobs 2 campaign's flow table is byte-identical to the --jobs 1 one's (the campaign folder's
    name, in the comments naming each run's folder, aside), every run's q the same bits, the same k (the runs are independent processes: their results do not depend on
    what runs beside them);
 4. a --jobs 2 campaign killed (SIGTERM) while two runs are going leaves no process of its session
    behind and no summary in an unfinished run's folder (every summary left parses); the rerun
    reuses every finished run (summary untouched) and runs exactly the others; the table is again
    byte-identical to the reference.
"""
import fcntl
import filecmp
import glob
import json
import os
import shutil
import signal
import subprocess
import sys
import time

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "campaign_jobs_out"))
STEPS = os.environ.get("MDPORE_TEST_STEPS", "4000")
GRADIENTS = "0.06,0.1,0.14,0.18,0.22"
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def mdpore(*args, env=None):
    return subprocess.run([MDPORE, *args], capture_output=True, text=True, cwd=OUT, env=env)


def campaign_args(wd, jobs):
    return ["permeability", "slit.h5", "--axis", "x", "--gradients", GRADIENTS, "--max-steps", STEPS,
            "--target-error", "0.04", "--np", "1", "--jobs", jobs, "--workdir", wd]


def with_cache(name):
    cache = os.path.join(OUT, name)
    return dict(os.environ, MDPORE_CACHE_DIR=cache), cache


def run_dirs(wd):
    man = os.path.join(wd, "campaign.txt")
    if not os.path.exists(man):
        return []
    return [l.split()[3] for l in open(man) if l.startswith("run: ")]


def q_values(wd):
    out = []
    for d in run_dirs(wd):
        s = os.path.join(d, "summary.json")
        out.append(json.load(open(s)).get("flux", {}).get("q") if os.path.exists(s) else None)
    return out


def k_of(wd):
    p = os.path.join(wd, "permeability.json")
    return json.load(open(p)).get("axes", {}).get("x", {}).get("k_rc2") if os.path.exists(p) else None


def same_table(a, wa, b, wb):
    """Byte-identical flow tables, but for the campaign folder in the comments that name each run's
    folder (runs/x-HASH: the same hash in both, the scenes being the same)."""
    if not (os.path.exists(a) and os.path.exists(b)):
        return False
    return open(a, "rb").read().replace(wa.encode(), b"WORKDIR") == open(b, "rb").read().replace(wb.encode(), b"WORKDIR")


def session_processes(sid):
    """Live processes of session sid (the campaign's: started with start_new_session), as 'pid sid cmd'.
    Zombies (state Z) have exited already: where the container's init does not reap orphans they stay
    listed as <defunct>, holding no memory, files or CPU, so they are not processes left running."""
    p = subprocess.run(["ps", "-eo", "pid=,sid=,stat=,args="], capture_output=True, text=True).stdout
    live = []
    for l in p.splitlines():
        f = l.split(None, 3)
        if len(f) == 4 and f[1] == str(sid) and not f[2].startswith("Z"):
            live.append(f"{f[0]} {f[1]} {f[3]}")
    return live


def session_processes_after(sid, wait_s=10.0):
    """The session's live processes once they have had wait_s to exit (a signal is not instant)."""
    deadline = time.time() + wait_s
    left = session_processes(sid)
    while left and time.time() < deadline:
        time.sleep(0.1)
        left = session_processes(sid)
    return left


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    p = mdpore("image", "make", "slit", "--width", "8", "--wall", "4", "--length", "12", "--depth", "8",
               "-o", "slit.h5")
    if p.returncode:
        sys.exit("image make failed: " + p.stderr)

    # 1. bad values
    for bad in ["0", "-1", "x"]:
        p = mdpore("permeability", "slit.h5", "--axis", "x", "--jobs", bad, "--emit-scenes", "bad")
        check(p.returncode == 2 and f"--jobs: expected a positive number of runs at once, or auto, got '{bad}'"
              in p.stderr, f"--jobs {bad} refused naming the option (exit {p.returncode}: {p.stderr.strip()[:200]})")
    with open(os.path.join(OUT, "bad_jobs.yaml"), "w") as f:
        f.write("image: slit.h5\naxis: x\ncampaign: {jobs: 0}\n")
    p = mdpore("couple", "bad_jobs.yaml")
    check(p.returncode == 1 and "'campaign.jobs'" in p.stderr,
          f"mdpore couple: campaign.jobs: 0 refused naming the key (exit {p.returncode}: {p.stderr.strip()[:200]})")

    # 2. the reference at --jobs 1
    ref = os.path.join(OUT, "jobs1")
    env1, cache1 = with_cache("cache1")
    t0 = time.time()
    p = mdpore(*campaign_args(ref, "1"), env=env1)
    t1 = time.time() - t0
    print(p.stderr[-3000:])
    check(p.returncode in (0, 3), f"--jobs 1 campaign ran (exit {p.returncode}, {t1:.1f} s)")
    check(" running," not in p.stderr, "--jobs 1: the progress lines as before (no 'running' count)")
    dbs = sorted(glob.glob(os.path.join(cache1, "wall-patches-*.h5")))
    check(len(dbs) == 1, f"--jobs 1 built one wall patch database: {dbs}")
    if len(dbs) != 1:
        sys.exit("no database to lock: " + "\n".join(failures))
    db_name = os.path.basename(dbs[0])

    # the same at --jobs 2, the database's lock held by this test while the runs start
    wd2 = os.path.join(OUT, "jobs2")
    env2, cache2 = with_cache("cache2")
    os.makedirs(cache2)
    lock = open(os.path.join(cache2, db_name + ".lock"), "w")
    fcntl.flock(lock, fcntl.LOCK_EX)
    t0 = time.time()
    proc = subprocess.Popen([MDPORE, *campaign_args(wd2, "2")], cwd=OUT, env=env2, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    waiting = []
    deadline = time.time() + 120
    while time.time() < deadline and proc.poll() is None and len(waiting) < 2:
        waiting = [d for d in run_dirs(wd2) if os.path.exists(os.path.join(d, "run.log")) and
                   "another process is building it: waiting" in open(os.path.join(d, "run.log")).read()]
        time.sleep(0.1)
    time.sleep(1.0)
    check(len(waiting) == 2, f"--jobs 2: two runs at once, both waiting for the locked database ({len(waiting)})")
    check(not os.path.exists(os.path.join(cache2, db_name)) and
          not any(os.path.exists(os.path.join(d, "summary.json")) for d in run_dirs(wd2)),
          "while the lock is held no run builds the database or finishes")
    fcntl.flock(lock, fcntl.LOCK_UN)
    lock.close()
    out, err = proc.communicate(timeout=600)
    t2 = time.time() - t0
    print(err[-3000:])
    check(proc.returncode in (0, 3), f"--jobs 2 campaign ran (exit {proc.returncode}, {t2:.1f} s)")
    check("up to 2 runs at once (--jobs 2)" in err and ", 2 running," in err and "progress 5/5 runs done, 0 running" in err,
          "--jobs 2: stderr says so, and the progress lines count the running runs")
    logs = [open(os.path.join(d, "run.log")).read() for d in run_dirs(wd2)]
    check(sum("built by the other process, read" in l for l in logs) == 1,
          "after the lock: one run built the database, one waited for it and read it")
    check(sorted(os.listdir(cache2)) == sorted([db_name, db_name + ".lock"]),
          f"the cache holds the one database (and its lock file), no temporary: {sorted(os.listdir(cache2))}")
    check(os.path.exists(os.path.join(cache2, db_name)) and
          filecmp.cmp(os.path.join(cache2, db_name), dbs[0], shallow=False),
          "the database built under --jobs 2 is byte-identical to --jobs 1's")

    # 3. the same table, q and k
    t_ref, t_2 = os.path.join(ref, "flow_x.csv"), os.path.join(wd2, "flow_x.csv")
    check(same_table(t_ref, ref, t_2, wd2), "--jobs 2 flow table byte-identical to --jobs 1's (but the folder's name)")
    q1, q2 = q_values(ref), q_values(wd2)
    check(len(q1) == 5 and None not in q1 and q1 == q2, f"every run's q the same bits: {q1} vs {q2}")
    check(k_of(ref) is not None and k_of(ref) == k_of(wd2), f"the same k: {k_of(ref)} vs {k_of(wd2)}")
    print(f"wall time: --jobs 1 {t1:.1f} s, --jobs 2 {t2:.1f} s (with the test's lock hold)")

    # 4. killed while two runs are going, then resumed
    wd3 = os.path.join(OUT, "killed")
    proc = subprocess.Popen([MDPORE, *campaign_args(wd3, "2")], cwd=OUT, env=env2, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)
    killed, running_then = False, []
    deadline = time.time() + 300
    while time.time() < deadline and proc.poll() is None:
        dirs = run_dirs(wd3)
        started = [d for d in dirs if os.path.exists(os.path.join(d, "run.log"))]
        going = [d for d in started if not os.path.exists(os.path.join(d, "summary.json"))]
        runs = [l for l in session_processes(proc.pid) if " run scene.yaml" in l]
        if len(started) >= 3 and len(going) == 2 and len(runs) == 2:
            proc.send_signal(signal.SIGTERM)
            killed, running_then = True, going
            break
        time.sleep(0.02)
    proc.communicate(timeout=120)
    check(killed and proc.returncode != 0, f"campaign killed while two runs were going (exit {proc.returncode})")
    left = session_processes_after(proc.pid)
    check(left == [], f"no live process of the killed campaign left (zombies excepted): {left}")
    finished = [d for d in run_dirs(wd3) if os.path.exists(os.path.join(d, "summary.json"))]
    unfinished = [d for d in run_dirs(wd3) if d not in finished]
    ok_json = True
    for d in finished:
        try:
            json.load(open(os.path.join(d, "summary.json")))
        except ValueError:
            ok_json = False
    check(ok_json and all(not os.path.exists(os.path.join(d, "summary.json")) for d in running_then if d in unfinished),
          f"after the kill: {len(finished)} finished (summaries whole), {len(unfinished)} without a summary")
    check(len(finished) >= 1 and len(unfinished) >= 2, "some runs finished and some not at the kill")
    stats = {d: os.stat(os.path.join(d, "summary.json")) for d in finished}
    p = mdpore(*campaign_args(wd3, "2"), env=env2)
    check(p.returncode in (0, 3), f"rerun exit {p.returncode}")
    check(all(f"reused {d}" in p.stderr for d in finished) and p.stderr.count("reused ") == len(finished),
          f"the rerun reuses the {len(finished)} finished runs")
    check(all(f"running in {d}" in p.stderr for d in unfinished) and p.stderr.count("running in") == len(unfinished),
          f"the rerun runs exactly the {len(unfinished)} unfinished ones")
    check(all(os.stat(os.path.join(d, "summary.json")).st_mtime_ns == s.st_mtime_ns for d, s in stats.items()),
          "the finished runs' summaries were not rewritten")
    t_3 = os.path.join(wd3, "flow_x.csv")
    check(same_table(t_ref, ref, t_3, wd3),
          "killed and resumed at --jobs 2: flow table byte-identical to --jobs 1's (but the folder's name)")

    if failures:
        print(f"{len(failures)} check(s) failed:\n  " + "\n  ".join(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
