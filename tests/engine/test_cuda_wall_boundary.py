#!/usr/bin/python3
"""ctest cuda_wall_boundary_np2: an image slit
with `wall_boundary` + `bounce_back` on 2 ranks of the CUDA backend (the ranks share the GPUs there
are), checked against the CPU backend's 2-rank run of the same scene. Skipped (exit 77, printing
why) without a GPU, like the other cuda_ tests.

The scene: a slit of 4 rc (8 voxels of 0.5 rc) between walls of 4 voxels along y, box 6 x 8 x 4 rc,
periodic, written here as a raw image + sidecar (docs/images.md); the lower wall organic and the
upper inorganic (two frozen species, both at rest); mDPD liquid A = -40, B = 25, rd = 0.75,
gamma = 4.5, kT = 1, dt = 0.01, the fluid-wall pairs the same; body force 0.1 along x on the liquid;
wall_boundary (its defaults) + bounce_back; the builder's defaults otherwise (patches file in the
work folder, built by the first run, reused by the second).

Checks (each backend, 2 ranks):
  1. trajectories: 5 steps from the same built start, positions and velocities at step 5 per id;
     CPU and CUDA agree within float rounding of the GPU's single-precision pair math (positions
     within 1e-5 rc, velocities within 1e-3; cuda_forces_match_cpu measured 2.5e-7 rc after 5 steps
     with wall_boundary reflections, so a larger gap means a different boundary decision);
  2. 3000 steps under the body force: 0 penetrations in every thermo sample (every 10 steps) and in
     the summary (2 ranks named there); the particle count N the same in every sample (the engine
     also stops on a changed count); thermo T and the mean flow u = p_x / N_liquid averaged over
     steps 500..3000 agree between the backends within 4 combined standard errors (6 block
     averages; the two runs start from the same state and diverge chaotically, so they are
     compared as statistics, not trajectories). Why so long: the slit's mean flow fluctuates by
     sqrt(kT / N_liquid) = 0.04 with a correlation time h^2 n / (pi^2 mu) = 1.9 (190 steps), so
     a few hundred steps hold about one independent sample and their block errors are
     meaningless: four CPU runs of 400 steps with different seeds gave u = 0.131 +- 0.005 and
     0.067 +- 0.010 (6 sigma apart); of 3000 steps, u = 0.100..0.130 and T = 1.003..1.017, every
     pair within 2.4 combined errors (CPU, 2 ranks, 12-18 s a run on a loaded 2-core machine).
Usage: test_cuda_wall_boundary.py MDPORE "MPIEXEC FLAGS" WORKDIR [BACKEND_B]
BACKEND_B (default cuda) is the backend compared with the CPU; `cpu` checks the harness itself on
a machine without a GPU (not a ctest).
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys

mdpore, mpi, work = sys.argv[1:4]
OTHER = sys.argv[4] if len(sys.argv) > 4 else "cuda"
failures = []

NX, NY, NZ, WALL = 12, 16, 8, 4  # voxels: 6 x 8 x 4 rc at 0.5 rc per voxel; pore 8 voxels = 4 rc
STEPS, EVERY, START, G = 3000, 10, 500, 0.1


def check(cond, what, detail=""):
    print(("ok   " if cond else "FAIL ") + what + ("" if cond or not detail else f"\n     {detail}"), flush=True)
    if not cond:
        failures.append(what)


def write_image(path):
    """Organic (2) below, pore, inorganic (1) above, along y; x fastest in the file."""
    data = bytearray()
    for _z in range(NZ):
        for y in range(NY):
            label = 2 if y < WALL else (1 if y >= NY - WALL else 0)
            data += bytes([label]) * NX
    with open(path, "wb") as f:
        f.write(data)
    with open(path + ".hdr", "w") as f:
        f.write(f"dims: {NX} {NY} {NZ}\ntype: uint8\nbyte_order: little\naxis_order: xyz\nheader_bytes: 0\n"
                "labels: pore=0,inorganic=1,organic=2\n")


def scene_text(steps, thermo_every, dump):
    out = f"  dump: {{every: {steps}, file: dump.lammpstrj}}\n" if dump else ""
    return f"""name: cuda_wall_boundary
box: {{lo: [0, 0, 0], hi: [{NX / 2:g}, {NY / 2:g}, {NZ / 2:g}], periodic: [true, true, true]}}
species:
  - {{name: liquid, mass: 1.0}}
  - {{name: bottom, mass: 1.0, frozen: true}}
  - {{name: top, mass: 1.0, frozen: true}}
pairs:
  default: {{A: -40.0, B: 25.0, gamma: 4.5, rc: 1.0, rd: 0.75}}
density_kernel: warren
kT: 1.0
effects:
  mdpd_attraction: {{}}
  mdpd_repulsion: {{}}
  dpd_thermostat: {{}}
  body_force: {{liquid: [{G}, 0.0, 0.0]}}
  wall_boundary: {{}}
  bounce_back: {{}}
geometry:
  image: {os.path.join(work, 'slit.raw')}
  rc_per_voxel: 0.5
  flow_axis: x
  species: {{fluid: liquid, organic: bottom, inorganic: top}}
  patches: {{file: {os.path.join(work, 'patches.h5')}, seed: 1}}
initial: {{temperature: 1.0}}
run: {{dt: 0.01, steps: {steps}, seed: 11}}
output:
  thermo: {{every: {thermo_every}, file: thermo.csv}}
  summary: summary.json
  progress: false
{out}"""


def run(backend, tag, steps, thermo_every, dump):
    out = os.path.join(work, f"{tag}_{backend}")
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, "scene.yaml")
    with open(path, "w") as f:
        f.write(scene_text(steps, thermo_every, dump))
    cmd = mpi.split() + ["-n", "2", mdpore, "run", "--backend", backend, "--output-dir", out, path]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    check(p.returncode == 0, f"{backend} {tag}: the 2-rank run ends with exit 0",
          (p.stdout[-800:] + p.stderr[-1500:]))
    return out, p


def thermo(out):
    head, rows = None, []
    for line in open(os.path.join(out, "thermo.csv")):
        if line.startswith("#"):
            continue
        cells = line.strip().split(",")
        if head is None:
            head = cells
            continue
        rows.append(dict(zip(head, (float(c) for c in cells))))
    return rows


def dump_state(out):
    """{id: (x, y, z, vx, vy, vz)} of the last frame of the LAMMPS text dump."""
    frames, cur, cols = [], None, None
    for line in open(os.path.join(out, "dump.lammpstrj")):
        if line.startswith("ITEM: ATOMS"):
            cols = line.split()[2:]
            cur = {}
            frames.append(cur)
        elif line.startswith("ITEM:"):
            cols = None
        elif cols:
            v = line.split()
            d = dict(zip(cols, v))
            cur[int(d["id"])] = tuple(float(d[k]) for k in ("x", "y", "z", "vx", "vy", "vz"))
    return frames[-1] if frames else {}


def mean_err(values, blocks=6):
    n = len(values) // blocks
    means = [sum(values[b * n:(b + 1) * n]) / n for b in range(blocks)]
    m = sum(means) / blocks
    return m, math.sqrt(sum((x - m) ** 2 for x in means) / (blocks * (blocks - 1)))


def main():
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    if OTHER == "cuda":
        probe = subprocess.run([mdpore, "run", "--backend", "cuda", "--explain",
                                os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes", "restart_small.yaml")],
                               capture_output=True, text=True)
        if probe.returncode:
            print("skipped: no GPU (" + probe.stderr.strip().split("available: ")[-1] + ")")
            sys.exit(77)
    write_image(os.path.join(work, "slit.raw"))
    box = [NX / 2, NY / 2, NZ / 2]

    # 1. five steps: trajectories within float rounding
    short = {b: dump_state(run(b, "short", 5, 5, True)[0]) for b in ("cpu", OTHER)}
    a, b = short["cpu"], short[OTHER]
    check(a and set(a) == set(b), f"short: both dumps hold the same {len(a)} ids at step 5")
    dx = dv = 0.0
    for i in set(a) & set(b):
        for d in range(3):
            e = abs(a[i][d] - b[i][d])
            dx = max(dx, min(e, box[d] - e))  # nearest image (a wrap near a face)
            dv = max(dv, abs(a[i][3 + d] - b[i][3 + d]))
    check(dx < 1e-5 and dv < 1e-3, f"short: cpu and {OTHER} agree at step 5 (max |dx| {dx:.2e} rc, max |dv| {dv:.2e})")

    # 2. 400 steps under the body force: penetrations, count, T and the mean flow as statistics
    stats = []
    for backend in ("cpu", OTHER):
        out, p = run(backend, "long", STEPS, EVERY, False)
        rows = thermo(out)
        m = re.search(r"fluid: liquid (\d+) particles", p.stdout)
        n_liq = int(m.group(1)) if m else 0
        check(rows and int(rows[-1]["step"]) == STEPS and n_liq > 0,
              f"{backend}: thermo reaches step {STEPS}; {n_liq} liquid particles built")
        if not rows or not n_liq:
            continue
        pen = [int(r["penetrations"]) for r in rows]
        check(max(pen) == 0, f"{backend}: 0 penetrations in all {len(pen)} thermo samples (max {max(pen)})")
        summary = json.load(open(os.path.join(out, "summary.json")))
        check(summary["ranks"] == 2 and summary["penetrations"]["samples_with_penetration"] == 0,
              f"{backend}: summary: 2 ranks, no sample with a penetration")
        counts = {int(r["N"]) for r in rows}
        check(len(counts) == 1, f"{backend}: particle count kept ({sorted(counts)})")
        late = [r for r in rows if r["step"] > START]
        stats.append((mean_err([r["T"] for r in late]), mean_err([r["px"] / n_liq for r in late]), counts))
    if len(stats) == 2:
        (tc, ec), (uc, euc), nc = stats[0]
        (tg, eg), (ug, eug), ng = stats[1]
        check(nc == ng, f"the same particle count on both backends ({sorted(nc)}, {sorted(ng)})")
        check(abs(tc - tg) < 4 * math.hypot(ec, eg),
              f"T: cpu {tc:.4f} +- {ec:.4f}, {OTHER} {tg:.4f} +- {eg:.4f} (within 4 combined errors)")
        check(abs(uc - ug) < 4 * math.hypot(euc, eug) and uc > 0,
              f"mean flow u_x: cpu {uc:.4f} +- {euc:.4f}, {OTHER} {ug:.4f} +- {eug:.4f} (within 4 combined errors)")


if __name__ == "__main__":
    main()
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")
