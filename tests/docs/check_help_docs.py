#!/usr/bin/python3
"""ctest cli_help_docs: every subcommand's --help exits 0, ends with a line "More: docs/PAGE.md ..."
naming pages that exist, and stays within 130 columns (the long option tables wrap before that).
usage: check_help_docs.py MDPORE ROOT [COMMAND ...]"""
import os
import re
import subprocess
import sys

mdpore, root, commands = sys.argv[1], sys.argv[2], sys.argv[3:]
bad = 0
for cmd in commands:
    p = subprocess.run([mdpore, *cmd.split(), "--help"], capture_output=True, text=True)
    text = p.stdout + p.stderr
    lines = text.rstrip("\n").split("\n")
    last = lines[-1] if lines else ""
    pages = re.findall(r"docs/[\w.-]+\.md", last)
    missing = [pg for pg in pages if not os.path.exists(os.path.join(root, pg))]
    wide = max((len(l) for l in lines), default=0)
    ok = p.returncode == 0 and last.startswith("More: docs/") and pages and not missing and wide <= 130
    print(f"{'ok  ' if ok else 'FAIL'} mdpore {cmd} --help: exit {p.returncode}, last line {last!r}, "
          f"pages {pages} (missing {missing}), widest line {wide}")
    bad += not ok
sys.exit(1 if bad else 0)
