#!/usr/bin/python3
"""ctest cli_help_docs: the help of mdpore and of every subcommand.

  mdpore --help and mdpore CMD --help (-h: the same text, checked where a parser of its own
  reads it): exit 0, fit an 80 x 24 terminal (at most 80 columns, at most 24 lines) and end with
  a line "More: docs/PAGE.md ..." naming pages that exist; CMD's purpose, after its usage lines,
  is one line;
  mdpore CMD --help-all (every option, for a pager): exit 0, at most 80 columns, ends with the same
  More line, and holds every option --help shows (and at least as many lines).
usage: check_help_docs.py MDPORE ROOT [COMMAND ...]"""
import os
import re
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

WIDTH, HEIGHT = 80, 24
mdpore, root, commands = sys.argv[1], sys.argv[2], sys.argv[3:]
bad = 0


def run(cmd_flag):
    """(exit, stdout + stderr) of `mdpore CMD FLAG`, with a TMPDIR of its own: Open MPI singletons
    started at once race on a shared session directory ("A call to mkdir was unable to create the
    desired directory", open-mpi/ompi#8510; 2 of 150 calls 6 at a time, none with their own)."""
    with tempfile.TemporaryDirectory() as tmp:
        p = subprocess.run([mdpore, *cmd_flag[0].split(), cmd_flag[1]], capture_output=True,
                           text=True, env=dict(os.environ, TMPDIR=tmp))
    return p.returncode, p.stdout + p.stderr


# every call first (4 at a time: each mostly waits on MPI's start), then the checks
# -h for mdpore itself, the getopt parsers (their own 'h') and one of the cli_help_flag ones
SHORT_FLAG = {"", "run", "forces", "build patches", "image"}
calls = [("", "--help"), ("", "-h")] + [(c, f) for c in commands for f in ("--help", "--help-all")]
calls += [(c, "-h") for c in commands if c in SHORT_FLAG]
with ThreadPoolExecutor(4) as pool:
    texts = dict(zip(calls, pool.map(run, calls)))


def helptext(cmd, flag):
    return texts[cmd, flag]


def options(text):
    """The options a help text names, less the two that ask for help."""
    return set(re.findall(r"(?<![\w-])(--[a-z][\w-]*)", text)) - {"--help", "--help-all"}


def check(label, ok, detail):
    global bad
    print(f"{'ok  ' if ok else 'FAIL'} {label}: {detail}")
    bad += not ok


def more_line(label, rc, text):
    """The More line of a help text (None when it has none); checks exit, size of the lines."""
    lines = text.rstrip("\n").split("\n")
    last = lines[-1] if lines else ""
    pages = re.findall(r"docs/[\w.-]+\.md", last)
    missing = [pg for pg in pages if not os.path.exists(os.path.join(root, pg))]
    wide = max((len(line) for line in lines), default=0)
    ok = rc == 0 and last.startswith("More: docs/") and pages and not missing and wide <= WIDTH
    check(label, ok, f"exit {rc}, {len(lines)} lines, widest {wide} (at most {WIDTH}), last line "
          f"{last!r}, pages {pages} (missing {missing})")
    return last if ok else None, len(lines)


for cmd in [""] + commands:
    name = ("mdpore " + cmd).strip()
    rc, short = helptext(cmd, "--help")
    last, height = more_line(name + " --help", rc, short)
    check(name + " --help", height <= HEIGHT, f"{height} lines (at most {HEIGHT})")
    if cmd in SHORT_FLAG:
        check(name + " -h", helptext(cmd, "-h") == (rc, short), "the same text as --help")
    if not cmd:
        continue
    # the purpose: one line, the first after the usage lines (those start with "usage:" or a space)
    lines = short.split("\n")
    k = next((i for i in range(1, len(lines)) if not lines[i].startswith(" ")), len(lines) - 1)
    after = lines[k + 1] if k + 1 < len(lines) else ""
    check(name + " --help", after.startswith(("  ", "All ", "The details:", "More:")),
          f"a one-line purpose after the usage: {lines[k]!r}")
    rc, full = helptext(cmd, "--help-all")
    last_all, height_all = more_line(name + " --help-all", rc, full)
    check(name + " --help-all", last_all == last and height_all >= height,
          f"ends with the More line of --help ({last_all == last}), {height_all} lines >= {height}")
    missing = sorted(options(short) - options(full))
    check(name + " --help-all", not missing,
          f"{len(options(full))} options, every option of --help in it (missing {missing})")
sys.exit(1 if bad else 0)
