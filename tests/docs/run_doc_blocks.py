#!/usr/bin/env python3
"""ctest docs_*: run the shell blocks a page marks as runnable, in a fresh temporary folder.

A block is runnable when the line before its opening ```sh fence is `<!-- doc-test -->`. The
runnable blocks of one page run in order as one `bash -e` script (a later block may use what an
earlier one wrote), with the folder of MDPORE (the built binary) first on PATH. Fails on a
non-zero exit, or when the page has no runnable block.

usage: run_doc_blocks.py MDPORE PAGE.md
"""
import os
import subprocess
import sys
import tempfile

MARK = "<!-- doc-test -->"


def blocks(path):
    lines = open(path, encoding="utf-8").read().split("\n")
    out, i = [], 0
    while i < len(lines):
        if lines[i].strip() == MARK and i + 1 < len(lines) and lines[i + 1].strip() == "```sh":
            j = i + 2
            while j < len(lines) and lines[j].strip() != "```":
                j += 1
            out.append("\n".join(lines[i + 2:j]))
            i = j
        i += 1
    return out


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    mdpore, page = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    found = blocks(page)
    if not found:
        sys.exit(f"{page}: no block marked {MARK}")
    env = dict(os.environ, PATH=os.path.dirname(mdpore) + os.pathsep + os.environ.get("PATH", ""))
    with tempfile.TemporaryDirectory(prefix="mdpore-doctest-") as work:
        script = "set -e\n" + "\n".join(found) + "\n"
        p = subprocess.run(["bash", "-c", script], cwd=work, env=env, capture_output=True, text=True)
        sys.stdout.write(p.stdout[-4000:])
        sys.stderr.write(p.stderr[-4000:])
        print(f"{os.path.basename(page)}: {len(found)} runnable block(s), exit {p.returncode}")
        return 1 if p.returncode else 0


if __name__ == "__main__":
    sys.exit(main())
