#!/usr/bin/env python3
"""`mdpore darcy --upscale` against OPM's upscale_perm (Debian package libopm-upscaling-bin).

The same block grids go to both tools: to mdpore as an HDF5 permeability dataset (unit attribute
"mD", axis_order "zyx") and to upscale_perm as an Eclipse GRDECL file (PERMX = PERMY = PERMZ in mD).
Both compute the tensor with fixed, linear and periodic boundary conditions. mdpore uses two-point
fluxes with harmonic face means, upscale_perm a mimetic finite-difference scheme; the script reports
how far apart they are:

  layered     layers along z (and along x): fixed and periodic diagonals are the arithmetic and
              harmonic means, exactly, for both tools (pass: mdpore within 1e-8, OPM within its
              six printed digits, 2e-5);
  smooth      a smooth periodic log-permeability field (a few Fourier modes, sigma = 1) sampled
              at n = 8, 16, 32 (64 in the full run): the gap must shrink with refinement (pass: the
              finest gap below the coarsest, fixed and periodic);
  lognormal   uncorrelated lognormal blocks (sigma = 1): the gap is reported;
  checker     a 100:1 checkerboard of 4^3 cubes (quick: 3^3) refined to n = 8, 16, 32, and one
              with a block per cube (n = 16): the gaps are reported;
  timing      both tools on a 100 x 100 x 50 lognormal grid, all three families, wall clock.

Writes results.md, results.csv, results.json and upscale_convergence.png to validation/upscale/
results/ (or --outdir); the grids and the two tools' files go to a temporary folder (--keep keeps
it). Exits 77 (skip) with a message when upscale_perm is not installed.
Usage: validate_upscale.py [--quick] [--mdpore PATH] [--upscale-perm PATH] [--outdir DIR]"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

FAMILIES = ("fixed", "linear", "periodic")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def write_grdecl(path, k_md, size):
    """Corner-point grid of a box: k_md shape (nz, ny, nx), x fastest; z is depth (down)."""
    nz, ny, nx = k_md.shape
    x = np.linspace(0.0, size[0], nx + 1)
    y = np.linspace(0.0, size[1], ny + 1)
    z = np.linspace(0.0, size[2], nz + 1)
    with open(path, "w") as f:
        f.write("SPECGRID\n%d %d %d 1 F /\n\nCOORD\n" % (nx, ny, nz))
        xx, yy = np.meshgrid(x, y)  # (ny+1, nx+1), x fastest
        coord = np.column_stack([xx.ravel(), yy.ravel(), np.zeros(xx.size), xx.ravel(),
                                 yy.ravel(), np.full(xx.size, size[2])])
        np.savetxt(f, coord, fmt="%.10g")
        f.write("/\n\nZCORN\n")
        zc = np.repeat(np.column_stack([z[:-1], z[1:]]).ravel(), 4 * nx * ny)
        np.savetxt(f, zc.reshape(-1, 8 if zc.size % 8 == 0 else 4), fmt="%.10g")
        f.write("/\n")
        flat = k_md.reshape(-1)
        pad = (-flat.size) % 6
        rows = np.concatenate([flat, np.full(pad, np.nan)]).reshape(-1, 6)
        for name in ("PERMX", "PERMY", "PERMZ"):
            f.write("\n%s\n" % name)
            body = "\n".join(" ".join("%.12g" % v for v in r if np.isfinite(v)) for r in rows)
            f.write(body + "\n/\n")


def run_opm(exe, grdecl):
    t0 = time.time()
    r = subprocess.run([exe, "-bc", "flp", grdecl], capture_output=True, text=True)
    wall = time.time() - t0
    if r.returncode != 0:
        raise RuntimeError("upscale_perm failed on %s:\n%s%s" % (grdecl, r.stdout, r.stderr))
    out, tens = r.stdout.splitlines(), {}
    for fam in FAMILIES:
        head = [i for i, l in enumerate(out)
                if l.startswith("# Upscaled permeability for %s boundary" % fam)]
        if not head:
            raise RuntimeError("no %s tensor in the upscale_perm output of %s" % (fam, grdecl))
        rows = [l for l in out[head[-1] + 1:] if l.strip() and not l.startswith("#")][:3]
        tens[fam] = np.array([[float(v) for v in l.split()] for l in rows])
    return tens, wall


def run_mdpore(exe, work, name, k_md, size):
    import h5py
    with h5py.File(os.path.join(work, name + ".h5"), "w") as h:
        d = h.create_dataset("k", data=k_md)
        d.attrs["unit"] = "mD"
        d.attrs["axis_order"] = "zyx"
    nz, ny, nx = k_md.shape
    cfg = ("units: SI\ngrid: {cells: [%d, %d, %d], size: [%.10g m, %.10g m, %.10g m]}\n"
           "fluid: {viscosity: 1 cP}\nlaws:\n  hdf5: {file: %s.h5, dataset: k}\n"
           "upscale: {conditions: [fixed, linear, periodic]}\nsolver: {rtol: 1.0e-10}\n"
           "output: {json: %s.json}\n" % (nx, ny, nz, size[0], size[1], size[2], name, name))
    with open(os.path.join(work, name + ".yaml"), "w") as f:
        f.write(cfg)
    t0 = time.time()
    r = subprocess.run([exe, "darcy", name + ".yaml", "--quiet"], cwd=work, capture_output=True,
                       text=True)
    wall = time.time() - t0
    if r.returncode != 0:
        raise RuntimeError("mdpore darcy failed on %s:\n%s%s" % (name, r.stdout, r.stderr))
    res = json.load(open(os.path.join(work, name + ".json")))
    tens, conv = {}, True
    for fam in FAMILIES:
        e = res["permeability"][fam]
        t = np.array([np.nan if v is None else v for v in e["tensor_mD"]]).reshape(3, 3)
        tens[fam] = t
        conv &= bool(e["converged"])
    return tens, wall, conv


def smooth_field(n, seed=7):
    """Periodic smooth log-k on the unit cube, sampled at the centres of n^3 cells."""
    rng = np.random.default_rng(seed)
    c = (np.arange(n) + 0.5) / n
    z, y, x = np.meshgrid(c, c, c, indexing="ij")
    logk = np.zeros_like(x)
    waves = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (1, 0, 1), (0, 1, 1), (1, -1, 1),
             (2, 1, 0), (0, 2, 1), (1, 0, 2)]
    for w in waves:
        logk += np.cos(2 * np.pi * (w[0] * x + w[1] * y + w[2] * z) + rng.uniform(0, 2 * np.pi))
    logk *= 1.0 / np.sqrt(len(waves) / 2.0)  # sigma = 1
    return 100.0 * np.exp(logk)


def checker(n, squares):
    """100:1 checkerboard of squares^3 cubes, each cube n/squares blocks wide (squares = n: one
    block per cube)."""
    i = (np.indices((n, n, n)) * squares // n).sum(axis=0)
    return np.where(i % 2 == 0, 100.0, 1.0)


def layered(n, axis):
    rng = np.random.default_rng(3)
    kl = np.exp(rng.normal(0.0, 1.5, n)) * 50.0
    shape = [1, 1, 1]
    shape[2 - axis] = n  # array axes are (z, y, x)
    k = np.broadcast_to(kl.reshape(shape), (n, n, n)).copy()
    return k, kl


def rel_gap(a, b):
    """Relative gap of mdpore (a) to OPM (b) per diagonal entry, and the largest in size (signed)."""
    d = np.array([(a[i, i] - b[i, i]) / b[i, i] for i in range(3)])
    return d, float(d[np.argmax(np.abs(d))])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller grids, no 100x100x50 timing")
    ap.add_argument("--mdpore", default=os.environ.get("MDPORE",
                                                       os.path.join(ROOT, "build/bin/mdpore")))
    ap.add_argument("--upscale-perm", default=shutil.which("upscale_perm"))
    ap.add_argument("--outdir", default=os.environ.get(
        "MDPORE_VALIDATION_OUT", os.path.join(ROOT, "validation/upscale/results")))
    ap.add_argument("--keep", action="store_true", help="keep the work folder (grids, configs)")
    a = ap.parse_args()
    if not a.upscale_perm or not os.path.exists(a.upscale_perm):
        print("skipped: OPM's upscale_perm is not installed (Debian package libopm-upscaling-bin; "
              "apt-get install libopm-upscaling-bin), so there is nothing to compare with")
        sys.exit(77)
    if not os.path.exists(a.mdpore):
        print("mdpore not found at %s (build it, or pass --mdpore)" % a.mdpore)
        sys.exit(2)
    os.makedirs(a.outdir, exist_ok=True)
    work = tempfile.mkdtemp(prefix="mdpore_upscale_")
    levels = [6, 12, 24] if a.quick else [8, 16, 32, 64]
    rows, failures = [], []

    def case(name, kind, n, k, size=(100.0, 100.0, 100.0), exact=None):
        write_grdecl(os.path.join(work, name + ".grdecl"), k, size)
        opm, t_opm = run_opm(a.upscale_perm, os.path.join(work, name + ".grdecl"))
        md, t_md, conv = run_mdpore(a.mdpore, work, name, k, size)
        if not conv:
            failures.append("%s: an mdpore solve did not converge" % name)
        for fam in FAMILIES:
            d, worst = rel_gap(md[fam], opm[fam])
            diag = np.mean([opm[fam][i, i] for i in range(3)])
            off = [(i, j) for i in range(3) for j in range(3) if i != j]
            off_gap = (max(abs(md[fam][i, j] - opm[fam][i, j]) for i, j in off) / diag
                       if fam != "fixed" else 0.0)
            row = dict(case=name, kind=kind, n=n, family=fam,
                       md=[md[fam][i, i] for i in range(3)], opm=[opm[fam][i, i] for i in range(3)],
                       gap=worst, gap_xyz=d.tolist(), off_gap=off_gap, t_md=t_md, t_opm=t_opm)
            if exact is not None and fam in ("fixed", "periodic"):
                em = max(abs(md[fam][i, i] / exact[i] - 1) for i in range(3))
                eo = max(abs(opm[fam][i, i] / exact[i] - 1) for i in range(3))
                row.update(exact=list(exact), err_md=em, err_opm=eo)
                if em > 1e-8:
                    failures.append("%s %s: mdpore off the exact mean by %.2e" % (name, fam, em))
                if eo > 2e-5:
                    failures.append("%s %s: OPM off the exact mean by %.2e" % (name, fam, eo))
            rows.append(row)
            print("%-14s n=%-3d %-8s mdpore %-36s OPM %-36s max gap %+.3e%s" % (
                name, n, fam, " ".join("%.6g" % v for v in row["md"]),
                " ".join("%.6g" % v for v in row["opm"]), worst,
                ("  exact err mdpore %.1e OPM %.1e" % (row["err_md"], row["err_opm"]))
                if "err_md" in row else ""))
        return rows[-3:]

    nl = 6 if a.quick else 10
    for axis, label in ((2, "layered_z"), (0, "layered_x")):
        k, kl = layered(nl, axis)
        ar, hm = kl.mean(), 1.0 / np.mean(1.0 / kl)
        exact = [ar, ar, ar]
        exact[axis] = hm
        case(label, "layered", nl, k, exact=exact)
    smooth = {}
    for n in levels:
        smooth[n] = case("smooth_%d" % n, "smooth", n, smooth_field(n))
    for fam_i, fam in enumerate(FAMILIES):
        if fam == "linear":
            continue  # reported, not a pass criterion (the two tools' linear tensors are
            # both defined by boundary fluxes, but the side faces carry flow)
        g0, g1 = abs(smooth[levels[0]][fam_i]["gap"]), abs(smooth[levels[-1]][fam_i]["gap"])
        if not g1 < g0:
            failures.append("smooth field, %s: the gap did not shrink with refinement (%.3e at n=%d,"
                            " %.3e at n=%d)" % (fam, g0, levels[0], g1, levels[-1]))
    rng = np.random.default_rng(11)
    nr = 10 if a.quick else 16
    case("lognormal_%d" % nr, "lognormal", nr, 100.0 * np.exp(rng.normal(0.0, 1.0, (nr,) * 3)))
    # checkerboard: a fixed pattern of cubes, refined (n / squares blocks per cube), and one with a
    # block per cube (rough at the block scale)
    checks, squares = {}, levels[0] // 2
    for n in levels[:3]:
        checks[n] = case("checker%d_%d" % (squares, n), "checker", n, checker(n, squares))
    nb = levels[1]
    case("checker_blocks_%d" % nb, "checker_blocks", nb, checker(nb, nb))
    orders = {}
    for fi, fam in enumerate(FAMILIES):
        for tool in ("md", "opm"):
            k = [np.mean(smooth[n][fi][tool]) for n in levels]
            d = [abs(k[i + 1] - k[i]) for i in range(len(k) - 1)]
            orders["%s_%s" % (tool, fam)] = [float(np.log2(d[i] / d[i + 1])) if d[i + 1] > 0 else
                                             float("nan") for i in range(len(d) - 1)]
    print("smooth field, observed order of the mean diagonal (successive differences):",
          {k: ["%.2f" % v for v in o] for k, o in orders.items()})
    # timing: the 100 x 100 x 50 grid of the issue (quick: 20 x 20 x 10), all three families
    shape = (10, 20, 20) if a.quick else (50, 100, 100)
    kt = 100.0 * np.exp(np.random.default_rng(5).normal(0.0, 1.0, shape))
    tname = "timing_%dx%dx%d" % (shape[2], shape[1], shape[0])
    trows = case(tname, "timing", shape[2], kt, size=(float(shape[2]), float(shape[1]),
                                                        float(shape[0])))
    timing = dict(grid="%d x %d x %d" % (shape[2], shape[1], shape[0]),
                  mdpore_s=trows[0]["t_md"], opm_s=trows[0]["t_opm"],
                  load_average_1min=os.getloadavg()[0])
    print("timing %s (fixed + linear + periodic, wall clock incl. start-up and input): mdpore %.1f s,"
          " upscale_perm %.1f s" % (timing["grid"], timing["mdpore_s"], timing["opm_s"]))

    with open(os.path.join(a.outdir, "results.json"), "w") as f:
        json.dump(dict(rows=rows, timing=timing, failures=failures, quick=a.quick, orders=orders),
                  f, indent=1)
    with open(os.path.join(a.outdir, "results.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "n", "family", "mdpore_kxx_mD", "mdpore_kyy_mD", "mdpore_kzz_mD",
                    "opm_kxx_mD", "opm_kyy_mD", "opm_kzz_mD", "max_rel_gap", "offdiag_gap",
                    "mdpore_s", "opm_s"])
        for r in rows:
            w.writerow([r["case"], r["n"], r["family"]] + ["%.8g" % v for v in r["md"]] +
                       ["%.8g" % v for v in r["opm"]] + ["%.3e" % r["gap"], "%.3e" % r["off_gap"],
                                                         "%.2f" % r["t_md"], "%.2f" % r["t_opm"]])
    with open(os.path.join(a.outdir, "results.md"), "w") as f:
        f.write("# mdpore darcy --upscale vs OPM upscale_perm%s\n\n" % (" (quick)" if a.quick else ""))
        f.write("Diagonal entries in mD; gap = (mdpore - OPM) / OPM of the diagonal entry where it is "
                "largest in size; off-diag = "
                "max |difference| of the off-diagonal entries / mean OPM diagonal.\n\n")
        f.write("| case | n | BCs | mdpore kxx kyy kzz | OPM kxx kyy kzz | gap | off-diag |\n")
        f.write("|---|---|---|---|---|---|---|\n")
        for r in rows:
            if r["kind"] == "timing":
                continue
            f.write("| %s | %d | %s | %s | %s | %+.2e | %.1e |\n" % (
                r["case"], r["n"], r["family"], " ".join("%.6g" % v for v in r["md"]),
                " ".join("%.6g" % v for v in r["opm"]), r["gap"], r["off_gap"]))
        f.write("\nSmooth field, observed convergence order of the mean diagonal from successive "
                "refinements (n = %s):\n\n" % ", ".join(str(n) for n in levels))
        for key, o in orders.items():
            tool, fam = key.split("_")
            f.write("- %s, %s: %s\n" % ("mdpore" if tool == "md" else "OPM", fam,
                                        ", ".join("%.2f" % v for v in o)))
        f.write("\nTiming, %s blocks, all three families, wall clock with input parsing, one core "
                "each on a shared 2-core machine (1-minute load average %.1f at the end): mdpore "
                "%.1f s, upscale_perm %.1f s.\n" % (timing["grid"], timing["load_average_1min"],
                                                    timing["mdpore_s"], timing["opm_s"]))
        f.write("\n%s\n" % ("All checks passed." if not failures else
                            "FAILED:\n" + "\n".join("- " + x for x in failures)))
    plot(a.outdir, levels, smooth, checks, squares)
    print("wrote %s/results.{md,csv,json} and upscale_convergence.png" % a.outdir)
    for x in failures:
        print("FAIL:", x)
    if a.keep:
        print("grids and outputs kept in", work)
    else:
        shutil.rmtree(work, ignore_errors=True)
    sys.exit(1 if failures else 0)


def plot(outdir, levels, smooth, checks, squares):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for fi, fam in enumerate(FAMILIES):
        mk = "os^"[fi]
        ax[0].loglog(levels, [abs(smooth[n][fi]["gap"]) for n in levels], mk + "-",
                     label="smooth field, %s" % fam)
        cl = sorted(checks)
        ax[0].loglog(cl, [abs(checks[n][fi]["gap"]) for n in cl], mk + "--",
                     label="checkerboard %d^3 cubes 100:1, %s" % (squares, fam))
        ax[1].semilogx(levels, [smooth[n][fi]["md"][0] for n in levels], mk + "-",
                       label="mdpore (two-point), %s" % fam)
        ax[1].semilogx(levels, [smooth[n][fi]["opm"][0] for n in levels], mk + ":",
                       label="OPM (mimetic), %s" % fam)
    ax[0].set_xlabel("cells per axis n")
    ax[0].set_ylabel("max |k_mdpore - k_OPM| / k_OPM (diagonal)")
    ax[0].set_title("gap between the schemes")
    ax[0].legend(fontsize=7)
    ax[1].set_xlabel("cells per axis n")
    ax[1].set_ylabel("k_xx [mD], smooth field")
    ax[1].set_title("convergence with refinement")
    ax[1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "upscale_convergence.png"), dpi=110)


if __name__ == "__main__":
    main()
