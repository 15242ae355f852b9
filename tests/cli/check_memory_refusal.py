"""A command refused for memory before it allocates what it was asked for.

Usage: check_memory_refusal.py WORKDIR [--copy FILE]... [--sparse NAME BYTES]...
           [--yaml-list NAME KEY COUNT]... [--limit BYTES] [--baseline ARGS] [--max-growth-mb MB]
           [--expect TEXT]... -- CMD...

Copies each FILE into WORKDIR, makes each NAME there a sparse file of BYTES zero bytes (a large
image that takes no disk) or, with --yaml-list, a YAML file whose KEY is a flow list of COUNT
zeros (a configuration of many nodes), then runs CMD in WORKDIR with MDPORE_MEMORY_LIMIT=BYTES. It must exit
non-zero with every TEXT in its stderr. With --baseline (a command line, run the same way without
the limit: the same start-up and reads, without the allocation refused), the peak resident memory
of CMD (getrusage of the child: ru_maxrss) may exceed the baseline's by at most --max-growth-mb:
the refusal came before the large arrays were made, not after.
"""
import argparse
import os
import shlex
import shutil
import subprocess
import sys


def run(args, cwd, env, tag):
    """Run args; return (exit code, stderr text, peak RSS in MB)."""
    out_path, err_path = os.path.join(cwd, tag + ".out"), os.path.join(cwd, tag + ".err")
    with open(out_path, "w") as fo, open(err_path, "w") as fe:
        proc = subprocess.Popen(args, stdout=fo, stderr=fe, cwd=cwd, env=env)
        _, status, usage = os.wait4(proc.pid, 0)
    with open(err_path) as f:
        err = f.read()
    return os.waitstatus_to_exitcode(status), err, usage.ru_maxrss / 1024.0


def main():
    argv = sys.argv[1:]
    if "--" not in argv:
        sys.exit(__doc__)
    cut = argv.index("--")
    ap = argparse.ArgumentParser()
    ap.add_argument("workdir")
    ap.add_argument("--copy", action="append", default=[])
    ap.add_argument("--sparse", nargs=2, action="append", default=[])
    ap.add_argument("--yaml-list", nargs=3, action="append", default=[])
    ap.add_argument("--limit")
    ap.add_argument("--baseline")
    ap.add_argument("--max-growth-mb", type=float, default=25.0)
    ap.add_argument("--expect", action="append", default=[])
    o = ap.parse_args(argv[:cut])
    cmd = argv[cut + 1:]
    work = os.path.abspath(o.workdir)
    os.makedirs(work, exist_ok=True)
    for f in o.copy:
        shutil.copy(f, work)
    for name, size in o.sparse:
        with open(os.path.join(work, name), "wb") as f:
            f.truncate(int(size))
    for name, key, count in o.yaml_list:
        with open(os.path.join(work, name), "w") as f:
            f.write("%s: [%s]\n" % (key, ",".join(["0"] * int(count))))
    env = dict(os.environ)
    env.pop("MDPORE_MEMORY_LIMIT", None)
    base_mb = None
    if o.baseline:
        rc, err, base_mb = run(shlex.split(o.baseline), work, env, "baseline")
        print("baseline: exit %d, peak RSS %.1f MB" % (rc, base_mb))
    if o.limit:
        env["MDPORE_MEMORY_LIMIT"] = o.limit
    rc, err, peak_mb = run(cmd, work, env, "refused")
    print("refused: exit %d, peak RSS %.1f MB\n%s" % (rc, peak_mb, err))
    if rc == 0:
        sys.exit("FAIL: the command was not refused (exit 0)")
    if rc < 0 or rc > 128:
        sys.exit("FAIL: the command crashed (exit %d)" % rc)
    missing = [t for t in o.expect if t not in err]
    if missing:
        sys.exit("FAIL: stderr lacks: %s" % "; ".join(repr(t) for t in missing))
    if base_mb is not None:
        growth = peak_mb - base_mb
        print("peak RSS growth over the baseline: %.1f MB (allowed %.1f)" % (growth,
                                                                            o.max_growth_mb))
        sanitized = os.environ.get("MDPORE_SANITIZED", "OFF") not in ("", "0", "OFF")
        if sanitized:
            print("not checked in a sanitizer build: ASan's quarantine keeps freed memory resident")
        elif growth > o.max_growth_mb:
            sys.exit("FAIL: the refused command grew %.1f MB over the baseline: it allocated "
                     "before refusing" % growth)
    print("ok")


if __name__ == "__main__":
    main()
