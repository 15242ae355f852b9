"""`mdpore relperm --emit-scenes` on a two-size pore (ctest relperm_emit; runs nothing).

The image: a channel along x, 12 voxels wide for x < 10 and 6 wide after (walls normal to y and z),
so the morphological drainage from the inlet face fills the wide part first. Checks: the command
exits 0; the phase images' non-wetting saturations lie in (0, 1) and fall as the target Sw rises;
targets that land on the same morphological step share one run; every scene names its images
relative to its folder (no path of this machine: neither the work folder nor the input), each such
image exists there; commands.txt has one relative line per run; --collect on the folder without
results fails (non-zero) naming the missing references.
"""
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "engine"))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "walls"))
import mdval  # noqa: E402
from common import write_raw_image  # noqa: E402


def main():
    out = mdval.out_dir("relperm_emit")
    lab = np.ones((20, 16, 16), dtype=np.uint8)
    lab[:10, 2:14, 2:14] = 0
    lab[10:, 5:11, 5:11] = 0
    img = write_raw_image(os.path.join(out, "two_size.raw"), lab)
    emit = os.path.join(out, "emit")
    cmd = [mdval.mdpore_binary(), "relperm", img, "--axis", "x", "--rc-per-voxel", "1", "--boundary", "mirror",
           "--saturations", "0.3,0.31,0.6,0.9", "--emit-scenes", emit]
    p = subprocess.run(cmd, env=mdval.mpi_env(), capture_output=True, text=True)
    print(p.stdout + p.stderr)
    fails = []
    if p.returncode != 0:
        print(f"emit_check: FAIL: exit {p.returncode}")
        return 1
    snw = [float(m) for m in re.findall(r"non-wetting saturation ([0-9.]+) by voxels", p.stderr)]
    if not snw or not all(0 < s < 1 for s in snw) or any(b >= a for a, b in zip(snw, snw[1:])):
        fails.append(f"phase images' Snw {snw}: expected in (0, 1), falling as Sw rises")
    shared = len(re.findall(r"one run for both", p.stderr))
    lines = open(os.path.join(emit, "commands.txt")).read().splitlines()
    if len(lines) != len(snw) + 2:
        fails.append(f"{len(lines)} commands for {len(snw)} distributions + 2 references")
    if len(snw) + shared != 4:
        fails.append(f"{len(snw)} distributions and {shared} shared of 4 targets")
    for line in lines:
        m = re.match(r'cd runs/([^ /]+) && "\$\{MDPORE:-mdpore\}" run scene\.yaml > run\.log 2>&1$', line)
        if not m:
            fails.append(f"command not relative: {line}")
            continue
        run = os.path.join(emit, "runs", m.group(1))
        text = open(os.path.join(run, "scene.yaml")).read()
        for bad in (emit, out, img):
            if bad in text:
                fails.append(f"{run}/scene.yaml names {bad}")
        for path in re.findall(r"image: \"?([^\"\n]+)", text):
            if path.startswith("/") or not os.path.exists(os.path.join(run, path)):
                fails.append(f"{run}/scene.yaml: image {path} not relative or missing")
    c = subprocess.run([mdval.mdpore_binary(), "relperm", "--collect", emit], env=mdval.mpi_env(),
                       capture_output=True, text=True)
    if c.returncode == 0 or "single-phase reference runs" not in c.stderr:
        fails.append(f"--collect without results: exit {c.returncode}, {c.stderr[-300:]}")
    if fails:
        print("emit_check: FAIL: " + "; ".join(fails))
        return 1
    print(f"emit_check: pass ({len(snw)} distributions, Snw {snw}, {shared} shared)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
