"""The geometry build's memory, checked before it runs, is an upper bound of what it holds.

Usage: check_geometry_build_plan.py MDPORE WORKDIR [FACTOR]

Makes a 40^3 random-sphere image (porosity 0.35) and runs `mdpore run --steps 0` on it at 0.5 rc per
voxel, one rank. The geometry report gives the build's measured peak ("build peak per rank") and
the estimate the run checked against the memory available before the image was read ("build checked
before it ran: at most X MB"). The estimate must not be below the peak (it would let through a build
that does not fit) and at most FACTOR (2.5) above it (it would refuse builds that fit).
"""
import os
import re
import subprocess
import sys

SCENE = """name: build_plan
box: {lo: [0, 0, 0], hi: [20, 20, 20]}
species:
  - {name: liquid}
  - {name: quartz, frozen: true}
pairs:
  default: {A: -40, B: 25, gamma: 4.5, rc: 1.0, rd: 0.75}
effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}}
geometry:
  image: spheres.raw
  flow_axis: x
  rc_per_voxel: 0.5
  species: {fluid: liquid, inorganic: quartz}
initial: {temperature: 1.0}
run: {dt: 0.01, steps: 0}
output:
  progress: false
"""


def main():
    exe, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    factor = float(sys.argv[3]) if len(sys.argv) > 3 else 2.5
    os.makedirs(work, exist_ok=True)
    subprocess.run([exe, "image", "make", "random-spheres", "--size", "40", "--radius", "4",
                    "--porosity", "0.35", "--seed", "3", "-o", "spheres.raw"], cwd=work,
                   check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(work, "build_plan.yaml"), "w") as f:
        f.write(SCENE)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    run = subprocess.run([exe, "run", "--backend", "cpu", "build_plan.yaml"], cwd=work, env=env,
                         capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit("mdpore run exited %d:\n%s%s" % (run.returncode, run.stdout, run.stderr))
    peak = re.search(r"build peak per rank ([0-9.e+-]+)\.\.([0-9.e+-]+) MB", run.stdout)
    plan = re.search(r"build checked before it ran: at most ([0-9.e+-]+) MB", run.stdout)
    if not peak or not plan:
        sys.exit("no build peak or build check line in the report:\n" + run.stdout)
    measured, estimate = float(peak.group(2)), float(plan.group(1))
    ratio = estimate / measured
    print("build peak measured %.4g MB, checked before the build %.4g MB: ratio %.3f (allowed "
          "1..%g)" % (measured, estimate, ratio, factor))
    if not 1.0 <= ratio <= factor:
        sys.exit("FAIL: the build's estimate is off its measured peak")
    print("ok")


if __name__ == "__main__":
    main()
