"""Shared helpers of the walls validations (validation/walls/: slit_poiseuille.py, tube_duct.py,
contact_angle.py): the repository's reference viscosity, the reverse-Poiseuille bulk viscosity at a
given density, images written from numpy (raw + sidecar, docs/images.md), the geometry scene of an
image, runs that can be reused, weighted least squares and error propagation.

Run with /usr/bin/python3 (Debian numpy, matplotlib, yaml, h5py).
"""
import csv
import json
import os
import sys

import numpy as np
import yaml

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "engine"))
import mdval  # noqa: E402

RC_PER_VOXEL = 0.5
MU_FALLBACK = (5.41, 0.007)  # validation/results/engine/viscosity (mdpd row), README closing notes
BOUNDARIES = ("bounce_back", "wall_boundary", "wall_boundary+bounce_back")


def mu_reference():
    """(mu, err, source) of the mDPD A = -40 viscosity measured by validation/engine/viscosity.py."""
    path = os.path.join(mdval.ROOT, "validation", "results", "engine", "viscosity", "viscosity.csv")
    try:
        with open(path) as f:
            for row in csv.DictReader(f):
                if row["case"] == "mdpd":
                    return float(row["eta"]), float(row["err"]), os.path.relpath(path, mdval.ROOT)
    except (OSError, KeyError, ValueError):
        pass
    return MU_FALLBACK[0], MU_FALLBACK[1], "fallback value 5.41 +- 0.007 (results file not found)"


def slit_slip_length(default=-0.2):
    """(b, spread, source): the slip length of the slit validation (fit D, the core parabola, mean of
    both walls over every width in validation/results/walls/slit_poiseuille.csv), else `default`."""
    path = os.path.join(mdval.ROOT, "validation", "results", "walls", "slit_poiseuille.csv")
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
        b = [float(r[k]) for r in rows for k in ("b_lo_D", "b_hi_D")]
        if b:
            return float(np.mean(b)), float(np.std(b)), (
                f"{os.path.relpath(path, mdval.ROOT)} (fit D, {len(b)} walls, h = "
                f"{', '.join(r['h'] for r in rows)})")
    except (OSError, KeyError, ValueError):
        pass
    return default, 0.0, f"fallback value {default} (slit results not found)"


def write_raw_image(path, labels, labelmap="pore=0;inorganic=1", voxel_size=None):
    """labels[ix, iy, iz] (uint8) as IMAGE.raw (x fastest) + IMAGE.raw.hdr (docs/images.md)."""
    lab = np.asarray(labels, dtype=np.uint8)
    nx, ny, nz = lab.shape
    with open(path, "wb") as f:
        f.write(np.ascontiguousarray(lab.transpose(2, 1, 0)).tobytes())
    with open(path + ".hdr", "w") as f:
        f.write(f"# mdpore raw image sidecar (validation/walls/common.py)\ndims: {nx} {ny} {nz}\n"
                f"type: uint8\nbyte_order: little\naxis_order: xyz\nheader_bytes: 0\nlabels: {labelmap}\n")
        if voxel_size:
            f.write(f"voxel_size: {voxel_size}\n")
    return path


def boundary_effect(boundary):
    """The `effects:` entry of the wall boundary named on the command line (its defaults)."""
    if boundary not in BOUNDARIES:
        raise ValueError(f"unknown boundary {boundary!r} (expected one of {', '.join(BOUNDARIES)})")
    return {name: {} for name in boundary.split("+")}


def image_scene(name, box, image, patches, *, steps, seed, patch_seed, flow_axis="x", a_wall=-40.0,
                gamma_wall=None, wall_density=None, g=None, boundary="bounce_back", fluid_region=None, thermo_every=100, profile=None,
                snapshot=None, rc_per_voxel=RC_PER_VOXEL, temperature=1.0):
    """A scene with `geometry:` (docs/scene-format.md): liquid mDPD A = -40, B = 25, rd = 0.75,
    gamma = 4.5, kT = 1, dt = 0.01, fluid-wall A = a_wall (and gamma = gamma_wall when given), one frozen wall species `wall` for the
    inorganic voxels; body force g (a 3-vector, or None) on the liquid; the boundary effect."""
    eff = {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {}}
    if g is not None:
        eff["body_force"] = {"liquid": [float(v) for v in g]}
    eff.update(boundary_effect(boundary))
    geo = {"image": image, "rc_per_voxel": rc_per_voxel, "flow_axis": flow_axis,
           "species": {"fluid": "liquid", "inorganic": "wall"},
           "patches": {"file": patches, "seed": int(patch_seed)}}
    if wall_density is not None:
        geo["wall_density"] = float(wall_density)
    if fluid_region:
        geo["fluid_region"] = {"lo": [float(v) for v in fluid_region[0]],
                               "hi": [float(v) for v in fluid_region[1]]}
    scene = {
        "name": name,
        "box": {"lo": [0.0, 0.0, 0.0], "hi": [float(v) for v in box], "periodic": [True, True, True]},
        "species": [{"name": "liquid", "mass": 1.0}, {"name": "wall", "mass": 1.0, "frozen": True}],
        "pairs": {"default": {"A": -40.0, "B": 25.0, "gamma": 4.5, "rc": 1.0, "rd": 0.75},
                  "liquid-wall": dict({"A": float(a_wall)},
                                      **({} if gamma_wall is None else {"gamma": float(gamma_wall)}))},
        "density_kernel": "warren",
        "kT": 1.0,
        "effects": eff,
        "geometry": geo,
        "initial": {"temperature": float(temperature)},
        "run": {"dt": 0.01, "steps": int(steps), "seed": int(seed)},
        "output": {"thermo": {"every": int(thermo_every), "file": "thermo.csv"},
                   "summary": "summary.json", "progress": False},
    }
    if profile:
        scene["output"]["profile"] = dict(profile, file="profile.csv")
    if snapshot:
        scene["output"]["snapshot"] = {"every": int(snapshot), "file": "snap"}
    return scene


def run_or_reuse(scene, wd, np_ranks, reuse):
    """mdval.run unless --reuse finds the same scene already run there; returns the wall seconds."""
    if reuse and os.path.exists(os.path.join(wd, "summary.json")) and os.path.exists(os.path.join(wd, "scene.yaml")):
        with open(os.path.join(wd, "scene.yaml")) as f:
            if yaml.safe_load(f) == yaml.safe_load(yaml.safe_dump(scene, sort_keys=False)):
                print(f"  reusing {wd}", flush=True)
                try:
                    return float(open(os.path.join(wd, "wall_s.txt")).read())
                except (OSError, ValueError):
                    return float(json.load(open(os.path.join(wd, "summary.json")))["timing"]["total_seconds"])
    wall = mdval.run(scene, wd, np_ranks, timeout=6 * 3600)
    with open(os.path.join(wd, "wall_s.txt"), "w") as f:
        f.write(f"{wall:.3f}\n")
    return wall


_BULK = {}


def bulk_viscosity(workdir, rho, length, depth, steps, np_ranks, reuse, seed):
    """Reverse-Poiseuille viscosity (validation/engine/viscosity.py's fit) of bulk mDPD A = -40 at
    density rho in a periodic L x 12 x D box: (mu, err, chi2, wall seconds); once per density."""
    key = (rho, length, depth, steps, seed)
    if key not in _BULK:
        _BULK[key] = _bulk_viscosity(workdir, rho, length, depth, steps, np_ranks, reuse, seed)
    return _BULK[key]


def _bulk_viscosity(workdir, rho, length, depth, steps, np_ranks, reuse, seed):
    from viscosity import fit_viscosity  # validation/engine/viscosity.py
    Ly, g, equil = 12.0, 0.05, 5000
    box = [length, Ly, depth]
    eff = {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {},
           "body_force": {"liquid": [g, 0.0, 0.0], "reverse_along": "y"}}
    scene = mdval.mdpd_scene(f"bulk_rho{rho:g}", box, [mdval.fill_box(box, rho)], steps=equil + steps,
                             effects=eff, seed=seed, thermo_every=100,
                             profile={"axis": "y", "bins": 24, "every": 10, "start": equil})
    wd = os.path.join(workdir, f"bulk_rho{rho:g}")
    wall = run_or_reuse(scene, wd, np_ranks, reuse)
    prof = mdval.read_table(os.path.join(wd, "profile.csv"))
    n = float(np.mean(prof["density"]))
    mu, dmu, chi2, _ = fit_viscosity(prof["y"], prof["vx"], prof["vx_err"], n, g, Ly)
    return float(mu), float(dmu), float(chi2), wall


def wls(X, y, err):
    """Weighted linear least squares: params, covariance scaled by max(1, chi2/dof), chi2/dof, model."""
    w = 1.0 / np.maximum(err, 1e-12) ** 2
    A = X * np.sqrt(w)[:, None]
    b = y * np.sqrt(w)
    p, *_ = np.linalg.lstsq(A, b, rcond=None)
    model = X @ p
    dof = max(1, len(y) - X.shape[1])
    chi2 = float(np.sum(w * (y - model) ** 2) / dof)
    cov = np.linalg.inv(A.T @ A) * max(1.0, chi2)
    return p, cov, chi2, model


def propagate(f, p, cov, eps=1e-7):
    """Value and standard errors of the vector function f(p) (numerical Jacobian)."""
    f0 = np.asarray(f(p), dtype=float)
    J = np.zeros((len(f0), len(p)))
    for k in range(len(p)):
        dp = np.array(p, dtype=float)
        h = eps * max(1.0, abs(dp[k]))
        dp[k] += h
        J[:, k] = (np.asarray(f(dp)) - f0) / h
    return f0, np.sqrt(np.maximum(np.diag(J @ cov @ J.T), 0.0))


def pm(v, e, digits=3):
    return f"{v:.{digits}f} ± {e:.{digits}f}"


def read_snapshots(wd, start_step, species=0):
    """(steps, list of (positions, velocities)) of the species in the HDF5 snapshots snap_*.h5 of a
    run folder from step start_step on, and the box (lo, hi)."""
    import glob
    import h5py
    out, steps, box = [], [], None
    for path in sorted(glob.glob(os.path.join(wd, "snap_*.h5"))):
        with h5py.File(path, "r") as f:
            step = int(f.attrs["step"])
            if step < start_step:
                continue
            p = f["particles"]
            sel = p["species"][:] == species
            out.append((p["position"][:][sel], p["velocity"][:][sel]))
            steps.append(step)
            box = (np.array(f.attrs["box_lo"]), np.array(f.attrs["box_hi"]))
    return steps, out, box


def penetrations(summary):
    pen = summary.get("penetrations", {})
    return (int(pen.get("samples_with_penetration", -1)), int(pen.get("max_particles", -1)),
            int(pen.get("samples", 0)))
