#!/usr/bin/env python3
"""Real rock crops: the mDPD permeability with the default boundary treatment and resolution against
the continuum (OpenFOAM) on the same voxels with the same boundary treatment (docs/permeability.md,
"Real rock images"; ../shared/data/external/rocks).

Per rock and crop size (cubes at a fixed corner), per axis:
  * mdpore foam CROP --axis A --boundary mirror --sides periodic at one cell per voxel and at
    --refine 2: the like-for-like reference of an mDPD campaign with its defaults (the flow axis
    mirrored, the lateral faces periodic); the reference k is the voxels' continuum limit by
    Richardson extrapolation of the second-order finite-volume error (k_inf = (4 k_r2 - k_r1) / 3:
    a slit of N cells reads (h^2/12)(1 + 2/N^2)), the voxel mesh and the refined one both reported;
  * mdpore permeability CROP --axis all with its defaults (boundary auto, resolution from the
    critical throat), emitted here, run anywhere (a GPU through `device`), collected here;
  * optional extra resolutions (--refine-rc LIST: rc per voxel values of one crop, axis x) for the
    trend of the gap with resolution.
Checks (exit 1 when one fails): |k_mDPD / k_foam - 1| <= 10% at the default resolution; every run's
pore-core density within 3% of the fill; penetrations 0.

Stages (WORK holds everything, relative paths only in what travels):
  rocks.py foam WORK       crops and the foam references (here, on the CPU)
  rocks.py emit WORK       the campaigns' scenes (WORK/runs.txt: one run folder per line, relative)
  rocks.py device WORK     run every scene of runs.txt with $MDPORE, JOBS at once (on the GPU machine)
  rocks.py report WORK     collect the campaigns, the table and PNG in validation/rocks/results/
  rocks.py rev WORK        porosity and the continuum k_xx, k_yy, k_zz of cubes of growing size, the
                           anisotropy ratio, the mDPD k where a campaign defined one (rev.md, rev.png)
  rocks.py quick WORK      the CI-sized variant on the CPU: the 16^3 Berea crop of cases/rock, axis x,
                           the campaign with its defaults on NP ranks and foam at 1 and 2 cells per
                           voxel; fails unless the boundary is mirror, the throat is >= 4 rc, no
                           particle entered a wall, k is defined and k_mDPD / k_foam is within 10%
Run with /usr/bin/python3 (numpy, matplotlib). MDPORE: the mdpore binary (default build/bin/mdpore).
"""
import argparse
import concurrent.futures
import csv
import json
import os
import re
import subprocess
import sys
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
MDPORE = os.environ.get("MDPORE") or os.path.join(ROOT, "build", "bin", "mdpore")
ROCKS = os.path.join(ROOT, "..", "shared", "data", "external", "rocks")
RESULTS = os.environ.get("MDPORE_VALIDATION_OUT") or os.path.join(ROOT, "validation", "rocks", "results")
ROCK_FILES = {"berea": ("berea_300", 300), "fontainebleau": ("fontainebleau_200", 200)}
AXES = "xyz"


def sh(*args, cwd=None, check=True):
    p = subprocess.run([MDPORE, *args], cwd=cwd, capture_output=True, text=True)
    if check and p.returncode != 0:
        sys.exit(f"mdpore {' '.join(args)}: exit {p.returncode}\n{p.stderr[-3000:]}")
    return p


def crops(a):
    """(rock, size, name) of every crop asked for: --crops ROCK:SIZE[:OFFSET] ..., else every --rock
    at every --sizes (at --offset)."""
    if a.crops:
        return [(c.split(":")[0], int(c.split(":")[1]), f"{c.split(':')[0]}_{c.split(':')[1]}") for c in a.crops]
    return [(r, s, f"{r}_{s}") for r in a.rock for s in a.sizes]


def crop_offset(a, rock, size):
    """The crop's corner (x, y, z) in voxels: OFFSET of --crops is one number for all three axes or
    X,Y,Z; else --offset on each axis."""
    for c in a.crops or []:
        f = c.split(":")
        if f[0] == rock and int(f[1]) == size and len(f) > 2:
            o = [int(v) for v in f[2].split(",")]
            if len(o) not in (1, 3):
                sys.exit(f"--crops {c}: expected OFFSET as one number or X,Y,Z")
            return tuple(o * 3 if len(o) == 1 else o)
    return (a.offset,) * 3


def make_crop(a, rock, size, name):
    d = os.path.join(a.work, name)
    os.makedirs(d, exist_ok=True)
    img = os.path.join(d, "crop.raw")
    if not os.path.exists(img):
        base, n = ROCK_FILES[rock]
        o = crop_offset(a, rock, size)
        sh("image", "convert", os.path.join(ROCKS, base, base + ".raw"), "--crop",
           ",".join(f"{v}:{v + size}" for v in o), "-o", img)
    return d, img


def foam_stage(a):
    for rock, size, name in crops(a):
        d, img = make_crop(a, rock, size, name)
        info = json.loads(sh("image", "info", img, "--json").stdout)
        json.dump(info, open(os.path.join(d, "info.json"), "w"))
        for ax in AXES:
            for refine in a.foam_refine:
                out = os.path.join(d, f"foam_{ax}_r{refine}.json")
                if os.path.exists(out):
                    continue
                t0 = time.time()
                p = sh("foam", img, "--axis", ax, "--boundary", "mirror", "--sides", "periodic", "--refine",
                       str(refine), "--np", str(a.np), check=False)
                if p.returncode == 0:
                    open(out, "w").write(p.stdout)
                    k = json.loads(p.stdout)["permeability_voxel2"]
                    print(f"{name} {ax} refine {refine}: k = {k:.5g} voxel^2 ({time.time() - t0:.0f} s)", flush=True)
                else:
                    open(out, "w").write(json.dumps({"error": p.stderr[-1500:], "exit": p.returncode}))
                    print(f"{name} {ax} refine {refine}: foam exit {p.returncode}: {p.stderr[-300:]}", flush=True)


def portable(scene_path, work):
    """Paths inside WORK written relative to the scene's folder: the run folders travel."""
    text = open(scene_path).read()
    rel = os.path.relpath(work, os.path.dirname(scene_path))
    new = text.replace(os.path.abspath(work) + "/", rel + "/")
    if new != text:
        open(scene_path, "w").write(new)


def campaigns(a):
    """(name, campaign folder, extra options) per crop and resolution. The default campaign runs
    --axis all; where the narrowest throat over the three axes is refused at the default resolution,
    one campaign per axis instead (each at its own default resolution, a refused axis reported)."""
    out = []
    for rock, size, name in crops(a):
        d = os.path.join(a.work, name)
        if a.per_axis or os.path.exists(os.path.join(d, "default.refused")):
            for ax in AXES:
                out.append((name, os.path.join(d, f"default_{ax}"), a.campaign_args.split() + ["--axis", ax]))
        else:
            out.append((name, os.path.join(d, "default"), a.campaign_args.split()))
        if size == min(a.sizes):
            for rcv in a.refine_rc:
                out.append((name, os.path.join(d, f"rc{rcv:g}"), ["--rc-per-voxel", f"{rcv:g}", "--force", "--axis", "x"]))
    return out


def emit_stage(a):
    runs = []
    for rock, size, name in crops(a):
        make_crop(a, rock, size, name)
    for name, em, extra in campaigns(a):
        img = os.path.join(os.path.dirname(em), "crop.raw")
        if not os.path.exists(os.path.join(em, "commands.txt")):
            axis = [] if "--axis" in extra else ["--axis", "all"]
            p = sh("permeability", img, *axis, "--emit-scenes", em, "--max-steps", str(a.max_steps), *extra,
                   check=False)
            open(os.path.join(os.path.dirname(em), os.path.basename(em) + ".emit.log"), "w").write(p.stdout + p.stderr)
            print(f"{name} {os.path.basename(em)}: emit exit {p.returncode}\n{p.stdout[-1200:]}{p.stderr[-600:]}", flush=True)
            if p.returncode != 0:
                if os.path.basename(em) == "default" and not a.per_axis:  # per axis instead
                    open(os.path.join(os.path.dirname(em), "default.refused"), "w").write(p.stderr)
                    return emit_stage(a)
                open(em + ".refused", "w").write(p.stderr)
                continue
        est = next((float(l.split()[1]) for l in open(os.path.join(em, "campaign.txt"))
                    if l.startswith("particles_estimate:")), 0.0)
        if a.max_particles and est > a.max_particles:
            open(em + ".skipped", "w").write(
                f"not run: about {est:.3g} particles per run at the default resolution, more than this "
                f"validation's --max-particles {a.max_particles:.3g} (see {os.path.basename(em)}.emit.log "
                f"for the time estimate)\n")
            print(f"{name} {os.path.basename(em)}: skipped ({est:.3g} particles per run)")
            continue
        for line in open(os.path.join(em, "campaign.txt")):
            if line.startswith("run: "):
                rd = line.split(maxsplit=3)[3].strip()
                portable(os.path.join(rd, "scene.yaml"), a.work)
                runs.append(os.path.relpath(rd, a.work))
    open(os.path.join(a.work, "runs.txt"), "w").write("".join(r + "\n" for r in runs))
    print(f"{len(runs)} runs in {a.work}/runs.txt")


def device_stage(a):
    """Every run of runs.txt that has no summary yet, JOBS at once; prints one line per run."""
    runs = [r.strip() for r in open(os.path.join(a.work, "runs.txt")) if r.strip()]
    todo = [r for r in runs if not os.path.exists(os.path.join(a.work, r, "summary.json"))]
    t_all = time.time()

    def one(r):
        d = os.path.join(a.work, r)
        t0 = time.time()
        if a.time_box and t0 - t_all > a.time_box:
            return r, "not started (time box)", 0.0
        with open(os.path.join(d, "run.log"), "w") as log:
            rc = subprocess.run([MDPORE, "run", "scene.yaml"], cwd=d, stdout=log, stderr=subprocess.STDOUT).returncode
        return r, rc, time.time() - t0

    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as ex:
        for r, rc, dt in ex.map(one, todo):
            print(f"{r}: exit {rc}, {dt:.1f} s", flush=True)
    print(f"{len(todo)} runs in {time.time() - t_all:.0f} s, {a.jobs} at once")


def run_stats(em):
    """Per run of a campaign folder: core density, fill, penetrations, seconds, particles, steps."""
    out = []
    for line in open(os.path.join(em, "campaign.txt")):
        if not line.startswith("run: "):
            continue
        _, ax, g, rd = line.split(maxsplit=3)
        s = os.path.join(rd.strip(), "summary.json")
        if not os.path.exists(s):
            continue
        j = json.load(open(s))
        out.append({"axis": ax, "g": float(g), "summary": j, "dir": os.path.basename(rd.strip().rstrip("/"))})
    return out


def find(j, *keys):
    for k in keys:
        if not isinstance(j, dict) or k not in j:
            return None
        j = j[k]
    return j


def foam_reference(d, ax, refine):
    ks = {}
    for r in refine:
        p = os.path.join(d, f"foam_{ax}_r{r}.json")
        if os.path.exists(p):
            j = json.load(open(p))
            if "permeability_voxel2" in j:
                ks[r] = (j["permeability_voxel2"], j.get("wall_s"))
    if 1 in ks and 2 in ks:  # cell-centred finite volumes on voxel walls: error ~ 1/N^2 (a slit's
        return (4 * ks[2][0] - ks[1][0]) / 3, ks  # k = (h^2/12)(1 + 2/N^2), docs/foam.md): Richardson
    if ks and len(refine) == 1:
        return ks[max(ks)][0], ks
    return None, ks  # the extrapolation needs both meshes: no reference from the voxel mesh alone


def mesh_factor(a):
    """The mean k_ref / k_r1 over the crops and axes of each rock where both foam meshes finished: the
    voxel mesh's error, used (and marked "est.") where the 2x mesh did not finish."""
    ratios = {}
    for rock, size, name in crops(a):
        for ax in AXES:
            ref, ks = foam_reference(os.path.join(a.work, name), ax, a.foam_refine)
            if ref and 1 in ks and 2 in ks:
                ratios.setdefault(rock, []).append(ref / ks[1][0])
    return {rock: sum(v) / len(v) for rock, v in ratios.items()}


def report_stage(a):
    os.makedirs(RESULTS, exist_ok=True)
    rows, failures = [], []
    factors = mesh_factor(a)
    for name, em, extra in campaigns(a):
        if os.path.exists(em + ".refused") or os.path.exists(em + ".skipped"):
            f = em + (".refused" if os.path.exists(em + ".refused") else ".skipped")
            why = open(f).read().strip().splitlines()[-1].replace(a.work + "/", "")[:400]
            if f.endswith(".refused"):
                why = "refused: " + why
            rows.append({"crop": name, "campaign": os.path.basename(em), "axis": em[-1] if "_" in os.path.basename(em) else "all",
                         "rc_per_voxel": None, "boundary": None, "k_mdpd_rc2": None, "k_mdpd_rc2_err": None,
                         "darcy_range": why, "k_mdpd_voxel2": None, "k_foam_r1": None, "k_foam_r2": None,
                         "k_foam_ref": None, "k_foam_ref_estimated": False, "ratio": None, "max_core_density_dev": None, "penetrations": 0,
                         "run_seconds": None, "particles": 0, "backend": None, "runs": 0,
                         "max_core_density_dev_all": None, "left_out": 0})
            continue
        if not os.path.exists(os.path.join(em, "campaign.txt")):
            continue
        p = sh("permeability", "--collect", em, check=False)
        open(em + ".report.txt", "w").write(p.stdout + p.stderr)
        pj = os.path.join(em, "permeability.json")
        if not os.path.exists(pj):
            failures.append(f"{name} {os.path.basename(em)}: no permeability.json (exit {p.returncode})")
            continue
        j = json.load(open(pj))
        rcv = j["rc_per_voxel"]
        d = os.path.dirname(em)
        stats = run_stats(em)
        for ax, axr in j["axes"].items():
            kr = axr.get("k_rc2") if axr.get("k_defined") else None
            kr_err = axr.get("k_rc2_err") if axr.get("k_defined") else None
            accepted = "yes" if axr.get("k_defined") else "no: " + str(axr.get("k_undefined_why"))[:160]
            k_vox = kr / rcv ** 2 if kr is not None else None
            ref, ks = foam_reference(d, ax, a.foam_refine)
            ref_estimated = False
            rock = next(r for r, sz, nm in crops(a) if nm == name)
            if ref is None and 1 in ks and rock in factors:
                ref, ref_estimated = ks[1][0] * factors[rock], True
            st = [s for s in stats if s["axis"] == ax]
            left = {os.path.basename(r["run"].rstrip("/")) for r in axr.get("left_out", [])}
            kept = [s for s in st if s["dir"] not in left]
            fill = j.get("fluid_density", 6.2)
            dens = [find(s["summary"], "pore_core_density", "mean") for s in kept]
            dens_dev = max((abs(x / fill - 1) for x in dens if x), default=None)
            dens_all = [find(s["summary"], "pore_core_density", "mean") for s in st]
            dens_dev_all = max((abs(x / fill - 1) for x in dens_all if x), default=None)
            pen = sum(find(s["summary"], "penetrations", "samples_with_penetration") or 0 for s in st)
            secs = sum(find(s["summary"], "timing", "total_seconds") or 0 for s in st)
            parts = max((find(s["summary"], "particles") or 0 for s in st), default=0)
            backend = st[0]["summary"].get("backend") if st else None
            ratio = k_vox / ref if (k_vox and ref) else None
            if not st:
                accepted = "not run"
            rows.append({"crop": name, "campaign": os.path.basename(em), "axis": ax, "rc_per_voxel": rcv,
                         "boundary": find(j, "boundary", ax, "faces"), "k_mdpd_rc2": kr, "k_mdpd_rc2_err": kr_err,
                         "darcy_range": accepted, "k_mdpd_voxel2": k_vox,
                         "k_foam_r1": ks.get(1, (None,))[0], "k_foam_r2": ks.get(2, (None,))[0], "k_foam_ref": ref,
                         "k_foam_ref_estimated": ref_estimated,
                         "ratio": ratio, "max_core_density_dev": dens_dev, "max_core_density_dev_all": dens_dev_all,
                         "left_out": len(left), "penetrations": pen, "run_seconds": secs,
                         "particles": parts, "backend": backend,
                         "runs": len(st)})
            if os.path.basename(em).startswith("default") and st:
                if ratio is None or abs(ratio - 1) > 0.10:
                    failures.append(f"{name} {ax}: k_mDPD / k_foam = {ratio}")
                if dens_dev is not None and dens_dev > 0.03:
                    failures.append(f"{name} {ax}: a kept run's pore-core density is {dens_dev:.1%} off the fill")
            if pen:
                failures.append(f"{name} {os.path.basename(em)} {ax}: {pen} penetrations")
    write_table(rows, failures)
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


def fmt(x, f="{:.4g}"):
    return "-" if x is None else f.format(x)


def write_table(rows, failures):
    keys = list(rows[0].keys()) if rows else []
    with open(os.path.join(RESULTS, "rocks.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    lines = ["| crop | campaign | axis | rc/voxel | boundary | k mDPD (rc^2) | Darcy range | k mDPD (voxel^2) | "
             "foam r1 | foam r2 | foam ref | mDPD/foam | core density off the fill (kept runs; all) | runs left out | penetrations | particles | run s (backend) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['crop']} | {r['campaign']} | {r['axis']} | {fmt(r['rc_per_voxel'])} | {r['boundary']} | "
                     f"{fmt(r['k_mdpd_rc2'])} +- {fmt(r['k_mdpd_rc2_err'], '{:.2g}')} | {r['darcy_range']} | "
                     f"{fmt(r['k_mdpd_voxel2'])} | {fmt(r['k_foam_r1'])} | {fmt(r['k_foam_r2'])} | "
                     f"{fmt(r['k_foam_ref'])}{' (est.)' if r.get('k_foam_ref_estimated') else ''} | "
                     f"{fmt(r['ratio'], '{:.3f}')} | "
                     f"{fmt(r['max_core_density_dev'], '{:.1%}')}; {fmt(r.get('max_core_density_dev_all'), '{:.1%}')} | "
                     f"{r.get('left_out', 0)} of {r['runs']} | {r['penetrations']} | {r['particles']} | {fmt(r['run_seconds'], '{:.0f}')} ({r['backend']}) |")
    lines += ["", "foam ref: (4 k_r2 - k_r1) / 3; est.: k_r1 times the rock's mean k_ref / k_r1 where both "
              "meshes finished (the 2x mesh did not finish here)",
              "", f"{len(failures)} checks failed" + ("".join(f"\n- {f}" for f in failures))]
    open(os.path.join(RESULTS, "rocks.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("no matplotlib: no PNG")
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for r in rows:
        if r["ratio"] is None:
            continue
        m = "o" if r["campaign"] == "default" else "s"
        ax.errorbar(r["rc_per_voxel"], r["ratio"],
                    yerr=(r["k_mdpd_rc2_err"] or 0) / r["k_mdpd_rc2"] * r["ratio"] if r["k_mdpd_rc2"] else 0,
                    fmt=m, label=f"{r['crop']} {r['axis']} {r['campaign']}")
    ax.axhspan(0.9, 1.1, color="0.9")
    ax.axhline(1, color="k", lw=0.5)
    ax.set_xlabel("rc per voxel")
    ax.set_ylabel("k mDPD / k foam (same voxels, mirror faces, periodic sides)")
    ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(RESULTS, "rocks.png"), dpi=120)


def quick_stage(a):
    """CI-sized: cases/rock/berea16.raw along x, the campaign's defaults, foam like for like."""
    img = os.path.join(ROOT, "cases", "rock", "berea16.raw")
    failures = []
    fj = {}
    for r in (1, 2):
        out = os.path.join(a.work, f"foam_x_r{r}.json")
        if not os.path.exists(out):
            p = sh("foam", img, "--axis", "x", "--boundary", "mirror", "--sides", "periodic", "--refine", str(r),
                   check=False)
            if p.returncode == 4:
                print("skipped: OpenFOAM not found")
                return 77
            if p.returncode:
                sys.exit(f"mdpore foam: exit {p.returncode}: {p.stderr[-1500:]}")
            open(out, "w").write(p.stdout)
        fj[r] = json.load(open(out))["permeability_voxel2"]
    k_foam = (4 * fj[2] - fj[1]) / 3
    em = os.path.join(a.work, "campaign")
    p = subprocess.run([MDPORE, "permeability", img, "--axis", "x", "--np", str(a.np), "--mpiexec",
                        "mpiexec --oversubscribe", "--workdir", em], capture_output=True, text=True)
    print(p.stdout[-2500:], p.stderr[-2500:])
    if p.returncode not in (0, 3):
        sys.exit(f"mdpore permeability: exit {p.returncode}")
    j = json.load(open(os.path.join(em, "permeability.json")))
    ax, rcv = j["axes"]["x"], j["rc_per_voxel"]

    def check(ok, what):
        print(("ok   " if ok else "FAIL ") + what, flush=True)
        if not ok:
            failures.append(what)
    check(j["boundary"]["x"]["faces"] == "mirror", f"boundary auto mirrored the crop ({j['boundary']['x']})")
    throat = j["resolution"]["critical_throat_voxels"][0] * rcv
    check(throat >= 4 - 1e-9, f"the critical throat is {throat:.3g} rc at the chosen {rcv:g} rc per voxel (>= 4)")
    pen = sum(find(s["summary"], "penetrations", "samples_with_penetration") or 0 for s in run_stats(em))
    check(pen == 0, f"no particle inside a wall ({pen} samples with penetrations)")
    check(bool(ax.get("k_defined")), f"k is defined ({ax.get('k_undefined_why')})")
    if ax.get("k_defined"):
        k_vox = ax["k_rc2"] / rcv ** 2
        ratio = k_vox / k_foam
        print(f"k_mDPD = {ax['k_rc2']:.5g} +- {ax['k_rc2_err']:.2g} rc^2 = {k_vox:.5g} voxel^2; foam (mirror faces, "
              f"periodic sides) {fj[1]:.5g} / {fj[2]:.5g} voxel^2 at 1 / 2 cells per voxel, continuum {k_foam:.5g}")
        check(abs(ratio - 1) <= 0.10, f"k_mDPD / k_foam = {ratio:.3f} within 10%")
    print(f"{len(failures)} failures")
    return 1 if failures else 0


def rev_stage(a):
    """Representative volume and anisotropy: cubes of growing size at the same corner, porosity and
    the continuum k_xx, k_yy, k_zz (foam on the voxel mesh, mirror faces, periodic sides: cheap, so
    every size) with the anisotropy ratio; the mDPD k of the campaigns where they define one."""
    os.makedirs(RESULTS, exist_ok=True)
    rows = []
    for rock in a.rock:
        base, n = ROCK_FILES[rock]
        for size in a.rev_sizes:
            name = f"{rock}_{size}"
            d, img = make_crop(a, rock, size, name)
            info = json.loads(sh("image", "info", img, "--json").stdout)
            row = {"rock": rock, "size": size, "porosity": info.get("porosity")}
            for ax in AXES:
                out = os.path.join(d, f"foam_{ax}_r1.json")
                if not os.path.exists(out):
                    p = sh("foam", img, "--axis", ax, "--boundary", "mirror", "--sides", "periodic", check=False)
                    open(out, "w").write(p.stdout if p.returncode == 0 else json.dumps({"exit": p.returncode}))
                j = json.load(open(out))
                row[f"k_{ax}{ax}_foam"] = j.get("permeability_voxel2")
                pj = os.path.join(d, f"default_{ax}", "permeability.json")
                m = json.load(open(pj))["axes"].get(ax, {}) if os.path.exists(pj) else {}
                row[f"k_{ax}{ax}_mdpd"] = m["k_rc2"] / json.load(open(pj))["rc_per_voxel"] ** 2 if m.get("k_defined") else None
            ks = [row[f"k_{ax}{ax}_foam"] for ax in AXES if row[f"k_{ax}{ax}_foam"]]
            row["anisotropy_foam"] = max(ks) / min(ks) if len(ks) == 3 and min(ks) > 0 else None
            rows.append(row)
            print(row, flush=True)
    keys = list(rows[0].keys())
    with open(os.path.join(RESULTS, "rev.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    lines = ["| rock | size (voxels) | porosity | k_xx foam | k_yy foam | k_zz foam | k_max/k_min | k_xx mDPD | k_yy mDPD | k_zz mDPD |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['rock']} | {r['size']} | {fmt(r['porosity'])} | " +
                     " | ".join(fmt(r[f'k_{ax}{ax}_foam']) for ax in AXES) + f" | {fmt(r['anisotropy_foam'], '{:.2f}')} | " +
                     " | ".join(fmt(r[f'k_{ax}{ax}_mdpd']) for ax in AXES) + " |")
    lines.append("\nk in voxel^2 (1 voxel^2 = (voxel size)^2); foam on the voxel mesh (one cell per voxel: reads high in "
                 "throats a few voxels wide, see rocks.md), mirror faces, periodic sides; cubes at the corner (offset, offset, offset).")
    open(os.path.join(RESULTS, "rev.md"), "w").write("\n".join(lines) + "\n")
    print("\n".join(lines))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return 0
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.8))
    for rock in a.rock:
        rr = [r for r in rows if r["rock"] == rock]
        a1.plot([r["size"] for r in rr], [r["porosity"] for r in rr], "o-", label=rock)
        for ax, m in zip(AXES, "os^"):
            a2.plot([r["size"] for r in rr], [r[f"k_{ax}{ax}_foam"] for r in rr], m + "-", label=f"{rock} k_{ax}{ax} foam")
            a2.plot([r["size"] for r in rr], [r[f"k_{ax}{ax}_mdpd"] for r in rr], m, mfc="none", ms=10, label=f"{rock} k_{ax}{ax} mDPD")
    a1.set_xlabel("cube edge (voxels)")
    a1.set_ylabel("porosity")
    a2.set_xlabel("cube edge (voxels)")
    a2.set_ylabel("k (voxel^2)")
    a2.set_yscale("log")
    a1.legend(fontsize=7)
    a2.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(os.path.join(RESULTS, "rev.png"), dpi=120)
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("stage", choices=["foam", "emit", "device", "report", "quick", "rev"])
    ap.add_argument("--rev-sizes", type=int, nargs="+", default=[16, 24, 32, 48, 64, 96])
    ap.add_argument("work")
    ap.add_argument("--rock", nargs="+", default=["berea"], choices=sorted(ROCK_FILES))
    ap.add_argument("--sizes", type=int, nargs="+", default=[48, 64])
    ap.add_argument("--offset", type=int, default=100, help="the crops' corner, voxels on each axis")
    ap.add_argument("--crops", nargs="+", default=[],
                    help="ROCK:SIZE[:OFFSET] per crop, OFFSET one number or X,Y,Z (instead of every --rock at every --sizes)")
    ap.add_argument("--foam-refine", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--refine-rc", type=float, nargs="*", default=[], help="extra rc per voxel of the smallest crop")
    ap.add_argument("--max-steps", type=int, default=20000)
    ap.add_argument("--max-particles", type=float, default=0,
                    help="emit: leave out (reported as not run) a campaign whose runs hold more particles")
    ap.add_argument("--per-axis", action="store_true",
                    help="one default campaign per axis (mdpore permeability --axis A: each axis at its own resolution)")
    ap.add_argument("--campaign-args", default="", help="extra options of the default campaigns")
    ap.add_argument("--np", type=int, default=2, help="foam ranks")
    ap.add_argument("--jobs", type=int, default=4, help="device: runs at once")
    ap.add_argument("--time-box", type=float, default=0, help="device: start no run after this many seconds")
    a = ap.parse_args()
    a.work = os.path.abspath(a.work)
    os.makedirs(a.work, exist_ok=True)
    stages = {"foam": foam_stage, "emit": emit_stage, "device": device_stage, "report": report_stage,
              "quick": quick_stage, "rev": rev_stage}
    return stages[a.stage](a) or 0


if __name__ == "__main__":
    sys.exit(main())
