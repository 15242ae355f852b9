#!/usr/bin/env python3
"""The continuum limit. Simple-cubic sphere arrays resolved at >= 20 rc per
cell (40 and 48 voxels per cell edge at 0.5 rc per voxel), the mDPD permeability (mdpore
permeability, body force along x) against Zick & Homsy (1982, Stokes) and against `mdpore foam`
(OpenFOAM, the SAME voxels, periodic drive, staircase walls); the target is agreement within 5%.

Two stages, because the mDPD runs want a GPU:
  sphere_array.py emit WORK [--max-steps N] [--target-error E]
      images, the foam runs (here, CPU), and each case's campaign emitted (mdpore permeability
      --emit-scenes): WORK/commands.txt lists every run (run them anywhere, e.g. on a GPU machine,
      in the same folder tree);
  sphere_array.py run WORK [--case sph40_c0.125] [--np N] [--gradients LIST]
      emit, then every run of WORK/commands.txt here, one after another (a CPU campaign: one
      case at 20 rc per cell is ~47k particles, minutes per 10^4 steps on 2 cores), then report;
  sphere_array.py report WORK [--outdir DIR]
      mdpore permeability --collect per case, the table (k_mDPD, k_foam, k_ZH in rc^2, ratios with
      errors), validation/permeability/results/sphere_array.{md,csv,png}; exit 1 when a ratio
      k_mDPD / k_foam is off 1 by more than 5% + 2 sigma;
  sphere_array.py draws TAG1,TAG2,... [--tag _draws]
      independent draws (reports of campaigns with different --seed, sphere_array{TAGi}.csv) side
      by side per case: each ratio with its error, their weighted mean, scatter and chi^2 per
      degree of freedom (do the error bars hold?), sphere_array{TAG}.md; exit 1 when a draw fails
      the 5% + 2 sigma rule.
Run with /usr/bin/python3 (numpy, matplotlib). MDPORE: the mdpore binary (default build/bin/mdpore).
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MDPORE = os.environ.get("MDPORE") or os.path.join(ROOT, "build", "bin", "mdpore")
RC_PER_VOXEL = 0.5
# Zick & Homsy (1982), simple-cubic spheres: k / L^2 against solid fraction c (validation/foam)
ZICK_HOMSY = {0.125: 0.03985, 0.343: 7.933e-3}
# (voxels per cell edge, c, rc per voxel); the others only when named with --case: a 20 rc cell at
# 0.25 rc voxels (a smoother staircase on the same spheres), and 40 rc cells at 0.5 rc voxels (twice
# the resolution of the spheres in rc: ~0.4 M particles, a GPU campaign)
CASES = [(40, 0.125, 0.5), (40, 0.343, 0.5), (48, 0.125, 0.5), (80, 0.125, 0.25), (80, 0.125, 0.5),
         (80, 0.343, 0.5)]
DEFAULT_CASES = 3


def foam_continuum(k_voxel_mesh, k_refined):
    """foam's continuum k of a voxel image from its voxel mesh and the mesh with each voxel cut in 2^3
    cells: the two-point scheme is second order, so Richardson's (4 k_refined - k_voxel_mesh) / 3.
    Throats a few voxels wide are where the voxel mesh alone reads high (sphere arrays 3-6%, the
    ring and the packs 12-21%). Used by every continuum comparison (sphere arrays, ring, packs)
    and the README's main job."""
    return (4 * k_refined - k_voxel_mesh) / 3


def foam_k_files(voxel_mesh_json, refined_json, rc_per_voxel):
    """(voxel mesh, refined 2x, continuum) k in rc^2 from two `mdpore foam` JSON outputs."""
    k1, k2 = (json.load(open(f))["permeability_voxel2"] * rc_per_voxel ** 2 for f in (voxel_mesh_json, refined_json))
    return k1, k2, foam_continuum(k1, k2)


def name(L, c, rcv=RC_PER_VOXEL):
    """sph{voxels}_c{c}; cells of 40 rc or more say so (sph80_c0.125_40rc: 80 voxels of 0.5 rc)."""
    return f"sph{L}_c{c:g}" + (f"_{L * rcv:g}rc" if L * rcv >= 40 else "")


def sh(*args, cwd=None):
    p = subprocess.run([MDPORE, *args], cwd=cwd, capture_output=True, text=True)
    if p.returncode:
        sys.exit(f"mdpore {' '.join(args)}: exit {p.returncode}\n{p.stderr[-2000:]}")
    return p.stdout


def emit(a):
    os.makedirs(a.work, exist_ok=True)
    cmds = []
    for L, c, rcv in cases(a):
        d = os.path.join(a.work, name(L, c, rcv))
        os.makedirs(d, exist_ok=True)
        img = os.path.join(d, "image.h5")
        if not os.path.exists(img):
            sh("image", "make", "spheres", "--cell", str(L), "--c", str(c), "-o", img)
        for refine in a.foam_refine:  # foam.json: the voxel mesh; foam_r2.json: each voxel cut in 2^3
            fj = os.path.join(d, "foam.json" if refine == 1 else f"foam_r{refine}.json")
            if not os.path.exists(fj):
                out = sh("foam", img, "--axis", "x", "--drive", "periodic", "--refine", str(refine), "--np",
                         str(a.foam_np))
                with open(fj, "w") as f:
                    f.write(out)
        em = os.path.join(d, "emit")
        if not os.path.exists(os.path.join(em, "commands.txt")):
            extra = ["--gradients", a.gradients] if a.gradients else []
            extra += ["--seed", str(a.seed)] if a.seed is not None else []
            extra += ["--wall-density", str(a.wall_density)] if a.wall_density is not None else []
            sh("permeability", img, "--axis", "x", "--emit-scenes", em, "--rc-per-voxel", str(rcv),
               "--max-steps", str(a.max_steps), "--target-error", str(a.target_error), "--np", str(a.np), *extra)
        cmds += open(os.path.join(em, "commands.txt")).read().splitlines()
    with open(os.path.join(a.work, "commands.txt"), "w") as f:
        f.write("\n".join(cmds) + "\n")
    print(f"{len(cmds)} runs in {os.path.join(a.work, 'commands.txt')}")


def cases(a):
    chosen = [(L, c, r) for i, (L, c, r) in enumerate(CASES)
              if (name(L, c, r) in a.case if a.case else i < DEFAULT_CASES)]
    if not chosen:
        sys.exit(f"sphere_array.py: --case: expected one of {', '.join(name(L, c, r) for L, c, r in CASES)}")
    return chosen


def run_commands(work):
    """Every line of WORK/commands.txt (emitted campaigns: `cd RUN && mpiexec ... run scene.yaml`) here,
    one after another, skipping the runs whose summary.json exists (finished before)."""
    cmds = open(os.path.join(work, "commands.txt")).read().splitlines()
    for i, cmd in enumerate(cmds):
        m = re.match(r"cd '([^']+)'", cmd)
        if m and os.path.exists(os.path.join(m.group(1), "summary.json")):
            print(f"[{i + 1}/{len(cmds)}] finished before: {m.group(1)}", flush=True)
            continue
        print(f"[{i + 1}/{len(cmds)}] {cmd}", flush=True)
        subprocess.run(["bash", "-c", cmd], check=False)


def run(a):
    emit(a)
    run_commands(a.work)
    return report(a)


def report(a):
    rows, setup = [], ""
    for L, c, rcv in cases(a):
        d = os.path.join(a.work, name(L, c, rcv))
        foam = json.load(open(os.path.join(d, "foam.json")))
        k_foam1 = foam["permeability_voxel2"] * rcv ** 2
        # the continuum k of these voxels; the voxel mesh alone where refine 2 did not run
        f2 = os.path.join(d, "foam_r2.json")
        k_foam2 = json.load(open(f2))["permeability_voxel2"] * rcv ** 2 if os.path.exists(f2) else float("nan")
        k_foam = foam_continuum(k_foam1, k_foam2) if os.path.exists(f2) else k_foam1
        k_zh = ZICK_HOMSY[c] * (L * rcv) ** 2
        em = os.path.join(d, "emit")
        if os.path.isdir(os.path.join(em, "runs")):  # else the campaign's report as it came back from a GPU machine
            subprocess.run([MDPORE, "permeability", "--collect", em], capture_output=True, text=True)
        pj = json.load(open(os.path.join(em, "permeability.json")))
        ax = pj["axes"]["x"]
        k, err = ax["k_rc2"], ax["k_rc2_err"]  # the Darcy k of the campaign (its report's k)
        dr = ax.get("darcy_range") or {}
        if dr.get("accepted"):  # the zero-forcing k: the rows above the linear range left out
            k, err = dr["k_rc2"], dr["k_rc2_err"]
        mu = pj["viscosity"]
        setup = (f"mu = {mu:g} ({pj.get('viscosity_source', '')}), wall density "
                 f"{pj.get('wall_density', 8):g}")
        rows.append(dict(case=name(L, c, rcv), cell_rc=L * rcv, rc_per_voxel=rcv, c=c, porosity=foam["porosity"],
                         k_mdpd=k, k_mdpd_err=err, k_foam_refine1=k_foam1, k_foam_refine2=k_foam2,
                         k_foam=k_foam, k_zh=k_zh,
                         mdpd_over_foam=k / k_foam, mdpd_over_foam_err=err / k_foam,
                         mdpd_over_zh=k / k_zh, foam_over_zh=k_foam / k_zh,
                         rows_table=ax.get("rows"), law=ax.get("chosen"),
                         viscosity=mu,
                         sphere_radius_rc=L * rcv * (3 * c / (4 * 3.141592653589793)) ** (1 / 3)))
    out = a.outdir
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, f"sphere_array{a.tag}.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    bad = [r for r in rows if abs(r["mdpd_over_foam"] - 1) > 0.05 + 2 * r["mdpd_over_foam_err"]]
    lines = ["# Sphere arrays at >= 20 rc per cell: mDPD against Zick & Homsy and OpenFOAM", "",
             f"Command: `/usr/bin/python3 validation/permeability/sphere_array.py emit|run|report WORK"
             + "".join(f" --case {x}" for x in (a.case or [])) + (f" --gradients {a.gradients}" if a.gradients else "")
             + (f" --seed {a.seed}" if a.seed is not None else "")
             + (f" --wall-density {a.wall_density:g}" if a.wall_density is not None else "")
             + f" --max-steps {a.max_steps} --target-error {a.target_error}`. k in rc^2 (superficial velocity "
             f"q = Q / A_total), rc per voxel as listed, body force along x, bounce_back walls, {setup}.", "",
             "k foam: `mdpore foam --drive periodic` on the same voxels, on the voxel mesh and with each voxel cut "
             "in 2^3 cells, extrapolated (4 k2 - k1) / 3 (second order; the voxel mesh alone where refine 2 did "
             "not run: then the two columns read nan). mDPD/foam is against the extrapolated value.", "",
             "| case | cell (rc) | rc/voxel | c | mu | k mDPD | k foam voxel mesh / refined 2x / extrapolated | k ZH | mDPD/foam | mDPD/ZH | foam/ZH |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['cell_rc']:g} | {r['rc_per_voxel']:g} | {r['c']:g} | {r['viscosity']:.4g} | {r['k_mdpd']:.4g} +- {r['k_mdpd_err']:.2g} | "
                     f"{r['k_foam_refine1']:.4g} / {r['k_foam_refine2']:.4g} / {r['k_foam']:.4g} | {r['k_zh']:.4g} | {r['mdpd_over_foam']:.3f} +- {r['mdpd_over_foam_err']:.3f} | "
                     f"{r['mdpd_over_zh']:.3f} | {r['foam_over_zh']:.3f} |")
    lines += ["", "Check (the 5% target): |mDPD/foam - 1| <= 0.05 + 2 sigma: " +
              ("passes for every case." if not bad else "FAILS for " + ", ".join(r["case"] for r in bad) + "."), "",
              "The viscosity is the campaign's (its source above): the standard water's at the "
              "density the runs measured in the pore core (docs/permeability.md, 'Conventions and units'); "
              "campaigns whose summaries carry no such measurement use 5.41 (n = 6.07). What this "
              "comparison rules out: docs/permeability.md, 'Sphere arrays against Zick & Homsy and OpenFOAM'."]
    open(os.path.join(out, f"sphere_array{a.tag}.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        for i, r in enumerate(rows):
            ax.errorbar(i, r["mdpd_over_foam"], yerr=r["mdpd_over_foam_err"], fmt="o", color="C0",
                        label="mDPD / foam" if i == 0 else None)
            ax.plot(i, r["mdpd_over_zh"], "s", color="C1", label="mDPD / Zick-Homsy" if i == 0 else None)
            ax.plot(i, r["foam_over_zh"], "^", color="C2", label="foam / Zick-Homsy" if i == 0 else None)
        ax.axhspan(0.95, 1.05, color="0.9")
        ax.set_xticks(range(len(rows)), [r["case"] for r in rows])
        ax.set_ylabel("permeability ratio")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, f"sphere_array{a.tag}.png"), dpi=120)
    except ImportError:
        pass
    return 1 if bad else 0


def draws(a):
    """The draws named in a.work (comma-separated report tags) side by side, per case."""
    tags = [t for t in a.work.split(",") if t]
    rows = {}
    for t in tags:
        f = os.path.join(a.outdir, f"sphere_array{t}.csv")
        if not os.path.exists(f):
            sys.exit(f"sphere_array.py draws: {f}: no such report (run `report` with --tag {t} first)")
        for r in csv.DictReader(open(f)):
            ref = "voxel mesh" if r["k_foam_refine2"] in ("", "nan") else "continuum (refined 2x, extrapolated)"
            rows.setdefault(r["case"], []).append((t, float(r["mdpd_over_foam"]), float(r["mdpd_over_foam_err"]), ref))
    lines = ["# Sphere arrays: independent draws of k_mDPD / k_foam (foam on the same voxels)", "",
             f"Draws: {', '.join(tags)} (validation/permeability/results/sphere_array{{TAG}}.csv).", "",
             "| case | foam reference | draws | each: ratio +- error | weighted mean | scatter (sd) | chi^2 / dof | "
             "every draw within 5% + 2 sigma |",
             "|---|---|---:|---|---|---:|---:|---|"]
    bad = 0
    for case, d in rows.items():
        r = [x[1] for x in d]
        e = [x[2] for x in d]
        w = [1 / x ** 2 for x in e]
        mean = sum(wi * ri for wi, ri in zip(w, r)) / sum(w)
        err = sum(w) ** -0.5
        n = len(r)
        sd = (sum((ri - sum(r) / n) ** 2 for ri in r) / (n - 1)) ** 0.5 if n > 1 else float("nan")
        chi2 = sum(((ri - mean) / ei) ** 2 for ri, ei in zip(r, e)) / (n - 1) if n > 1 else float("nan")
        ok = all(abs(ri - 1) <= 0.05 + 2 * ei for ri, ei in zip(r, e))
        bad += not ok
        refs = sorted({x[3] for x in d})
        lines.append(f"| {case} | {' / '.join(refs)} | {n} | {', '.join(f'{ri:.3f} +- {ei:.3f}' for ri, ei in zip(r, e))} | "
                     f"{mean:.3f} +- {err:.3f} | {sd:.3f} | {chi2:.2f} | {'yes' if ok else 'NO'} |")
    lines += ["", "chi^2 / dof near 1: the draws scatter as their error bars say; well above 1: the error bars are "
              "understated."]
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(a.outdir, f"sphere_array{a.tag or '_draws'}.md"), "w") as f:
        f.write(text)
    return 1 if bad else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("stage", choices=["emit", "run", "report", "draws"])
    ap.add_argument("--case", action="append", help="only these cases (default all), e.g. sph40_c0.125")
    ap.add_argument("--np", type=int, default=1, help="ranks per run in commands.txt")
    ap.add_argument("--tag", default="", help="suffix of the result files (sphere_array{TAG}.md)")
    ap.add_argument("--gradients", help="body forces (default: the campaign's auto ladder)")
    ap.add_argument("--seed", type=int, help="the campaign's base seed (default its own): an independent repeat")
    ap.add_argument("work", help="the work folder (draws: the report tags, comma-separated)")
    ap.add_argument("--wall-density", type=float, help="the campaign's wall patch density (default its own, 4)")
    ap.add_argument("--foam-refine", type=int, nargs="+", default=[1, 2], choices=[1, 2],
                    help="foam meshes: 1 = the voxels, 2 = each voxel cut in 2^3 (default both: extrapolated)")
    ap.add_argument("--foam-np", type=int, default=2, help="OpenFOAM ranks (default 2)")
    ap.add_argument("--max-steps", type=int, default=200000)
    ap.add_argument("--target-error", type=float, default=0.02)
    ap.add_argument("--outdir", default=os.path.join(ROOT, "validation", "permeability", "results"))
    a = ap.parse_args()
    return {"emit": emit, "run": run, "report": report, "draws": draws}[a.stage](a)


if __name__ == "__main__":
    sys.exit(main() or 0)
