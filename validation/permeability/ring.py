#!/usr/bin/env python3
"""The paper's ring medium (physics.md section 7; usermeso25 section 5.1) as an
image, its mDPD permeability (`mdpore permeability`, body force along z as the paper drives it)
against `mdpore foam` (OpenFOAM, Stokes flow) on the SAME voxels.

The medium: cells of Lx = Lz = 16 rc, each with a ring of frozen wall of outer radius 7 rc (no fluid
inside it), cells repeated in x and z with every second row shifted by Lx / 2; porosity ~0.4, the
narrowest gap 2 rc between neighbouring rings of a row. As an image (0.5 rc per voxel) the periodic
unit is one cell in x and two rows in z: 32 x Ny x 64 voxels, solid where the distance to a ring
centre in the x-z plane is below 7 rc (the builder keeps wall particles only within rc + rd of the
pore, a ring 5.25-7 rc, the paper's ring is 6-7 rc: no fluid reaches its inside either way). The paper's
Ly is 2 rc; the flow is two-dimensional, so k does not depend on Ly, and the image takes --ly
(default 4 rc, so that a 2-rank decomposition never cuts a slab thinner than rc).

  ring.py run WORK [--np N] [--max-steps N] [--target-error E] [--gradients LIST]
      the image, foam (periodic drive), the campaign (here, on the CPU: ~8k particles), the report;
  ring.py report WORK      the table again from WORK.
Writes validation/permeability/results/ring.{md,csv,png}; exit 1 when k_mDPD / k_foam is off 1 by
more than 5% + 2 sigma (the sphere arrays' continuum-limit band), which a 2 rc gap need not
meet: the table says so either way. Run with /usr/bin/python3 (numpy, matplotlib).
"""
import argparse
import csv
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "walls"))
import sphere_array as sa  # noqa: E402  (sh, MDPORE, ROOT)
from common import write_raw_image  # noqa: E402  (validation/walls/common.py)

RC_PER_VOXEL = 0.5
CELL, R_OUT = 16.0, 7.0  # rc: cell edge, ring outer radius (physics.md section 7)


def ring_labels(ly):
    """labels[ix, iy, iz]: 1 (solid) inside a ring's outer radius, 0 pore. Two rows along z, the
    second shifted by CELL / 2 along x; distances periodic in x and z."""
    nx, nz, ny = int(CELL / RC_PER_VOXEL), int(2 * CELL / RC_PER_VOXEL), int(round(ly / RC_PER_VOXEL))
    x = (np.arange(nx) + 0.5) * RC_PER_VOXEL
    z = (np.arange(nz) + 0.5) * RC_PER_VOXEL
    X, Z = np.meshgrid(x, z, indexing="ij")
    solid = np.zeros((nx, nz), dtype=bool)
    for cx, cz in ((CELL / 2, CELL / 2), (0.0, 1.5 * CELL)):
        dx = np.abs(X - cx)
        dx = np.minimum(dx, CELL - dx)
        dz = np.abs(Z - cz)
        dz = np.minimum(dz, 2 * CELL - dz)
        solid |= dx * dx + dz * dz < R_OUT * R_OUT
    return np.repeat(solid[:, None, :], ny, axis=1).astype(np.uint8)


def run(a):
    os.makedirs(a.work, exist_ok=True)
    img = os.path.join(a.work, "ring.raw")
    lab = ring_labels(a.ly)
    if not os.path.exists(img):
        write_raw_image(img, lab)
    for refine in (1, 2):
        fj = os.path.join(a.work, f"foam_r{refine}.json")
        if not os.path.exists(fj):
            open(fj, "w").write(sa.sh("foam", img, "--axis", "z", "--drive", "periodic", "--refine", str(refine)))
    cmd = ["permeability", img, "--axis", "z", "--workdir", os.path.join(a.work, "campaign"), *a.extra,
           "--rc-per-voxel", str(RC_PER_VOXEL), "--max-steps", str(a.max_steps),
           "--target-error", str(a.target_error), "--np", str(a.np)]
    if a.gradients:
        cmd += ["--gradients", a.gradients]
    p = subprocess.run([sa.MDPORE, *cmd], text=True)
    if p.returncode:
        sys.exit(f"mdpore {' '.join(cmd)}: exit {p.returncode}")
    return report(a)


def report(a):
    # foam on the voxels' own mesh (refine 1) and each voxel cut in 2^3 (refine 2): the 2 rc gaps are 4
    # cells wide, where the two-point scheme is 1 + 2 / N^2 high (physics.md section 4): the continuum
    # k of these voxels is sa.foam_continuum's extrapolation.
    k_r = [json.load(open(os.path.join(a.work, f"foam_r{r}.json")))["permeability_voxel2"] * RC_PER_VOXEL ** 2
           for r in (1, 2)]
    k_foam = sa.foam_continuum(k_r[0], k_r[1])
    pj = json.load(open(os.path.join(a.work, "campaign", "permeability.json")))
    ax = pj["axes"]["z"]
    k, err = ax["k_rc2"], ax["k_rc2_err"]
    lab = ring_labels(a.ly)
    porosity = 1.0 - lab.mean()
    ratio, ratio_err = k / k_foam, err / k_foam
    ok = abs(ratio - 1) <= 0.05 + 2 * ratio_err
    row = dict(case="ring", cell_rc=CELL, ring_radius_rc=R_OUT, narrowest_gap_rc=CELL - 2 * R_OUT,
               ly_rc=a.ly, porosity=porosity, k_mdpd=k, k_mdpd_err=err, k_foam_refine1=k_r[0],
               k_foam_refine2=k_r[1], k_foam=k_foam,
               mdpd_over_foam=ratio, mdpd_over_foam_err=ratio_err, law=ax.get("chosen"),
               viscosity=pj.get("viscosity"), wall_density=pj.get("wall_density"))
    os.makedirs(a.outdir, exist_ok=True)
    with open(os.path.join(a.outdir, f"ring{a.tag}.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(row))
        w.writeheader()
        w.writerow(row)
    lines = ["# The paper's ring medium: mDPD against OpenFOAM on the same voxels", "",
             f"Command: `/usr/bin/python3 validation/permeability/ring.py run WORK --np {a.np} --max-steps "
             f"{a.max_steps} --target-error {a.target_error}"
             + (f" --gradients {a.gradients}" if a.gradients else "") + "".join(f" --extra={x}" for x in a.extra)
             + f"` (the campaign's defaults otherwise: wall density {pj.get('wall_density', 8):g}, mu "
             f"{pj.get('viscosity'):g} = {pj.get('viscosity_source', 'mu')}). Image {lab.shape[0]} x {lab.shape[1]} x {lab.shape[2]} voxels "
             f"of {RC_PER_VOXEL} rc (one cell of {CELL:g} rc in x, two shifted rows in z, Ly = {a.ly:g} rc), "
             f"porosity {porosity:.3f}, flow along z. k in rc^2 with the superficial velocity q = Q / A_total.", "",
             "| k mDPD (rc^2) | law chosen | k foam, voxel mesh / refined 2x / extrapolated (rc^2) | mDPD / foam "
             "(extrapolated) | within 5% + 2 sigma |",
             "|---|---|---|---|---|",
             f"| {k:.4g} +- {err:.2g} | {ax.get('chosen')} | {k_r[0]:.4g} / {k_r[1]:.4g} / {k_foam:.4g} | "
             f"{ratio:.3f} +- {ratio_err:.3f} | {'yes' if ok else 'NO'} |", "",
             "foam: `mdpore foam --drive periodic --refine 1|2` on the same image; the gaps are 4 voxels wide, so "
             "the voxel mesh alone is second-order far from its continuum limit: k_foam = (4 k_refine2 - k_refine1) / 3.",
             "",
             f"The gaps between rings are {CELL - 2 * R_OUT:g} rc wide (4 voxels): a nanopore where one slip length "
             f"of 0.1 rc changes a slit's k by 6 b / h = {600 * 0.1 / (CELL - 2 * R_OUT):.0f}%."]
    open(os.path.join(a.outdir, f"ring{a.tag}.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(9, 4), gridspec_kw={"width_ratios": [1, 1.3]})
        ax0.imshow(lab[:, 0, :].T, origin="lower", cmap="Greys",
                   extent=[0, lab.shape[0] * RC_PER_VOXEL, 0, lab.shape[2] * RC_PER_VOXEL])
        ax0.set_xlabel("x (rc)")
        ax0.set_ylabel("z (rc), flow")
        ax0.set_title("ring medium (solid black)")
        ax1.errorbar([0], [k], yerr=[err], fmt="o", label="mDPD")
        ax1.plot([1], [k_foam], "s", label="OpenFOAM, same voxels")
        ax1.set_xticks([0, 1], ["mDPD", "foam"])
        ax1.set_ylabel("k (rc^2)")
        ax1.set_title(f"mDPD / foam = {ratio:.3f} +- {ratio_err:.3f}")
        ax1.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(a.outdir, f"ring{a.tag}.png"), dpi=120)
    except ImportError:
        pass
    return 0 if ok else 1


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("stage", choices=["run", "report"])
    ap.add_argument("work")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--ly", type=float, default=4.0, help="thickness along y in rc (default 4)")
    ap.add_argument("--max-steps", type=int, default=40000)
    ap.add_argument("--target-error", type=float, default=0.02)
    ap.add_argument("--gradients", help="body forces (default: the campaign's auto ladder)")
    ap.add_argument("--extra", action="append", default=[], help="more mdpore permeability options, e.g. --extra=--dt --extra=0.005")
    ap.add_argument("--tag", default="", help="suffix of the result files (ring{TAG}.md)")
    ap.add_argument("--outdir", default=os.path.join(sa.ROOT, "validation", "permeability", "results"))
    a = ap.parse_args()
    return run(a) if a.stage == "run" else report(a)


if __name__ == "__main__":
    sys.exit(main() or 0)
