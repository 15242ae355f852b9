#!/usr/bin/python3
"""ctest docs_keys: the keys the readers accept and the keys the docs describe are the same set.

Accepted keys come from the readers themselves: with MDPORE_KEY_LOG=FILE every key list a reader
checks is appended to FILE (common/yaml_tree.c, yt_record_keys: "PATH<TAB>KEY KEY ... [*]", "*"
where species names are accepted too). The replay entries of the fuzz targets (tests/fuzz: the
scene, darcy config and couple config readers) read every scene and config of the repository (the
fuzz seed corpus, tests/engine/scenes, cases/, tests/upscale) and every ```yaml block of the pages
below, so every block of each reader is reached. A documented key inside a block that no input
reaches is listed as a note, not checked (its own key in the block above is): add an input that
reaches the block (a seed in tests/fuzz/corpus) to check it.

Documented keys:
  - docs/scene-format.md: the first column of every table whose header starts "| key" under a
    "### `BLOCK`" heading (`a`, `b` / `c`, `x.y`, `name: {k1, k2 (default)}` forms), the options
    column of the effects table, and the keys of its ```yaml blocks;
  - docs/darcy-config.md and docs/twophase-darcy.md (mdpore darcy), docs/coupling.md (mdpore
    couple): the keys of their ```yaml blocks (lines "# key: ..." that start an alternative are read
    too).
Checks, each failure naming the key:
  1. every documented key is accepted at that place;
  2. every accepted key is mentioned in its page: in backticks (alone, dotted or in a {...} list)
     in the section of its top-level block (scene-format.md: the "### `BLOCK`" section; the other
     pages: anywhere), or as a key of one of its ```yaml blocks;
  3. every option of each subcommand's --help-all (the complete option reference; --help shows
     the common ones) is mentioned in docs/ or README.md (in backticks or a code block), and
     every `mdpore CMD ... --opt` written in docs/ and README.md is an option of CMD's
     --help-all.
usage: check_keys_docs.py MDPORE BIN_DIR ROOT WORKDIR [COMMAND ...]"""
import glob
import os
import re
import subprocess
import sys

import yaml

mdpore, bindir, root, work = [os.path.abspath(a) for a in sys.argv[1:5]]
commands = sys.argv[5:]
work = os.path.abspath(work)
os.makedirs(work, exist_ok=True)
failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL " + msg, flush=True)


def read(rel):
    with open(os.path.join(root, rel)) as f:
        return f.read()


class KeyLoader(yaml.SafeLoader):
    """YAML as the readers see it: `no:`, `on:` and `yes:` are keys, not booleans (YAML 1.1)."""


KeyLoader.yaml_implicit_resolvers = {
    k: [(tag, rx) for tag, rx in v if tag != "tag:yaml.org,2002:bool"]
    for k, v in yaml.SafeLoader.yaml_implicit_resolvers.items()}


def block_variants(text):
    """The text of each ```yaml block of a page, twice: as written, and with each commented line
    that starts an alternative ("# key: v") uncommented (two variants: an alternative may exclude
    what the block has, e.g. `upscale:` and `sources:`)."""
    out = []
    for block in re.findall(r"```yaml\n(.*?)```", text, re.S):
        lines = []
        for line in block.splitlines():
            m = re.match(r"^(\s*)# ?([A-Za-z_][\w-]*:(\s.*)?)$", line)
            lines.append(m.group(1) + m.group(2) if m else line)
        out.append(block)
        if "\n".join(lines) != block:
            out.append("\n".join(lines) + "\n")
    return out


def yaml_blocks(text):
    """The parsed ```yaml blocks of a page (both variants; a variant that is no YAML is skipped)."""
    out = []
    for candidate in block_variants(text):
        try:
            docs = list(yaml.load_all(candidate, Loader=KeyLoader))
        except yaml.YAMLError:
            continue
        out.extend(d for d in docs if isinstance(d, (dict, list)))
    return out


def yaml_paths(node, prefix=""):
    """Dotted key paths of a YAML value ([] for list items)."""
    paths = []
    if isinstance(node, dict):
        for k, v in node.items():
            p = "%s%s%s" % (prefix, "." if prefix else "", k)
            paths.append(p)
            paths += yaml_paths(v, p)
    elif isinstance(node, list):
        for v in node:
            paths += yaml_paths(v, prefix + "[]")
    return paths


# ---- accepted keys, from the readers ----------------------------------------------------------
def record(entry, inputs, tag):
    log = os.path.join(work, "keys_%s.log" % tag)
    if os.path.exists(log):
        os.remove(log)
    exe = os.path.join(bindir, entry)
    if not os.path.exists(exe):
        return {}
    for i in range(0, len(inputs), 200):
        subprocess.run([exe, *inputs[i:i + 200]], env=dict(os.environ, MDPORE_KEY_LOG=log),
                       capture_output=True, cwd=work)
    catalog = {}
    if os.path.exists(log):
        for line in open(log):
            path, _, keys = line.rstrip("\n").partition("\t")
            path = re.sub(r"\[\d+\]", "[]", path)
            entry_keys, any_other = catalog.setdefault(path, (set(), [False]))
            for k in keys.split():
                if k == "*":
                    any_other[0] = True
                else:
                    entry_keys.add(k)
    return catalog


def normalise(catalog):
    """Paths under a mapping of free names (species, pairs) become '*': {path: (keys, any)}."""
    out = {}
    for path in sorted(catalog, key=lambda p: p.count(".")):
        keys, any_other = catalog[path]
        parts = path.split(".") if path else []
        norm = []
        for i, part in enumerate(parts):
            parent = ".".join(norm)
            name = part[:-2] if part.endswith("[]") else part
            pk, pa = out.get(parent, (set(), [False]))
            if name not in pk and pa[0]:
                part = "*" + ("[]" if part.endswith("[]") else "")
            norm.append(part)
        key = ".".join(norm)
        k0, a0 = out.setdefault(key, (set(), [False]))
        k0 |= keys
        a0[0] |= any_other[0]
    return out


def accepted(catalog, path):
    """Is the dotted documented path a key the reader accepts (free names matched by '*')? None
    when no input reached the block that holds it (its own key in the block above is checked)."""
    parts = path.split(".")
    here = ""
    for part in parts:
        listy = part.endswith("[]")
        name = part[:-2] if listy else part
        if here not in catalog:
            return None
        keys, any_other = catalog.get(here, (set(), [False]))
        if name in keys:
            step = name
        elif any_other[0]:
            step = "*"
        else:
            return False
        here = "%s%s%s%s" % (here, "." if here else "", step, "[]" if listy else "")
        if here not in catalog and here.replace("[]", "") + "[]" in catalog:
            here = here.replace("[]", "") + "[]"
    return True


def write_blocks(page, tag, edit=None):
    """The page's ```yaml blocks as reader inputs (`edit` adapts a block's text, e.g. its paths)."""
    files = []
    for i, text in enumerate(block_variants(read(page))):
        path = os.path.join(work, "%s_block%d.yaml" % (tag, i))
        with open(path, "w") as f:
            f.write(edit(text) if edit else text)
        files.append(path)
    return files


def inputs_of(patterns):
    files = []
    for pat in patterns:
        files += sorted(glob.glob(os.path.join(root, pat), recursive=True))
    return files


# ---- documented keys ---------------------------------------------------------------------------
def scene_sections(text):
    """{top-level block: section text} from the "### `BLOCK`" headings of scene-format.md."""
    sections, current = {}, None
    for line in text.splitlines():
        m = re.match(r"^(#{2,3}) (.*)", line)
        if m:
            names = re.findall(r"`([\w.]+)`", m.group(2)) if m.group(1) == "###" else []
            current = names if names else None
            for n in names:
                sections.setdefault(n, "")
            if m.group(1) == "##":
                current = None
        if current:
            for n in current:
                sections[n] += line + "\n"
    return sections


def cell_keys(cell):
    """Keys of a table's first cell: `a`, `a` / `b`, `x.y`, `name: {k1, k2 (d), k3}`."""
    keys = []
    for token in re.findall(r"`([^`]+)`", cell):
        m = re.match(r"^([\w.]+): \{(.*)\}$", token)
        if m:
            keys.append(m.group(1))
            depth, item, items = 0, "", []
            for ch in m.group(2):  # split the top level of the {...} list on commas
                depth += ch in "{[("
                depth -= ch in "}])"
                if ch == "," and depth == 0:
                    items.append(item)
                    item = ""
                else:
                    item += ch
            items.append(item)
            for it in items:
                w = re.match(r"\s*([A-Za-z_]\w*)", it)
                if w:
                    keys.append(m.group(1) + "." + w.group(1))
        elif re.match(r"^[\w.]+$", token):
            keys.append(token)
    return keys


def scene_documented(text):
    """(path, where) of every key in a key table, the effects table and the yaml blocks."""
    docs = []
    for block, body in scene_sections(text).items():
        rows = body.splitlines()
        in_table, kind = False, None
        for line in rows:
            if line.startswith("| key") or line.startswith("| effect"):
                in_table, kind = True, line.split("|")[1].strip()
                continue
            if not line.startswith("|"):
                in_table = False
                continue
            if not in_table or line.startswith("|---"):
                continue
            cells = [c.strip() for c in re.split(r"(?<!\\)\|", line)[1:-1]]
            if kind == "effect":
                for name in cell_keys(cells[0]):
                    docs.append(("effects." + name, "effects table"))
                    for opt in re.findall(r"`([A-Za-z_]\w*)(?::[^`]*)?`", cells[1]):
                        docs.append(("effects.%s.%s" % (name, opt), "effects table, options"))
            else:
                prefix = block + ("[]" if block == "species" else "")
                for k in cell_keys(cells[0]):
                    docs.append(("%s.%s" % (prefix, k), "### `%s` table" % block))
    for doc in yaml_blocks(text):
        for p in yaml_paths(doc):
            docs.append((p, "a yaml block"))
    return docs


def spans(text):
    """The `code spans` of a page's prose, paired within each paragraph (a stray backtick elsewhere
    cannot shift the pairing), fenced blocks left out."""
    prose = re.sub(r"```.*?```", "", text, flags=re.S)
    out = []
    for para in re.split(r"\n\s*\n", prose):
        out += re.findall(r"`([^`]+)`", para)
    return out


def mentioned(key, text):
    """The key in backticks (alone, dotted, or in a {...} list), or as a key of a yaml block."""
    k = re.escape(key)
    for span in spans(text):
        if re.search(r"(?<![\w-])%s(?![\w-])" % k, span):
            return True
    for block in re.findall(r"```yaml\n(.*?)```", text, re.S):
        if re.search(r"(^|[\s{,#-])%s:" % k, block, re.M):
            return True
    return False


def check_reader(name, catalog, documented, page_text, section_of=None):
    n_doc = n_acc = 0
    unreached = set()
    for path, where in documented:
        n_doc += 1
        verdict = accepted(catalog, path)
        if verdict is None:
            unreached.add(path)
        elif not verdict:
            fail("%s: documented key '%s' (%s) is not accepted by the reader" % (name, path, where))
    for path in sorted(unreached):  # e.g. a block added with its docs and no input reaching it yet
        print("note: %s: documented key '%s' not checked: no input reaches its block" % (name, path))
    for path, (keys, _) in sorted(catalog.items()):
        for k in sorted(keys):
            full = "%s%s%s" % (path, "." if path else "", k)
            text = section_of(full) if section_of else page_text
            n_acc += 1
            if not mentioned(k, text):
                fail("%s: accepted key '%s' is not documented (no `%s` in %s)" %
                     (name, full, k, "its section" if section_of else "the page"))
    print("%s: %d documented keys checked against %d accepted" % (name, n_doc, n_acc))


def main():
    # --- scene
    scene_text = read("docs/scene-format.md")
    scene_inputs = inputs_of(["tests/fuzz/corpus/scene/*", "tests/engine/**/*.yaml",
                              "cases/**/*.yaml", "validation/**/*.yaml", "bench/**/*.yaml"])
    scene_inputs += write_blocks("docs/scene-format.md", "scene")
    cat = normalise(record("fuzz_scene_replay", scene_inputs, "scene"))
    sections = scene_sections(scene_text)

    def scene_section(full):
        top = re.sub(r"\[\]", "", full.split(".")[0])
        if "." not in full:  # a top-level key: its own heading, or a mention under "## Keys"
            return sections.get(top, "") + scene_text.split("## Keys", 1)[-1].split("\n## ", 1)[0]
        return sections.get(top, "")
    check_reader("scene (docs/scene-format.md)", cat, scene_documented(scene_text), scene_text,
                 scene_section)
    # --- mdpore darcy: its config and the twophase block
    darcy_pages = read("docs/darcy-config.md") + read("docs/twophase-darcy.md")
    darcy_inputs = inputs_of(["tests/fuzz/corpus/darcy_config/*", "tests/upscale/**/*.yaml",
                              "cases/**/darcy*.yaml"])
    darcy_inputs += write_blocks("docs/darcy-config.md", "darcy")
    darcy_inputs += write_blocks("docs/twophase-darcy.md", "twophase")
    cat = normalise(record("fuzz_darcy_config_replay", darcy_inputs, "darcy"))
    if cat:
        documented = [(p, "a yaml block") for d in yaml_blocks(darcy_pages) for p in yaml_paths(d)]
        check_reader("mdpore darcy (docs/darcy-config.md, docs/twophase-darcy.md)", cat,
                     documented, darcy_pages)
    else:
        print("mdpore darcy: no reader built (PETSc off): skipped")
    # --- mdpore couple
    couple_text = read("docs/coupling.md")
    couple_inputs = inputs_of(["tests/fuzz/corpus/couple_config/*", "tests/coupling/**/*.yaml"])
    # the couple reader checks that its images exist: the blocks' image names point at one
    dummy = os.path.join(work, "sample.h5")
    open(dummy, "w").close()
    couple_inputs += write_blocks(
        "docs/coupling.md", "couple",
        lambda t: re.sub(r"^(#\s*)?(image|block_images): .*$",
                         lambda m: "image: " + dummy if m.group(2) == "image" else m.group(0),
                         t, flags=re.M))
    cat = normalise(record("fuzz_couple_config_replay", couple_inputs, "couple"))
    if cat:
        documented = [(p, "a yaml block") for d in yaml_blocks(couple_text) for p in yaml_paths(d)]
        check_reader("mdpore couple (docs/coupling.md)", cat, documented, couple_text)
    else:
        print("mdpore couple: no reader built (PETSc off): skipped")
    # --- command-line options
    all_docs = "".join(read(p) for p in ["README.md"] + sorted(
        os.path.relpath(f, root) for f in glob.glob(os.path.join(root, "docs", "*.md"))))
    helps = {}
    for cmd in commands:
        p = subprocess.run([mdpore, *cmd.split(), "--help-all"], capture_output=True, text=True)
        text = p.stdout + p.stderr
        helps[cmd] = set(re.findall(r"(?<![\w-])(--[a-z][\w-]*)", text)) - {"--help",
                                                                             "--help-all"}
        pages = re.findall(r"docs/[\w.-]+\.md", text.rstrip().splitlines()[-1])
        own = "".join(read(pg) for pg in pages if os.path.exists(os.path.join(root, pg)))
        code = "\n".join(re.findall(r"```.*?```", own + all_docs, re.S) + spans(own + all_docs) +
                         re.findall(r"^(?: {4}|\t).*$", own + all_docs, re.M))  # indented code
        for opt in sorted(helps[cmd]):
            if not re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(opt), code):
                fail("mdpore %s: option %s of --help-all is not documented (no `%s` in %s or "
                     "docs/)"
                     % (cmd, opt, opt, ", ".join(pages)))
    sub_helps = {}

    def sub_options(cmd, sub):
        """Options of `mdpore CMD SUB --help-all` (a subcommand with a help of its own), else
        none."""
        if (cmd, sub) not in sub_helps:
            p = subprocess.run([mdpore, *cmd.split(), sub, "--help-all"], capture_output=True,
                               text=True)
            sub_helps[cmd, sub] = set(re.findall(r"(?<![\w-])(--[a-z][\w-]*)", p.stdout + p.stderr)) \
                if p.returncode == 0 else set()
        return sub_helps[cmd, sub]

    for m in re.finditer(r"mdpore ((?:build )?[a-z]+)\b([^`\n]*)", all_docs):
        cmd, rest = m.group(1), m.group(2)
        if cmd not in helps:
            continue
        sub = re.match(r"\s+([a-z][\w-]*)(?=\s|$)", rest)  # a word, not a file name
        known = helps[cmd] | (sub_options(cmd, sub.group(1)) if sub else set())
        for opt in re.findall(r"(?<![\w-])(--[a-z][\w-]*)", rest.split("|")[0]):
            if opt not in known and opt not in ("--help", "--help-all"):
                fail("docs: `mdpore %s ... %s`: %s is not an option of mdpore %s --help-all"
                     % (cmd, opt, opt, cmd))
    print("%d failure(s)" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
