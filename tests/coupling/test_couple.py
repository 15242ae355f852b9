#!/usr/bin/python3
"""ctest coupling_loop: a CI-sized `mdpore couple` loop (CPU, 2 x 1 x 1 blocks, a few minutes).

Two slit blocks in series along x (`mdpore image make slit`, 12 x 16 x 8 voxels at 0.5 rc): block A
a pore of h = 4 rc, block B of h = 2 rc. Each block gets a permeability campaign (5 gradients for
mean pore velocities 0.02-0.12, <= 2000 steps, 2 ranks); the sample is driven at G = 1.65
kT/rc^4, which puts block B's gradient in series (G k_eff / k_B ~ 2.9) above the range its
campaign was calibrated on (top ~2), so pass 1 adds a run at that gradient to B, pass 2 refits and
solves again. Why not the default velocity range: its top already heats B's liquid by 3% (G =
3.4), and the runs above it were heated beyond the 5% the campaign accepts (+6.6% at G = 3.9):
left out of the fit, so B's range could never cover its gradient (the loop then warns that B's
law is extrapolated there).

Asserted:
 1. bad configs exit 1 naming the file, the key and what was expected; no CONFIG exits 2;
 2. a loop killed (SIGTERM) after its first finished run leaves no run process behind;
 3. the loop rerun in the same folder resumes (the finished run is reused, not rewritten), adds at
    least one run where the continuum gradient left a block's calibrated range, converges (exit 0,
    couple.json converged), and its k_eff equals the harmonic mean of the two blocks' own campaign
    permeabilities (series, equal lengths: exact for the two-point scheme) with an error bar > 0;
    every block carries the same flux (series); per-pass tables, HDF5 field and XDMF written;
 4. a rerun is instant (every run and fit cached: no run summary rewritten);
 5. the slurm launcher on the finished folder has nothing pending (exit 0); on a fresh folder it
    writes the job array of the 10 unfinished runs and exits 3.
"""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "couple_test_out"))
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def mdpore(*args, **kw):
    return subprocess.run([MDPORE, *args], capture_output=True, text=True, cwd=OUT, **kw)


def write(name, text):
    with open(os.path.join(OUT, name), "w") as f:
        f.write(text)
    return name


CAMPAIGN = '{np: 2, max_steps: 2000, target_error: 0.05, velocity_range: [0.02, 0.12], mpiexec: "mpiexec --oversubscribe"}'


def config(name, workdir, extra=""):
    return write(name, f"""block_images: [a.h5, b.h5]
blocks: [2, 1, 1]
axis: x
gradient: 1.65
workdir: {workdir}
campaign: {CAMPAIGN}
loop: {{max_passes: 4}}
{extra}""")


def expect_error(text, needles, what):
    path = write("bad.yaml", text)
    p = mdpore("couple", path)
    ok = p.returncode == 1 and all(n in p.stderr for n in needles)
    check(ok, f"{what}: exit {p.returncode}, stderr names {needles}" + ("" if ok else f" (got: {p.stderr.strip()[:300]})"))


def summaries(workdir):
    out = {}
    for root, _, files in os.walk(workdir):
        if "summary.json" in files:
            st = os.stat(os.path.join(root, "summary.json"))
            out[root] = (st.st_ino, st.st_mtime_ns)
    return out


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    os.environ.setdefault("MDPORE_CACHE_DIR", os.path.join(OUT, "cache"))
    for name, width, wall in (("a.h5", 8, 4), ("b.h5", 4, 6), ("c.h5", 4, 8)):
        p = mdpore("image", "make", "slit", "--width", str(width), "--wall", str(wall), "--length", "12",
                   "--depth", "8", "-o", name)
        if p.returncode:
            sys.exit("image make failed: " + p.stderr)

    # block images of the same voxels at 0.82 nm and 20 nm are different boxes
    for name, size in (("d.h5", "0.82nm"), ("e.h5", "20nm")):
        p = mdpore("image", "make", "slit", "--width", "4", "--wall", "6", "--length", "12", "--depth", "8",
                   "--voxel-size", size, "-o", name)
        if p.returncode:
            sys.exit("image make failed: " + p.stderr)

    # 1. bad configs
    p = mdpore("couple")
    check(p.returncode == 2 and "usage" in p.stderr, "no CONFIG: usage, exit 2")
    expect_error("image: missing.h5\naxis: x\n", ["bad.yaml", "'image'", "missing.h5"], "missing image")
    expect_error("image: a.h5\nblock_images: [a.h5, b.h5]\nblocks: [2,1,1]\naxis: x\n",
                 ["bad.yaml", "exactly one of 'image'"], "image and block_images")
    expect_error("block_images: [a.h5]\nblocks: [2,1,1]\naxis: x\n", ["'block_images'", "expected 2 images"],
                 "wrong number of block images")
    expect_error("block_images: [a.h5, c.h5]\nblocks: [2,1,1]\naxis: x\n",
                 ["'block_images[1]'", "12 x 16 x 8"], "block images of different sizes")
    expect_error("block_images: [d.h5, e.h5]\nblocks: [2,1,1]\naxis: x\n",
                 ["bad.yaml", "'block_images[1]'", "voxel size", "8.2e-10 m", "2e-08 m", "image_voxel_size"],
                 "block images of different voxel sizes")
    expect_error("image: a.h5\nblocks: [5,1,1]\naxis: x\n", ["'blocks'", "divide"], "blocks not dividing the image")
    expect_error("image: a.h5\naxis: w\n", ["'axis'", "x"], "bad axis")
    expect_error("image: a.h5\naxis: x\ngradient: 3 furlongs\n", ["'gradient'", "Pa/m"], "gradient with a bad unit")
    expect_error("image: a.h5\naxis: x\nlop: {max_passes: 2}\n", ["'lop'"], "unknown key")
    expect_error("image: a.h5\naxis: x\nloop: {max_passes: 1}\n", ["'loop.max_passes'", "2 to 16"], "max_passes < 2")
    expect_error("image: a.h5\naxis: x\ncampaign: {np: 0}\n", ["'campaign.np'"], "np 0")

    # 2. a loop killed after its first finished run
    wd = os.path.join(OUT, "loop")
    cfg = config("loop.yaml", wd)
    proc = subprocess.Popen([MDPORE, "couple", cfg], cwd=OUT, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, start_new_session=True)
    deadline, killed, first = time.time() + 300, False, {}
    while time.time() < deadline and proc.poll() is None:
        first = summaries(wd)
        if first:
            proc.send_signal(signal.SIGTERM)
            killed = True
            break
        time.sleep(0.2)
    proc.communicate(timeout=120)
    check(killed and proc.returncode != 0, f"loop killed after its first finished run (exit {proc.returncode})")
    time.sleep(0.5)
    left = subprocess.run(["pgrep", "-f", os.path.join(wd, "blocks")], capture_output=True, text=True).stdout.strip()
    check(left == "", "no run process left behind by the killed loop")

    # 3. resumed to the end
    t0 = time.time()
    p = mdpore("couple", cfg)
    t_loop = time.time() - t0
    print(p.stdout)
    print(p.stderr[-3000:])
    print(f"loop: {t_loop:.1f} s")
    check(p.returncode == 0, f"loop converged: exit 0 (got {p.returncode})")
    after = summaries(wd)
    check(all(after.get(d) == s for d, s in first.items()) and first,
          f"the {len(first)} run(s) finished before the kill were reused, not rewritten")
    res = json.load(open(os.path.join(wd, "couple.json"))) if os.path.exists(os.path.join(wd, "couple.json")) else {}
    check(res.get("converged") is True and res.get("passes", 0) >= 2, f"couple.json: converged after {res.get('passes')} passes")
    hist = res.get("history", [])
    check(bool(hist) and hist[0]["new_runs"] >= 1, "pass 1 fed back at least one run (a block above its calibrated range)")
    blocks = res.get("blocks_final", [])
    check(len(blocks) == 2 and blocks[1]["G_seen"] > 0 and blocks[1]["calibrated_G"][1] >= blocks[1]["G_seen"] / 1.05,
          "block B's final calibrated range covers the gradient it sees")
    kb = []
    for b in ("b0_0_0", "b1_0_0"):
        pj = os.path.join(wd, "blocks", b, "campaign", "permeability.json")
        kb.append(json.load(open(pj))["axes"]["x"]["k_rc2"] if os.path.exists(pj) else float("nan"))
    k = res.get("effective_permeability", {})
    harmonic = 2.0 / (1.0 / kb[0] + 1.0 / kb[1])
    print(f"blocks k = {kb}; harmonic mean {harmonic:.6g}; loop k_eff = {k.get('k_rc2')} +- {k.get('k_rc2_err')}")
    check(k.get("k_rc2") and abs(k["k_rc2"] / harmonic - 1) < 1e-6,
          f"series: k_eff = harmonic mean of the blocks' campaign k ({k.get('k_rc2')} vs {harmonic:.6g})")
    check((k.get("k_rc2_err") or 0) > 0 and k.get("k_nD", 0) > 0 and k.get("k_m2", 0) > 0,
          "k_eff has an error bar and is given in m^2 and nD")
    check(len(blocks) == 2 and abs(blocks[0]["q_continuum"] / blocks[1]["q_continuum"] - 1) < 1e-8,
          "series: both blocks carry the same flux")
    passes = res.get("passes", 0)
    for n in range(1, passes + 1):
        d = os.path.join(wd, f"pass_{n}")
        csv = open(os.path.join(d, "blocks.csv")).read().splitlines() if os.path.exists(os.path.join(d, "blocks.csv")) else []
        check(len(csv) == 4 and csv[1].startswith("i,j,k,porosity,law_used"), f"pass {n}: blocks.csv with 2 blocks")
        xmf = open(os.path.join(d, "field.xmf")).read() if os.path.exists(os.path.join(d, "field.xmf")) else ""
        check(os.path.exists(os.path.join(d, "field.h5")) and "field.h5:/pressure" in xmf, f"pass {n}: field.h5 + field.xmf")
    try:
        import h5py
        with h5py.File(os.path.join(wd, f"pass_{passes}", "field.h5"), "r") as f:
            pr = f["pressure"][...]
            check(pr.shape == (1, 1, 2) and pr[0, 0, 0] > pr[0, 0, 1] and f["pressure"].attrs["unit"] in (b"kT/rc^3", "kT/rc^3"),
                  "field.h5: pressure (nz, ny, nx), falling along x, with a unit")
    except ImportError:
        print("skip h5py checks: no h5py")

    # 4. a rerun is instant
    before = summaries(wd)
    t0 = time.time()
    p = mdpore("couple", cfg)
    t_rerun = time.time() - t0
    print(f"rerun: {t_rerun:.1f} s (loop {t_loop:.1f} s)")
    check(p.returncode == 0 and summaries(wd) == before, "rerun: exit 0, no run rewritten")
    check(t_rerun < max(30.0, 0.25 * t_loop), f"rerun took {t_rerun:.1f} s (< max(30 s, loop/4))")
    res2 = json.load(open(os.path.join(wd, "couple.json")))
    check(res2["effective_permeability"]["k_rc2"] == k.get("k_rc2"), "rerun: the same k_eff")

    # 5. slurm launcher
    p = mdpore("couple", config("slurm_done.yaml", wd, "launcher: slurm\n"))
    check(p.returncode == 0, f"slurm launcher on the finished folder: nothing pending, exit 0 (got {p.returncode})")
    wd2 = os.path.join(OUT, "slurm")
    p = mdpore("couple", config("slurm.yaml", wd2, "launcher: slurm\n"))
    script = os.path.join(wd2, "pass_1", "slurm.sh")
    cmds = open(os.path.join(wd2, "pass_1", "commands.txt")).read().splitlines() \
        if os.path.exists(os.path.join(wd2, "pass_1", "commands.txt")) else []
    check(p.returncode == 3 and "sbatch" in p.stdout, f"slurm launcher, fresh folder: exit 3, says sbatch (got {p.returncode})")
    check(os.path.exists(script) and "--array=1-10" in open(script).read() and len(cmds) == 10 and
          all(c.startswith("cd ") and " run scene.yaml" in c for c in cmds),
          f"slurm.sh with --array=1-10 and 10 run commands ({len(cmds)})")
    res3 = json.load(open(os.path.join(wd2, "couple.json"))) if os.path.exists(os.path.join(wd2, "couple.json")) else {}
    check(res3.get("pending") is True, "couple.json says runs are pending")

    # campaign.accuracy: the preset's dt, target error and budget reach the block scenes; a given
    # target_error wins (docs/accuracy.md); a bad preset is refused
    wd3 = os.path.join(OUT, "accuracy")
    cfg3 = write("accuracy.yaml", f"""block_images: [a.h5, b.h5]
blocks: [2, 1, 1]
axis: x
workdir: {wd3}
launcher: slurm
campaign: {{np: 2, accuracy: precise, target_error: 0.02}}
""")
    p = mdpore("couple", cfg3)
    cmds3 = open(os.path.join(wd3, "pass_1", "commands.txt")).read().splitlines() \
        if os.path.exists(os.path.join(wd3, "pass_1", "commands.txt")) else []
    scene3 = open(os.path.join(cmds3[0].split("'")[1], "scene.yaml")).read() if cmds3 else ""
    check(p.returncode == 3 and "dt: 0.005" in scene3 and "steps: 400000" in scene3 and "target_error: 0.02" in scene3,
          "campaign.accuracy precise: dt 0.005 and 400000 steps in the block scenes, the given target_error 0.02 wins")
    expect_error("image: a.h5\naxis: x\ncampaign: {accuracy: medium}\n", ["'campaign.accuracy'", "precise"],
                 "bad accuracy preset")

    if failures:
        print(f"{len(failures)} check(s) failed:\n  " + "\n  ".join(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
