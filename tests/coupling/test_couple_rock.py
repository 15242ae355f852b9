#!/usr/bin/python3
"""ctest coupling_rock: `mdpore couple` on a crop of a real rock, whose blocks are not periodic.

cases/rock/berea16.raw (16^3 voxels of Berea sandstone) cut into 2 x 1 x 1 blocks of 8 x 16 x 16
voxels along x. A block's end slices do not continue each other (seam continuity ~0.5, periodic at
>= 0.8): in a periodic box the seam would close or invent flow paths. The block campaigns resolve
their boundary treatment the way a single-image campaign does (`--boundary auto`, per block and
axis), so each block runs mirrored along x.

Asserted:
 1. config errors: a bad campaign.boundary / campaign.sides word, and boundary mirror with
    drive: pressure, exit 1 naming the key;
 2. the loop (auto gradient, 5 gradients per block, <= 1500 steps on 2 ranks) converges; every
    block's campaign.txt has a `boundary:` line with mirror along x; couple.json's
    block_boundaries and blocks_final, the pass table and stdout say mirror with the block's seam
    continuity (< 0.8); k_eff is finite and positive with an error bar;
 3. campaign.boundary: periodic forced (slurm launcher: scenes only, nothing runs): the campaigns,
    couple.json and stdout say periodic, chosen by campaign.boundary, and the loop warns that the
    block's faces do not continue each other;
 4. campaign.sides: mirror reaches the block campaigns (campaign.txt `sides: mirror`).
The re-run of a block driven outside its calibrated range is test_couple.py's (ctest coupling_loop).
"""
import json
import os
import shutil
import subprocess
import sys
import time

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "couple_rock_out"))
ROCK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "cases", "rock", "berea16.raw")
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def mdpore(*args):
    return subprocess.run([MDPORE, *args], capture_output=True, text=True, cwd=OUT)


def write(name, text):
    with open(os.path.join(OUT, name), "w") as f:
        f.write(text)
    return name


def config(name, workdir, campaign_extra="", extra=""):
    return write(name, f"""image: {os.path.abspath(ROCK)}
blocks: [2, 1, 1]
axis: x
workdir: {workdir}
campaign: {{np: 2, max_steps: 1500, target_error: 0.05, mpiexec: "mpiexec --oversubscribe"{campaign_extra}}}
loop: {{max_passes: 3}}
{extra}""")


def manifest_boundary(workdir, block):
    """The `boundary:` and `sides:` lines of a block campaign's manifest (campaign.txt)."""
    path = os.path.join(workdir, "blocks", block, "campaign", "campaign.txt")
    out = {}
    if os.path.exists(path):
        for line in open(path):
            key, _, value = line.partition(":")
            if key in ("boundary", "sides", "seam_continuity"):
                out[key] = value.split()
    return out


def load(path):
    return json.load(open(path)) if os.path.exists(path) else {}


BLOCKS = ("b0_0_0", "b1_0_0")


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    os.environ.setdefault("MDPORE_CACHE_DIR", os.path.join(OUT, "cache"))

    # 1. config errors
    for text, needles, what in (
            ("campaign: {boundary: open}\n", ["'campaign.boundary'", "mirror"], "bad campaign.boundary"),
            ("campaign: {sides: open}\n", ["'campaign.sides'", "periodic"], "bad campaign.sides"),
            ("campaign: {drive: pressure, boundary: mirror}\n", ["'campaign.boundary'", "reservoir"],
             "boundary mirror with drive: pressure")):
        path = write("bad.yaml", f"image: {os.path.abspath(ROCK)}\naxis: x\n" + text)
        p = mdpore("couple", path)
        ok = p.returncode == 1 and all(n in p.stderr for n in needles)
        check(ok, f"{what}: exit {p.returncode}, stderr names {needles}" + ("" if ok else f" (got: {p.stderr.strip()[:300]})"))

    # 2. the loop on the rock's blocks: auto resolves mirror per block
    wd = os.path.join(OUT, "auto")
    t0 = time.time()
    p = mdpore("couple", config("auto.yaml", wd))
    t_loop = time.time() - t0
    print(p.stdout)
    print(p.stderr[-3000:])
    print(f"loop: {t_loop:.1f} s")
    check(p.returncode == 0, f"loop on the rock's blocks converged: exit 0 (got {p.returncode})")
    for i, b in enumerate(BLOCKS):
        m = manifest_boundary(wd, b)
        seam = float(m["seam_continuity"][0]) if "seam_continuity" in m else float("nan")
        check(m.get("boundary", [""])[0] == "mirror" and seam < 0.8,
              f"{b}: campaign.txt boundary along x mirror (seam continuity {seam:.3g} < 0.8; got {m.get('boundary')})")
        check(f"block ({i},0,0) axis x: mirror (seam continuity" in p.stdout, f"{b}: stdout names its treatment")
    res = load(os.path.join(wd, "couple.json"))
    bb = res.get("block_boundaries", [])
    check(len(bb) == 2 and all(x["faces"] == "mirror" and x["chosen_by"] == "auto" and x["seam_continuity"] < 0.8
                               for x in bb), f"couple.json block_boundaries: mirror by auto ({bb})")
    bf = res.get("blocks_final", [])
    check(len(bf) == 2 and all(x.get("boundary") == "mirror" for x in bf), "couple.json blocks_final: boundary mirror")
    csv = open(os.path.join(wd, "pass_1", "blocks.csv")).read().splitlines() \
        if os.path.exists(os.path.join(wd, "pass_1", "blocks.csv")) else []
    check(len(csv) == 4 and ",boundary,seam_continuity," in csv[1] and all(",mirror," in r for r in csv[2:]),
          "pass_1/blocks.csv: boundary column mirror for both blocks")
    k = res.get("effective_permeability", {})
    kb = []
    for b in BLOCKS:
        pj = load(os.path.join(wd, "blocks", b, "campaign", "permeability.json"))
        kb.append(pj.get("axes", {}).get("x", {}).get("k_rc2", float("nan")))
    print(f"blocks k (mirror) = {kb} rc^2; loop k_eff = {k.get('k_rc2')} +- {k.get('k_rc2_err')} rc^2 "
          f"= {k.get('k_m2')} m^2, {res.get('passes')} passes")
    kk = k.get("k_rc2") or float("nan")
    check(kk == kk and 0 < kk < float("inf") and (k.get("k_rc2_err") or 0) > 0 and (k.get("k_m2") or 0) > 0,
          f"k_eff finite and positive with an error bar ({k.get('k_rc2')} +- {k.get('k_rc2_err')})")

    # 3. periodic forced: scenes only (slurm launcher), the reports say periodic and warn
    wd2 = os.path.join(OUT, "periodic")
    p = mdpore("couple", config("periodic.yaml", wd2, ", boundary: periodic", "launcher: slurm\n"))
    print(p.stdout)
    print(p.stderr[-2000:])
    check(p.returncode == 3, f"periodic forced, slurm launcher: exit 3 (runs pending; got {p.returncode})")
    for i, b in enumerate(BLOCKS):
        m = manifest_boundary(wd2, b)
        check(m.get("boundary", [""])[0] == "periodic", f"{b}: campaign.txt boundary along x periodic ({m.get('boundary')})")
        check(f"block ({i},0,0) axis x: periodic (seam continuity" in p.stdout and "campaign.boundary" in p.stdout,
              f"{b}: stdout says periodic, chosen by campaign.boundary")
    check("warning: block (0,0,0) runs periodic along x" in p.stderr, "the loop warns of the periodic seam")
    res2 = load(os.path.join(wd2, "couple.json"))
    bb2 = res2.get("block_boundaries", [])
    check(res2.get("pending") is True and len(bb2) == 2 and
          all(x["faces"] == "periodic" and x["chosen_by"] == "campaign.boundary" for x in bb2),
          f"couple.json (pending) block_boundaries: periodic by campaign.boundary ({bb2})")

    # 4. campaign.sides reaches the block campaigns
    wd3 = os.path.join(OUT, "sides")
    p = mdpore("couple", config("sides.yaml", wd3, ", sides: mirror", "launcher: slurm\n"))
    m = manifest_boundary(wd3, BLOCKS[0])
    check(p.returncode == 3 and m.get("sides") == ["mirror"] and m.get("boundary", [""])[0] == "mirror",
          f"campaign.sides mirror: campaign.txt sides mirror ({m})")

    if failures:
        print(f"{len(failures)} check(s) failed:\n  " + "\n  ".join(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
