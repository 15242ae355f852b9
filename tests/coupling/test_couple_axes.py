#!/usr/bin/python3
"""ctest coupling_axes: `mdpore couple` with campaign.axes (a k per block along each axis), scenes
only (launcher: slurm: the campaigns write their scenes, nothing runs; a few seconds).

A 2 x 2 x 1 checkerboard of two slit blocks anisotropic by construction, flow along x: Q, a slit
with walls normal to y (`mdpore image make slit`: open along x and z, closed along y), and P, a
slit with walls normal to z (written here as a raw image: open along x and y). Asserted:
 1. campaign.axes: all gives every block its campaign along x, and a campaign along y to the P
    blocks only (Q's pore space does not span y: impermeable along y, no runs), none along z (one
    block along z: no face between blocks carries flow along z); the job array holds the 20 runs
    along x and the 10 along y, the y runs' scenes drive along y, and the cross campaigns' boundary
    treatment is printed per block and axis;
 2. campaign.axes: flow (the default) writes the runs along x only, the same scenes as a config
    without the key;
 3. a bad campaign.axes is refused naming the file, the key and the words expected.
"""
import json
import os
import shutil
import subprocess
import sys

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "couple_axes_out"))
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


def z_slit(name, nx=12, ny=16, nz=8, wall=2):
    """Walls normal to z (z < wall or z >= nz - wall solid): open along x and y, closed along z."""
    data = bytes(1 if (z < wall or z >= nz - wall) else 0
                 for z in range(nz) for y in range(ny) for x in range(nx))  # x fastest
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)
    write(name + ".hdr", f"dims: {nx} {ny} {nz}\ntype: uint8\nbyte_order: little\naxis_order: xyz\n"
          "header_bytes: 0\nlabels: pore=0;inorganic=1\n")


def config(name, workdir, axes, images="[q.h5, p.raw, p.raw, q.h5]", blocks="[2, 2, 1]"):
    return write(name, f"""block_images: {images}
blocks: {blocks}
axis: x
workdir: {workdir}
launcher: slurm
campaign: {{np: 1, max_steps: 500{axes}}}
""")


def commands(workdir):
    path = os.path.join(workdir, "pass_1", "commands.txt")
    return open(path).read().splitlines() if os.path.exists(path) else []


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    os.environ.setdefault("MDPORE_CACHE_DIR", os.path.join(OUT, "cache"))
    p = mdpore("image", "make", "slit", "--width", "8", "--wall", "4", "--length", "12", "--depth", "8",
               "-o", "q.h5")
    if p.returncode:
        sys.exit("image make failed: " + p.stderr)
    z_slit("p.raw")

    # 1. axes: all
    wd = os.path.join(OUT, "all")
    p = mdpore("couple", config("all.yaml", wd, ", axes: all"))
    cmds = commands(wd)
    along = {a: [c for c in cmds if f"/campaign_{a}/" in c] for a in "yz"}
    x_runs = [c for c in cmds if "/campaign/" in c]
    check(p.returncode == 3, f"axes: all, slurm: exit 3, runs pending (got {p.returncode}: {p.stderr[-300:]})")
    check(len(x_runs) == 20 and len(along["y"]) == 10 and not along["z"],
          f"job array: 20 runs along x, 10 along y, none along z (got {len(x_runs)}, {len(along['y'])}, "
          f"{len(along['z'])})")
    y_blocks = sorted({c.split("/blocks/")[1].split("/")[0] for c in along["y"]})
    check(y_blocks == ["b0_1_0", "b1_0_0"], f"campaigns along y for the P blocks only (got {y_blocks})")
    for b in ("b0_0_0", "b1_1_0"):
        check(not os.path.exists(os.path.join(wd, "blocks", b, "campaign_y")),
              f"no campaign along y for Q block {b} (its pore space does not span y)")
    scene = open(os.path.join(along["y"][0].split("'")[1], "scene.yaml")).read() if along["y"] else ""
    check("flow_axis: y" in scene, "a y run's scene has flow_axis: y")
    check("block (1,0,0) axis y:" in p.stdout and "block (0,1,0) axis y:" in p.stdout,
          "the boundary treatment of the campaigns along y is printed per block")
    res = json.load(open(os.path.join(wd, "couple.json"))) if os.path.exists(os.path.join(wd, "couple.json")) else {}
    check(res.get("pending") is True and res.get("campaign_axes") == "all",
          "couple.json: pending, campaign_axes all")

    # 2. axes: flow (default) = no key (a 2 x 1 x 1 pair of the same blocks: fewer campaigns)
    wd2, wd3 = os.path.join(OUT, "flow"), os.path.join(OUT, "default")
    p2 = mdpore("couple", config("flow.yaml", wd2, ", axes: flow", "[q.h5, p.raw]", "[2, 1, 1]"))
    p3 = mdpore("couple", config("default.yaml", wd3, "", "[q.h5, p.raw]", "[2, 1, 1]"))

    def scenes(wd):
        return sorted(open(os.path.join(c.split("'")[1], "scene.yaml")).read().replace(wd, "W")
                      for c in commands(wd))
    c2 = commands(wd2)
    check(p2.returncode == 3 and len(c2) == 10 and not any("/campaign_" in c for c in c2),
          f"axes: flow: the 10 runs along x only (got {len(c2)})")
    check(scenes(wd2) == scenes(wd3) and len(scenes(wd3)) == 10,
          "axes: flow writes the same scenes as a config without the key")

    # 3. a bad value
    write("bad.yaml", "block_images: [q.h5]\naxis: x\ncampaign: {axes: some}\n")
    p = mdpore("couple", "bad.yaml")
    check(p.returncode == 1 and all(s in p.stderr for s in ("bad.yaml", "'campaign.axes'", "auto")),
          f"bad campaign.axes refused naming the key (got {p.returncode}: {p.stderr.strip()[:200]})")

    if failures:
        print(f"{len(failures)} check(s) failed:\n  " + "\n  ".join(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
