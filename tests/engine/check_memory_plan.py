"""The memory plan is real: mdpore run --explain's total per rank against the run's measured peak.

Usage: check_memory_plan.py MDPORE SCENE WORKDIR [FACTOR]

Runs `mdpore run --explain SCENE` and `mdpore run SCENE` (one rank each, in WORKDIR) and reads each
process's peak resident memory (getrusage of the child: ru_maxrss). The run's growth over the
explain's (the same start-up, libraries and scene, but no particles) must be within FACTOR (1.5) of
the plan's host total either way: an estimate that is off by more would refuse runs that fit, or
let through runs that do not.
"""
import os
import re
import subprocess
import sys


def peak_kb(args, cwd, tag):
    """Run args; return (exit code, stdout text, peak RSS in kB)."""
    out_path, err_path = os.path.join(cwd, tag + ".out"), os.path.join(cwd, tag + ".err")
    with open(out_path, "w") as fo, open(err_path, "w") as fe:
        proc = subprocess.Popen(args, stdout=fo, stderr=fe, cwd=cwd)
        _, status, usage = os.wait4(proc.pid, 0)
        proc.returncode = os.waitstatus_to_exitcode(status)
    with open(out_path) as f:
        out = f.read()
    if proc.returncode != 0:
        with open(err_path) as f:
            sys.exit("%s exited %d:\n%s%s" % (" ".join(args), proc.returncode, out, f.read()))
    return out, usage.ru_maxrss


def to_bytes(text):
    value, unit = text.split()
    return float(value) * {"kB": 1e3, "MB": 1e6, "GB": 1e9}[unit]


def main():
    if os.environ.get("MDPORE_SANITIZED", "OFF") not in ("", "0", "OFF"):
        print("skipped: a sanitizer build (MDPORE_SANITIZE): ASan's shadow memory and redzones "
              "change the measured peak, which the plan does not count")
        sys.exit(77)
    exe, scene, work = (os.path.abspath(a) for a in sys.argv[1:4])
    factor = float(sys.argv[4]) if len(sys.argv) > 4 else 1.5
    os.makedirs(work, exist_ok=True)
    explain, base_kb = peak_kb([exe, "run", "--explain", "--backend", "cpu", scene], work, "explain")
    m = re.search(r"^  total \(host\)\s+([0-9.e+]+ [kMG]B)$", explain, re.M)
    if not m:
        sys.exit("no 'total (host)' line in the --explain output:\n" + explain)
    plan = to_bytes(m.group(1))
    items = [i for i in re.findall(r"^  (\S.*?)\s{2,}([0-9.e+]+ [kMG]B)$", explain, re.M)
             if not i[0].startswith("total")]
    _, run_kb = peak_kb([exe, "run", "--backend", "cpu", scene], work, "run")
    growth = (run_kb - base_kb) * 1024.0
    ratio = plan / growth if growth > 0 else float("inf")
    print("plan items: " + "; ".join("%s %s" % i for i in items))
    print("plan total %.4g MB; peak RSS: explain %.4g MB, run %.4g MB, growth %.4g MB; "
          "plan / growth = %.3f (allowed %.3g..%.3g)"
          % (plan / 1e6, base_kb * 1024 / 1e6, run_kb * 1024 / 1e6, growth / 1e6, ratio,
             1 / factor, factor))
    if not (1 / factor <= ratio <= factor):
        sys.exit("the memory plan is off by more than a factor %g" % factor)


if __name__ == "__main__":
    main()
