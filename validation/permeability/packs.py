#!/usr/bin/env python3
"""The POREMAPS BCC and FCC overlapping-sphere packs (../shared/data/external/
poremaps_benchmarks, 100^3 voxels, porosity 0.30), mDPD against `mdpore foam` on the SAME voxels: a
table of k_mDPD / k_foam with error bars and a PNG. Both run on the image downsampled by
--downsample (majority vote; 2: 50^3 voxels, a 25 rc box, for a GPU; 4, the default: 25^3 voxels, a
12.5 rc box of ~10^4 particles that a 2-core CPU runs in minutes) at 0.5 rc per voxel. foam runs on
the same downsampled voxels. `--pack drp` adds the drp-benchmarks random sphere pack (621 spheres of
radius 3.5 in a periodic 55.2 x 55.4 x 55.5 box, ../shared/data/external/drp_spherepack), voxelised
with --drp-dx (default 0.5: R = 7 voxels = 3.5 rc at 0.5 rc per voxel, 110 x 111 x 111 voxels, a
55 rc box of ~0.55 M particles: a GPU campaign); its foam runs on the voxel mesh only (refine 2 would
be 3.7 M cells), periodic (the pack is periodic; the end faces where pore meets solid are walls).

  packs.py emit WORK     images, foam (here), the campaigns emitted (WORK/commands.txt: run anywhere)
  packs.py run WORK      emit, then every run of WORK/commands.txt here, one after another
  packs.py report WORK   collect, the table, validation/permeability/results/packs.{md,csv,png}
Same stages and conventions as sphere_array.py (body force along x, bounce_back, mu = 5.41).
"""
import argparse
import csv
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sphere_array as sa  # noqa: E402  (sh, MDPORE, RC_PER_VOXEL, MU_*)

EXT = os.path.join(sa.ROOT, "..", "shared", "data", "external", "poremaps_benchmarks")
DRP = os.path.join(sa.ROOT, "..", "shared", "data", "external", "drp_spherepack")
DRP_RADIUS = 3.5  # the pack's sphere radius in its own units (Box_DIM.dat, final_loc_cn1.dat)
PACKS = {"bcc": "SPHERE3D_bcc_NX100_NY100_NZ100_PHI0.3_DIAMETER0.0008745237084764591_VSIZE1e-05.raw",
         "fcc": "SPHERE3D_fcc_NX100_NY100_NZ100_PHI0.3_DIAMETER0.000693979234383925_VSIZE1e-05.raw"}


def emit(a):
    os.makedirs(a.work, exist_ok=True)
    cmds = []
    for pack in a.pack:
        d = os.path.join(a.work, pack)
        os.makedirs(d, exist_ok=True)
        img = os.path.join(d, "image.h5")
        if not os.path.exists(img) and pack == "drp":
            sa.sh("image", "make", "sphere-file", "--centres", os.path.join(DRP, "final_loc_cn1.dat"), "--box-file",
                  os.path.join(DRP, "Box_DIM.dat"), "--radius", str(DRP_RADIUS), "--dx", str(a.drp_dx), "-o", img)
        elif not os.path.exists(img):
            sa.sh("image", "convert", os.path.join(EXT, PACKS[pack]), "--dims", "100x100x100", "--labels",
                  "pore=0,inorganic=1", "--downsample", str(a.downsample), "-o", img)
        for refine in a.foam_refine if pack != "drp" else [1]:  # the voxel mesh and each voxel cut in 2^3 (report: extrapolation)
            fj = os.path.join(d, f"foam_r{refine}.json")
            if not os.path.exists(fj):  # periodic like the mDPD runs; pressure where the end slices differ
                p = subprocess.run([sa.MDPORE, "foam", img, "--axis", "x", "--drive", "periodic", "--refine",
                                    str(refine)], capture_output=True, text=True)
                out = p.stdout if p.returncode == 0 else sa.sh("foam", img, "--axis", "x", "--drive", "pressure",
                                                               "--refine", str(refine))
                open(fj, "w").write(out)
        em = os.path.join(d, "emit")
        if not os.path.exists(os.path.join(em, "commands.txt")):
            grads = a.gradients
            if grads and "=" in grads:  # per pack: bcc=0.05,0.1;fcc=0.15,0.3
                grads = dict(kv.split("=", 1) for kv in grads.split(";")).get(pack)
            extra = ["--gradients", grads] if grads else []
            extra += ["--wall-density", str(a.wall_density)] if a.wall_density is not None else []
            sa.sh("permeability", img, "--axis", "x", "--emit-scenes", em, "--rc-per-voxel", str(sa.RC_PER_VOXEL),
                  "--max-steps", str(a.max_steps), "--target-error", str(a.target_error), "--np", str(a.np), *extra)
        cmds += open(os.path.join(em, "commands.txt")).read().splitlines()
    open(os.path.join(a.work, "commands.txt"), "w").write("\n".join(cmds) + "\n")
    print(f"{len(cmds)} runs in {os.path.join(a.work, 'commands.txt')}")


def run(a):
    emit(a)
    sa.run_commands(a.work)
    return report(a)


def report(a):
    rows, viscosity_note = [], ""
    for pack in a.pack:
        d = os.path.join(a.work, pack)
        # k of the voxels' continuum limit (sa.foam_continuum), the voxel mesh where refine 2 did not run
        levels = [r for r in (1, 2) if os.path.exists(os.path.join(d, f"foam_r{r}.json"))]
        foams = [json.load(open(os.path.join(d, f"foam_r{r}.json"))) for r in levels]
        foam = foams[0]
        k_r = [f["permeability_voxel2"] * sa.RC_PER_VOXEL ** 2 for f in foams] + [float("nan")]
        k_foam = sa.foam_continuum(k_r[0], k_r[1]) if len(levels) == 2 else k_r[0]
        em = os.path.join(d, "emit")
        subprocess.run([sa.MDPORE, "permeability", "--collect", em], capture_output=True, text=True)
        pj = json.load(open(os.path.join(em, "permeability.json")))
        ax = pj["axes"]["x"]
        viscosity_note = f"mu = {pj['viscosity']:g}: {pj['viscosity_source']}; wall density {pj.get('wall_density', 8)}"
        k, err = ax["k_rc2"], ax["k_rc2_err"]
        dr = ax.get("darcy_range") or {}
        if dr.get("accepted"):  # the zero-forcing k: the rows above the linear range left out
            k, err = dr["k_rc2"], dr["k_rc2_err"]
        rows.append(dict(pack=pack, porosity=foam["porosity"], foam_drive=foam["drive"], k_mdpd=k, k_mdpd_err=err,
                         k_foam_refine1=k_r[0], k_foam_refine2=k_r[1], k_foam=k_foam,
                         ratio=k / k_foam, ratio_err=err / k_foam,
                         law=ax.get("chosen"), darcy_rows=dr.get("rows") if dr.get("accepted") else ax.get("rows")))
    os.makedirs(a.outdir, exist_ok=True)
    with open(os.path.join(a.outdir, f"packs{a.tag}.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = ["# POREMAPS BCC / FCC packs: mDPD against OpenFOAM on the same voxels", "",
             f"Command: `/usr/bin/python3 validation/permeability/packs.py run WORK --downsample {a.downsample} "
             f"--np {a.np} --max-steps {a.max_steps} --target-error {a.target_error} --pack {' '.join(a.pack)}"
             + (f" --wall-density {a.wall_density:g}" if a.wall_density is not None else "")
             + (f" --gradients {a.gradients}" if a.gradients else "") + "`. POREMAPS images downsampled "
             f"{a.downsample}x to {100 // a.downsample}^3 voxels at 0.5 rc per voxel ({50 / a.downsample:g} rc box)"
             + (f"; drp: spheres of radius {DRP_RADIUS} voxelised at dx {a.drp_dx} ({DRP_RADIUS / a.drp_dx:g} voxels = "
                f"{DRP_RADIUS / a.drp_dx * sa.RC_PER_VOXEL:g} rc)" if "drp" in a.pack else "") + "; k in "
             f"rc^2, superficial velocity; the campaign's wall density and mu ({viscosity_note}).", "",
             "k foam: `mdpore foam --refine 1|2` on the same voxels, extrapolated (4 k2 - k1) / 3 (second order); "
             "where only the voxel mesh ran (refine 1, `--foam-refine 1`), that value, which is high by the "
             "scheme's error in throats a few voxels wide (the ring medium's 4-voxel gaps: 18%).", "",
             "k mDPD: the Darcy range's k where the campaign found one (the rows of the lowest gradients that a Darcy "
             "law fits; docs/permeability.md), else the Darcy fit over all rows.", "",
             "| pack | porosity | k mDPD (rc^2) | rows in k | k foam voxel mesh / refined / extrapolated (rc^2, drive) | mDPD / foam | fitted law |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['pack']} | {r['porosity']:.3f} | {r['k_mdpd']:.4g} +- {r['k_mdpd_err']:.2g} | {r['darcy_rows']} | "
                     f"{r['k_foam_refine1']:.4g} / {r['k_foam_refine2']:.4g} / {r['k_foam']:.4g} ({r['foam_drive']}) | {r['ratio']:.3f} +- {r['ratio_err']:.3f} | {r['law']} |")
    open(os.path.join(a.outdir, f"packs{a.tag}.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(4.5, 3.5))
        ax.errorbar(range(len(rows)), [r["ratio"] for r in rows], yerr=[r["ratio_err"] for r in rows], fmt="o",
                    label="mDPD / foam")
        ax.axhspan(0.95, 1.05, color="0.9")
        ax.set_xticks(range(len(rows)), [r["pack"] for r in rows])
        ax.set_ylabel("k mDPD / k foam")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(a.outdir, f"packs{a.tag}.png"), dpi=120)
    except ImportError:
        pass
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("stage", choices=["emit", "run", "report"])
    ap.add_argument("work")
    ap.add_argument("--wall-density", type=float, help="the campaign's wall patch density (default its own, 4)")
    ap.add_argument("--max-steps", type=int, default=40000)
    ap.add_argument("--downsample", type=int, default=4, help="majority downsampling of the 100^3 image (2 or 4)")
    ap.add_argument("--pack", nargs="+", default=["bcc", "fcc"], choices=["bcc", "fcc", "drp"],
                    help="packs (default bcc fcc; drp: the random sphere pack, a GPU campaign)")
    ap.add_argument("--drp-dx", type=float, default=0.5,
                    help="drp voxel edge in the pack's units (R = 3.5): 0.5 gives R = 7 voxels = 3.5 rc")
    ap.add_argument("--np", type=int, default=2, help="ranks per run")
    ap.add_argument("--foam-refine", type=int, nargs="+", default=[1, 2], choices=[1, 2],
                    help="foam meshes: 1 = the voxels, 2 = each voxel cut in 2^3 (default both: extrapolated)")
    ap.add_argument("--gradients", help="body forces (default: the campaign's auto ladder), or per pack: "
                                        "'bcc=0.05,0.1;fcc=0.15,0.3'")
    ap.add_argument("--target-error", type=float, default=0.02)
    ap.add_argument("--tag", default="", help="suffix of the result files (packs{TAG}.md)")
    ap.add_argument("--outdir", default=os.path.join(sa.ROOT, "validation", "permeability", "results"))
    a = ap.parse_args()
    return {"emit": emit, "run": run, "report": report}[a.stage](a)


if __name__ == "__main__":
    sys.exit(main() or 0)
