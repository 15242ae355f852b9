#!/usr/bin/python3
"""ctest docs_structure: every docs page has the parts of the docs standard, and every reference to
a section of a docs page points at a heading that exists.

1. Parts. A user-facing page of docs/ has a "## " heading for each of the five parts: what it is
   for, how to use it, the reference of its options or keys, the validation that backs it, its
   limits (the keywords of PARTS below). The internal pages and the tutorial have their own parts
   (PAGE_PARTS). The pages of NOT_YET are not checked yet.
2. References, in the sources, scripts, CMake files and Markdown of the repository (folders named
   build*, hidden folders, shared/ and CHANGELOG.md, a record of past versions, left out):
   - `docs/PAGE.md section N` (also `sections N and M`, `sections N, M`, `section N.M`): PAGE has a
     heading whose text starts with that number;
   - `PAGE.md, "Title"` and `PAGE.md, section "Title"`: PAGE has a heading that starts with Title
     (a leading "N. " of the heading ignored);
   - `PAGE.md#anchor` (Markdown links): PAGE has a heading with that anchor (GitHub's rule).
   PAGE is a page of docs/ written as `docs/PAGE.md` or as a bare `PAGE.md` (a path with another
   folder, e.g. shared/reference/physics.md, is not a docs page). A reference written in a page of
   NOT_YET is listed as a note (its restructure fixes it), every other one must hold.
Each failure names the page and part, or the file and line of the reference and what it expected.
usage: check_docs_structure.py ROOT"""
import os
import re
import sys

# The five parts of a user-facing page: a "## " heading matching each pattern (case-insensitive).
PARTS = {
    "what it is for": r"what (it|they|this|the \w+) (is|are) for",
    "how to use it": r"how to use|quick start|usage",
    "reference": r"reference|\bkeys\b|\boptions\b",
    "validation": r"validation|verification",
    "limits": r"limits",
}
INTERNAL = {
    "what it is for": PARTS["what it is for"],
    "how it works": r"how (it|they) works?",
    "how to extend it": r"how to extend|adding an? ",
    "validation": PARTS["validation"],
    "limits": PARTS["limits"],
}
PAGE_PARTS = {
    "architecture.md": INTERNAL,
    "engine-core.md": INTERNAL,
    # internal, with the user-facing GPU options (--backend, --skin, --gpu-memory, rng, precision)
    "engine-cuda.md": dict(INTERNAL, **{"how to use it": PARTS["how to use it"]}),
    # a walk-through: what it shows, its numbered steps, and where it stops
    "tutorial.md": {"what it is for": PARTS["what it is for"], "steps": r"^1\. ",
                    "limits": PARTS["limits"]},
}
# Not yet restructured to the standard (their restructure is a later step): remove a page from
# this list when it is done, and the check above then holds it to the five parts.
NOT_YET = set()
SKIP_DIRS = {"shared", "node_modules", "__pycache__"}
SCANNED = (".c", ".h", ".cu", ".cuh", ".py", ".sh", ".md", ".txt", ".cmake", ".yaml", ".in")


def headings(text):
    """(level, text) of the Markdown headings outside fenced blocks."""
    out = []
    for line in re.sub(r"```.*?```", "", text, flags=re.S).splitlines():
        m = re.match(r"^(#{1,6}) (.*?)\s*#*\s*$", line)
        if m:
            out.append((len(m.group(1)), m.group(2)))
    return out


def slugs(heads):
    """GitHub's anchors of the headings: lower case, punctuation dropped, spaces to hyphens,
    repeats numbered -1, -2, ..."""
    seen, out = {}, set()
    for _, h in heads:
        s = re.sub(r"[^\w\- ]", "", h.replace("`", "").lower()).replace(" ", "-")
        n = seen.get(s, 0)
        seen[s] = n + 1
        out.add(s if n == 0 else "%s-%d" % (s, n))
    return out


JOIN = re.compile(r"\n[ \t]*(?:#+|//|\*|--)?[ \t]*")


def line_in(text, pos):
    """The line of `text` that holds offset `pos` of JOIN.sub(" ", text)."""
    line, shift = 1, 0
    for m in JOIN.finditer(text):
        if m.start() - shift >= pos:
            break
        shift += len(m.group(0)) - 1
        line += 1
    return line


def norm(t):
    return re.sub(r"\s+", " ", t.replace("`", "").strip()).lower()


def main():
    root = os.path.abspath(sys.argv[1])
    docs = os.path.join(root, "docs")
    pages = {f: open(os.path.join(docs, f), encoding="utf-8").read()
             for f in sorted(os.listdir(docs)) if f.endswith(".md")}
    heads = {f: headings(t) for f, t in pages.items()}
    failures = []

    # --- 1. the parts of every page
    for f in sorted(pages):
        if f in NOT_YET:
            print("note: docs/%s: not yet restructured (NOT_YET), parts not checked" % f)
            continue
        parts = PAGE_PARTS.get(f, PARTS)
        h2 = [h for lvl, h in heads[f] if lvl == 2]
        missing = [p for p, rx in parts.items() if not any(re.search(rx, h, re.I) for h in h2)]
        if missing:
            failures.append("docs/%s: no '## ' heading for the part(s) %s (headings: %s)"
                            % (f, ", ".join(repr(m) for m in missing), "; ".join(h2)))
    for f in sorted(NOT_YET - set(pages)):
        failures.append("NOT_YET names docs/%s, which does not exist" % f)

    # --- 2. references to sections
    page_rx = r"(?:(?:\.\./)?docs/|(?<![\w/.-]))(%s)" % "|".join(re.escape(p) for p in pages)
    number_rx = re.compile(page_rx + r"\)?,? sections? ((?:\d+(?:\.\d+)*(?:,? (?:and )?)?)+)")
    title_rx = re.compile(page_rx + r"\)?, (?:section )?\"([^\"]{1,120})\"")
    anchor_rx = re.compile(page_rx + r"#([\w-]+)")
    n_refs = 0
    for dirpath, dirnames, filenames in os.walk(root):
        rel_dir = os.path.relpath(dirpath, root)
        dirnames[:] = [d for d in dirnames
                       if d not in SKIP_DIRS and not d.startswith(("build", "."))]
        for name in filenames:
            rel = os.path.normpath(os.path.join(rel_dir, name))
            if rel == "CHANGELOG.md" or not (name.endswith(SCANNED) or name == "CMakeLists.txt"):
                continue
            try:
                text = open(os.path.join(dirpath, name), encoding="utf-8").read()
            except (UnicodeDecodeError, OSError):
                continue
            # a reference may wrap: join the lines, dropping the comment leaders of the next line
            flat = JOIN.sub(" ", text)

            def line_of(pos):
                return line_in(text, pos)

            for m in number_rx.finditer(flat):
                page = m.group(1)
                for num in re.findall(r"\d+(?:\.\d+)*", m.group(2)):
                    n_refs += 1
                    ok = any(re.match(re.escape(num) + r"(?:\.(?!\d)|\s)", h) for _, h in heads[page])
                    if not ok:
                        failures.append("%s:%d: '%s' cites docs/%s section %s: no heading '%s. ...' "
                                        "there" % (rel, line_of(m.start()), m.group(0)[:60], page,
                                                   num, num))
            for m in title_rx.finditer(flat):
                page, title = m.group(1), norm(m.group(2))
                n_refs += 1
                ok = any(norm(re.sub(r"^\d+(\.\d+)*\.? ", "", h)).startswith(title) or
                         norm(h).startswith(title) for _, h in heads[page])
                if not ok:
                    failures.append("%s:%d: cites docs/%s, \"%s\": no heading starting so there"
                                    % (rel, line_of(m.start()), page, m.group(2)))
            for m in anchor_rx.finditer(flat):
                page, anchor = m.group(1), m.group(2)
                n_refs += 1
                if anchor not in slugs(heads[page]):
                    failures.append("%s:%d: links docs/%s#%s: no heading with that anchor there"
                                    % (rel, line_of(m.start()), page, anchor))
    notes = [f for f in failures if re.match(r"docs/(%s):\d+:" % "|".join(map(re.escape, NOT_YET)), f)]
    failures = [f for f in failures if f not in notes]
    for f in notes:
        print("note (a page not yet restructured): " + f)
    for f in failures:
        print("FAIL " + f)
    print("%d pages (%d not yet restructured), %d section references checked, %d failure(s)"
          % (len(pages), len(NOT_YET & set(pages)), n_refs, len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
