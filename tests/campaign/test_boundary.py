#!/usr/bin/python3
"""ctest campaign_boundary: the boundary treatments of an image that is not periodic along the flow
(docs/permeability.md, "Boundaries"), on a Z-shaped channel (CPU, 2 gradients of <= 3000 steps on
2 ranks, a few seconds each).

Image (rc_per_voxel 0.5): 24 x 20 x 8 voxels (12 x 10 x 4 rc), solid but for a channel 8 voxels (4 rc)
wide in y that runs along x in y = [2, 10) for x < 16, in y = [10, 18) for x >= 8 (the two legs
overlap at x = 8..15, the connector, 8 voxels wide: the critical throat is 8 voxels = 4 rc), open along z. The channel joins the x faces, so the image
percolates along x; but its last slice (pore at y = 10..17) meets its first (pore at y = 2..9) pore to
solid: in a periodic box along x the seam closes the only flow path.

Asserted:
 1. --boundary auto reads the x seam as not periodic (continuity 0) and mirrors: the run scenes read
    WORKDIR/mirror_x.raw (48 x 20 x 8 voxels, the image and its reflection), the box is 24 rc long,
    the manifest and permeability.json name the treatment; the z axis (all open) reads periodic;
 2. --sides mirror doubles y and z too; --boundary periodic sees the seam as a 1-voxel throat and is
    refused without --force, and with it warns that the seam closes flow paths;
    --boundary mirror with --drive pressure is refused; --boundary other is refused;
 3. the flow: with the mirror the runs carry a flux, k_mirror > 0 by more than 5 errors; forced
    periodic, the seam blocks it: |q| of every periodic run is below 10% of the mirror run's at the
    same g (only thermal noise crosses a closed seam).
"""
import json
import os
import shutil
import subprocess
import sys

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "boundary_test_out"))
NP = os.environ.get("MDPORE_TEST_NP", "2")
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def mdpore(*args):
    return subprocess.run([MDPORE, *args], capture_output=True, text=True, cwd=OUT)


def write_z_channel(path):
    nx, ny, nz = 24, 20, 8
    vox = bytearray([1]) * (nx * ny * nz)
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                if (i < 16 and 2 <= j < 10) or (i >= 8 and 10 <= j < 18):
                    vox[i + nx * (j + ny * k)] = 0
    with open(path, "wb") as f:
        f.write(vox)
    with open(path + ".hdr", "w") as f:
        f.write(f"dims: {nx} {ny} {nz}\ntype: uint8\nlabels: pore=0;inorganic=1\n")


def flux_by_g(workdir):
    """q per g of the axis-x runs of a campaign folder, from the run summaries."""
    out = {}
    with open(os.path.join(workdir, "campaign.txt")) as f:
        for line in f:
            if line.startswith("run: x "):
                _, _, g, d = line.split(maxsplit=3)
                s = os.path.join(d.strip(), "summary.json")
                if os.path.exists(s):
                    out[float(g)] = json.load(open(s))["flux"]["q"]
    return out


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    img = os.path.join(OUT, "zchannel.raw")
    write_z_channel(img)
    common = ["--rc-per-voxel", "0.5", "--gradients", "0.065,0.13", "--max-steps", "3000",
              "--target-error", "0.2", "--np", NP, "--mpiexec", "mpiexec --oversubscribe"]

    # 1. auto: mirror along x, periodic along z
    p = mdpore("permeability", img, "--axis", "all", "--emit-scenes", "em_auto", "--rc-per-voxel", "0.5")
    check("boundary along x: mirror" in p.stdout and "boundary along z: periodic" in p.stdout,
          f"auto: x mirrored, z periodic (stdout: {p.stdout[:600]})")
    em = os.path.join(OUT, "em_auto")
    info = mdpore("image", "info", os.path.join(em, "mirror_x.raw"))
    check("48 x 20 x 8" in info.stdout, f"mirror_x.raw is 48 x 20 x 8 ({info.stdout[:120]})")
    manifest = open(os.path.join(em, "campaign.txt")).read()
    check("boundary: mirror none periodic" in manifest or "boundary: mirror" in manifest,
          "the manifest names the treatment per axis")
    scenes = [os.path.join(em, "runs", d, "scene.yaml") for d in os.listdir(os.path.join(em, "runs"))
              if d.startswith("x-")]
    text = open(scenes[0]).read() if scenes else ""
    check("mirror_x.raw" in text and "hi: [24, 10, 4]" in text,
          f"an x run reads the mirrored image in a 24 rc box ({scenes[:1]})")

    # 2. sides mirror, periodic warning, refusals
    p = mdpore("permeability", img, "--axis", "x", "--emit-scenes", "em_sides", "--rc-per-voxel", "0.5",
               "--sides", "mirror")
    info = mdpore("image", "info", os.path.join(OUT, "em_sides", "mirror_x.raw"))
    check(p.returncode == 0 and "48 x 40 x 16" in info.stdout, f"--sides mirror: 48 x 40 x 16 ({info.stdout[:120]})")
    # forced periodic, the seam is a wall one voxel from the channel: the critical throat through
    # the runs' faces is 1 voxel, so the campaign refuses it without --force
    p = mdpore("permeability", img, "--axis", "x", "--emit-scenes", "em_per0", "--rc-per-voxel", "0.5",
               "--boundary", "periodic")
    check(p.returncode != 0 and "critical throat along x is 1 voxel" in p.stderr,
          f"--boundary periodic: the seam's throat refused ({p.stderr[-300:]})")
    p = mdpore("permeability", img, "--axis", "x", "--emit-scenes", "em_per", "--rc-per-voxel", "0.5",
               "--boundary", "periodic", "--force")
    check(p.returncode == 0 and "closes or invents flow paths" in p.stderr,
          f"--boundary periodic on a non-periodic image warns ({p.stderr[-300:]})")
    p = mdpore("permeability", img, "--axis", "x", "--emit-scenes", "em_bad", "--boundary", "mirror",
               "--drive", "pressure")
    check(p.returncode != 0 and "--boundary mirror" in p.stderr, f"mirror + pressure refused ({p.stderr[-200:]})")
    p = mdpore("permeability", img, "--axis", "x", "--emit-scenes", "em_bad", "--boundary", "open")
    check(p.returncode != 0 and "--boundary" in p.stderr, "an unknown treatment refused")

    # 3. the flow through the seam
    pm = mdpore("permeability", img, "--axis", "x", "--workdir", "mirror", *common)
    print(pm.stdout[-1500:])
    pp = mdpore("permeability", img, "--axis", "x", "--workdir", "periodic", "--boundary", "periodic", "--force",
               *common)
    print(pp.stdout[-1500:])
    qm, qp = flux_by_g(os.path.join(OUT, "mirror")), flux_by_g(os.path.join(OUT, "periodic"))
    check(len(qm) == 2 and len(qp) == 2, f"both campaigns ran their 2 runs ({len(qm)}, {len(qp)})")
    pj = os.path.join(OUT, "mirror", "permeability.json")
    if os.path.exists(pj):
        j = json.load(open(pj))
        check(j.get("boundary", {}).get("x", {}).get("faces") == "mirror",
              "permeability.json names the mirror treatment")
        ax = j["axes"]["x"]
        k, e = ax.get("k_rc2"), ax.get("k_rc2_err")
        check(k is not None and e is not None and k > 5 * e, f"k_mirror = {k} +- {e} > 5 errors")
    else:
        check(False, "the mirror campaign wrote permeability.json")
    for g in sorted(qm):
        if g in qp:
            check(abs(qp[g]) < 0.1 * qm[g],
                  f"g = {g}: periodic q = {qp[g]:.3g} below 10% of the mirror's {qm[g]:.3g} (the seam is closed)")
    print(f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
