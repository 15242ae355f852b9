#!/usr/bin/env python3
"""Flooding: one mDPD liquid displacing another (docs/twophase.md, "Flooding").

Parts:
  slit   a slit 6 rc wide between frozen walls (the set-up of cases/flood_slit.yaml), driven by a body
         force along it: water displacing oil with the water wetting the walls (A_water-wall -40,
         A_oil-wall -20), and oil displacing water in the same slit (a non-wetting invader). Checks:
         the two liquids' particles are conserved (N_inv_box + N_def_box in every row); before
         breakthrough the recovery equals the pore volumes injected within 0.05 + 10% (the volume
         balance of a displacement of one incompressible liquid by another); breakthrough happens,
         after 0.5 to 1.3 pore volumes; the wetting invader recovers more at breakthrough than the
         non-wetting one (which leaves wetting films behind). --quick: the wetting invader only, a
         shorter slit (the ctest).
  rock   floods of a rock crop at three water-wall attractions with the oil-wall one fixed (the
         paper's contact-angle study values A_SL = -35, -30, -20 for the water): --emit DIR writes one
         folder per case (scene.yaml and the padded image; run `mdpore run scene.yaml` in each, on a
         GPU with --backend cuda), --collect DIR reads them back: table, JSON and PNG (saturation and
         recovery against pore volumes injected, the saturation profiles).

Results: validation/results/twophase/flood_slit.{md,json,png}, flood_rock.{md,json,png} (or
$MDPORE_VALIDATION_OUT/twophase). Exit status 1 when a check fails.
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "engine"))
import mdval  # noqa: E402

PAIRS = {"A": -40.0, "B": 25.0, "gamma": 4.5, "rc": 1.0, "rd": 0.75}
RHO = 6.05


def slit_scene(name, invading, defending, *, L, sink, Lz, steps, start, g, a_ww=-40.0, a_ow=-20.0,
               every=50, seed=7):
    """The slit of cases/flood_slit.yaml: sample [0, L), sink [sink, sink + 1), box sink + 1 long."""
    Lx, h, wt = sink + 1.0, 6.0, 2.0
    Ly = h + 2 * wt
    fills = [{"species": "wall", "density": RHO, "lo": [0, 0, 0], "hi": [Lx, wt, Lz]},
             {"species": "wall", "density": RHO, "lo": [0, wt + h, 0], "hi": [Lx, Ly, Lz]},
             {"species": defending, "density": RHO, "lo": [0, wt, 0], "hi": [Lx, wt + h, Lz]}]
    return {
        "name": name,
        "box": {"lo": [0.0, 0.0, 0.0], "hi": [Lx, Ly, float(Lz)], "periodic": [True, False, True]},
        "species": [{"name": "water"}, {"name": "oil"}, {"name": "wall", "frozen": True}],
        "pairs": {"default": dict(PAIRS), "water-oil": {"A": -20.0}, "water-wall": {"A": a_ww},
                  "oil-wall": {"A": a_ow}},
        "kT": 1.0,
        "effects": {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {}, "box_walls": {},
                    "body_force": {"water": [g, 0.0, 0.0], "oil": [g, 0.0, 0.0]}},
        "initial": {"fill": fills, "temperature": 1.0},
        "run": {"dt": 0.01, "steps": int(steps), "seed": int(seed)},
        "flood": {"along": "x", "sample": [0.0, float(L)], "sink": [float(sink), float(sink) + 1.0],
                  "invading": invading, "defending": defending, "start": int(start), "every": int(every),
                  "bins": int(L), "file": "flood.csv", "profile": "flood_profile.csv"},
        "output": {"thermo": {"every": 100, "file": "thermo.csv"}, "summary": "summary.json", "progress": False},
    }


def read_flood(wd):
    t = mdval.read_table(os.path.join(wd, "flood.csv"))
    summary = json.load(open(os.path.join(wd, "summary.json")))
    return t, summary["flood"], summary


def check_flood(tag, t, fl, start, bt_range, failures):
    """The checks every flood passes; returns a result row."""
    conserved = t["N_inv_box"] + t["N_def_box"]
    if np.ptp(conserved) != 0:
        failures.append(f"{tag}: the liquids' particles changed: {conserved.min():.0f}..{conserved.max():.0f}")
    bt = fl["breakthrough"]
    after = t["step"] > start
    before = after & (t["step"] < (bt["step"] if bt else np.inf)) & (t["recovery"] > 0.05)
    dev = float(np.max(np.abs(t["recovery"][before] - t["pvi"][before]) - 0.1 * t["pvi"][before])) \
        if before.any() else float("nan")
    if not before.any():
        failures.append(f"{tag}: no census between the start and breakthrough")
    elif dev > 0.05:
        failures.append(f"{tag}: before breakthrough the recovery departs from the pore volumes injected "
                        f"by more than 0.05 + 10% (excess {dev:.3f})")
    if not bt:
        failures.append(f"{tag}: no breakthrough")
    elif not bt_range[0] <= bt["pore_volumes_injected"] <= bt_range[1]:
        failures.append(f"{tag}: breakthrough after {bt['pore_volumes_injected']:.3f} pore volumes, "
                        f"outside [{bt_range[0]}, {bt_range[1]}]")
    return {"case": tag, "particles_conserved": bool(np.ptp(conserved) == 0),
            "recovery_minus_pvi_excess": dev,
            "bt_step": bt["step"] if bt else None, "bt_pvi": bt["pore_volumes_injected"] if bt else None,
            "bt_recovery": bt["recovery"] if bt else None,
            "final_pvi": fl["pore_volumes_injected"], "final_recovery": fl["recovery"],
            "final_S_inv": fl["saturation_invading"]}


def slit(args, out, failures):
    L, sink, Lz = (8.0, 11.0, 3.0) if args.quick else (12.0, 17.0, 3.0)
    steps = 4000 if args.quick else 7000
    start = 300 if args.quick else 500
    cases = [("water_into_oil", "water", "oil")]
    if not args.quick:
        cases.append(("oil_into_water", "oil", "water"))
    rows = []
    for tag, inv, dfd in cases:
        s = slit_scene(f"flood_slit_{tag}", inv, dfd, L=L, sink=sink, Lz=Lz, steps=steps, start=start, g=args.g)
        wd = os.path.join(out, f"flood_slit_{tag}")
        if not (args.reuse and os.path.exists(os.path.join(wd, "summary.json"))):
            mdval.run(s, wd, 1)
        t, fl, _ = read_flood(wd)
        row = check_flood(tag, t, fl, start, (0.5, 1.3), failures)
        row["series"] = {k: t[k].tolist() for k in ("step", "S_inv", "recovery", "pvi")}
        rows.append(row)
    if len(rows) == 2 and rows[0]["bt_recovery"] is not None and rows[1]["bt_recovery"] is not None:
        if not rows[0]["bt_recovery"] > rows[1]["bt_recovery"]:
            failures.append("slit: the wetting invader's recovery at breakthrough is not above the "
                            "non-wetting invader's")
    report(out, "flood_slit", rows, "Flooding a slit of width 6 between frozen walls (body force g = "
           f"{args.g} on both liquids; water wets the walls: A_water-wall -40, A_oil-wall -20, A_wo -20)")
    plot(out, "flood_slit", rows)


def report(out, name, rows, title):
    header = ["case", "particles conserved", "max |RF - PVI| - 0.1 PVI before bt", "bt step", "PVI at bt",
              "RF at bt", "final PVI", "final RF", "final S_inv"]
    table = [[r["case"], str(r["particles_conserved"]), r["recovery_minus_pvi_excess"], r["bt_step"],
              r["bt_pvi"], r["bt_recovery"], r["final_pvi"], r["final_recovery"], r["final_S_inv"]]
             for r in rows]
    mdval.write_report(out, name, header, table, notes=title)
    mdval.write_json(os.path.join(out, name + ".json"), rows)


def plot(out, name, rows):
    try:
        plt = mdval.pyplot()
    except ImportError:
        return
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for r in rows:
        s = r["series"]
        ax[0].plot(s["pvi"], s["recovery"], label=r["case"])
        ax[1].plot(s["pvi"], s["S_inv"], label=r["case"])
    x = np.linspace(0, 1, 2)
    ax[0].plot(x, x, "k:", label="RF = PVI (no invader produced)")
    ax[0].set_xlabel("pore volumes injected")
    ax[0].set_ylabel("recovery factor")
    ax[1].set_xlabel("pore volumes injected")
    ax[1].set_ylabel("invading saturation of the sample")
    for a in ax:
        a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, name + ".png"), dpi=120)


# --- rock crops -------------------------------------------------------------------------------------


def rock_emit(args, root):
    exe = mdval.mdpore_binary()
    os.makedirs(root, exist_ok=True)
    image = os.path.join(root, "rock.raw")
    cmd = [exe, "image", "convert", os.path.abspath(args.image), "--pad", f"x={args.reservoir}", "-o", image]
    if args.crop:
        cmd[4:4] = ["--crop", args.crop]
    subprocess.run(cmd, check=True, env=mdval.mpi_env())
    hdr = open(image + ".hdr").read()
    dims = [int(v) for v in hdr.split("dims:")[1].split("\n")[0].split()]
    r = args.rc_per_voxel
    W = args.reservoir
    Lx = dims[0] * r
    sample = [W * r, (dims[0] - W) * r]
    sink = [Lx - r, Lx]
    for a_ww, seed in [(a, sd) for a in args.a_water_wall for sd in args.seeds]:
        tag = case_tag(a_ww, seed, args.seeds)
        wd = os.path.join(root, tag)
        os.makedirs(wd, exist_ok=True)
        s = {
            "name": f"flood_rock_{tag}",
            "box": {"lo": [0.0, 0.0, 0.0], "hi": [Lx, dims[1] * r, dims[2] * r], "periodic": [True, True, True]},
            "species": [{"name": "water"}, {"name": "oil"}, {"name": "quartz", "frozen": True}],
            "pairs": {"default": dict(PAIRS), "water-oil": {"A": -20.0}, "water-quartz": {"A": float(a_ww)},
                      "oil-quartz": {"A": float(args.a_oil_wall)}},
            "kT": 1.0,
            "effects": {"mdpd_attraction": {}, "mdpd_repulsion": {}, "dpd_thermostat": {}, "bounce_back": {},
                        "body_force": {"water": [args.g, 0.0, 0.0], "oil": [args.g, 0.0, 0.0]}},
            "geometry": {"image": "../rock.raw", "rc_per_voxel": r, "flow_axis": "x", "fluid_density": RHO,
                         "wall_density": 4, "species": {"fluid": "oil", "inorganic": "quartz"}},
            "initial": {"temperature": 1.0},
            "run": {"dt": 0.01, "steps": int(args.steps), "seed": int(seed)},
            "flood": {"along": "x", "sample": sample, "sink": sink, "invading": "water", "defending": "oil",
                      "start": int(args.start), "every": 200, "bins": 16, "file": "flood.csv",
                      "profile": "flood_profile.csv",
                      "maps": {"every": max(1, int(args.steps) // 8), "cell": 2.0, "file": "flood_maps"}},
            "output": {"thermo": {"every": 500, "file": "thermo.csv"}, "summary": "summary.json",
                       "progress": False},
        }
        import yaml
        with open(os.path.join(wd, "scene.yaml"), "w") as f:
            yaml.safe_dump(s, f, sort_keys=False)
    print(f"wrote {len(args.a_water_wall) * len(args.seeds)} scenes under {root}: run `mdpore run scene.yaml` in each folder")


def case_tag(a_ww, seed, seeds):
    """Folder of one rock flood: AwwA for the first seed, AwwA_seedS for the others."""
    return f"Aww{int(a_ww)}" if seed == seeds[0] else f"Aww{int(a_ww)}_seed{seed}"


def map_series(wd, out, name, axis_title):
    """A PNG time series of the saturation maps of one flood: the invading saturation on the
    box's middle z plane at up to five map times (HDF5 flood_maps_<step>.h5)."""
    try:
        import h5py
        plt = mdval.pyplot()
    except ImportError:
        return None
    files = sorted(f for f in os.listdir(wd) if f.startswith("flood_maps_") and f.endswith(".h5"))
    if not files:
        return None
    pick = [files[int(round(k))] for k in np.linspace(0, len(files) - 1, min(5, len(files)))]
    fig, ax = plt.subplots(1, len(pick), figsize=(3.2 * len(pick), 3.2))
    ax = np.atleast_1d(ax)
    for a, f in zip(ax, pick):
        with h5py.File(os.path.join(wd, f), "r") as h:
            sat = h["saturation"][()]
            step = int(h.attrs["step"][()]) if np.ndim(h.attrs["step"]) == 0 else int(h.attrs["step"][0])
            lo, hi = h.attrs["box_lo"], h.attrs["box_hi"]
        plane = sat[sat.shape[0] // 2]  # [y][x] at the middle z
        im = a.imshow(plane, origin="lower", extent=(lo[0], hi[0], lo[1], hi[1]), vmin=0, vmax=1, cmap="coolwarm")
        a.set_title(f"step {step}", fontsize=9)
        a.set_xlabel("x (flow)")
    ax[0].set_ylabel("y")
    fig.colorbar(im, ax=list(ax), shrink=0.8, label="invading saturation (NaN: solid)")
    fig.suptitle(axis_title, fontsize=10)
    path = os.path.join(out, name + ".png")
    fig.savefig(path, dpi=110)
    return path


def rock_collect(args, root, out, failures):
    rows = []
    for a_ww, seed in [(a, sd) for a in args.a_water_wall for sd in args.seeds]:
        tag = case_tag(a_ww, seed, args.seeds)
        wd = os.path.join(root, tag)
        if not os.path.exists(os.path.join(wd, "summary.json")):
            failures.append(f"{tag}: no summary.json in {wd} (not run)")
            continue
        t, fl, summary = read_flood(wd)
        start = fl["start_step"]
        row = check_flood(f"A_water-wall {a_ww:g} seed {seed}", t, fl, start, (0.05, 1.5), failures)
        row["A_water_wall"] = a_ww
        row["seed"] = seed
        row["series"] = {k: t[k].tolist() for k in ("step", "S_inv", "recovery", "pvi")}
        row["penetrations"] = summary.get("penetrations", {}).get("samples_with_penetration")
        row["particles"] = summary["particles"]
        row["loop_seconds"] = summary["timing"]["loop_seconds"]
        row["backend"] = summary["backend"]
        rows.append(row)
    # per wettability over the seeds: mean and standard error of the recovery at breakthrough and at
    # the common end (the smallest final PVI of the group, interpolated)
    stats = []
    for a_ww in args.a_water_wall:
        grp = [r for r in rows if r["A_water_wall"] == a_ww and r["bt_recovery"] is not None]
        if not grp:
            continue
        pv_end = min(r["final_pvi"] for r in grp)
        rf_end = [float(np.interp(pv_end, r["series"]["pvi"], r["series"]["recovery"])) for r in grp]
        bt = [r["bt_recovery"] for r in grp]
        n = len(grp)
        se = (lambda v: float(np.std(v, ddof=1) / np.sqrt(n)) if n > 1 else float("nan"))
        stats.append({"A_water_wall": a_ww, "seeds": n, "bt_recovery": float(np.mean(bt)), "bt_recovery_err": se(bt),
                      "bt_pvi": float(np.mean([r["bt_pvi"] for r in grp])), "pvi_end": pv_end,
                      "recovery_end": float(np.mean(rf_end)), "recovery_end_err": se(rf_end)})
    if stats:
        mdval.write_report(out, "flood_rock_wettability",
                           ["A_water-wall", "seeds", "RF at bt", "+-", "PVI at bt", "PVI (common end)", "RF there", "+-"],
                           [[st["A_water_wall"], st["seeds"], st["bt_recovery"], st["bt_recovery_err"], st["bt_pvi"],
                             st["pvi_end"], st["recovery_end"], st["recovery_end_err"]] for st in stats],
                           notes="Recovery against wettability: mean over seeds, standard error of the mean")
        mdval.write_json(os.path.join(out, "flood_rock_wettability.json"), stats)
        ordered = [st["recovery_end"] for st in stats]
        if len(stats) == 3 and not (ordered[0] > ordered[1] > ordered[2]):
            print("note: the recovery at the common end is not ordered with the water-wall attraction")
    for a_ww in args.a_water_wall:
        wd = os.path.join(root, case_tag(a_ww, args.seeds[0], args.seeds))
        if os.path.isdir(wd):
            map_series(wd, out, f"flood_rock_maps_Aww{int(a_ww)}",
                       f"water saturation, middle z plane, A_water-wall {a_ww:g} (water enters at the left face)")
    if rows:
        report(out, "flood_rock", rows, f"Flooding {os.path.basename(args.image)} ({args.crop or 'the whole image'}), water displacing "
               f"oil, A_oil-wall {args.a_oil_wall:g}, body force {args.g}")
        plot(out, "flood_rock", rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--parts", nargs="+", default=["slit"], choices=["slit", "rock"])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--reuse", action="store_true", help="analyse finished runs again")
    ap.add_argument("--g", type=float, default=0.1, help="body force per particle (0.1)")
    ap.add_argument("--image", help="rock image (raw with sidecar, HDF5 or TIFF)")
    ap.add_argument("--crop", help="X0:X1,Y0:Y1,Z0:Z1 of the image")
    ap.add_argument("--rc-per-voxel", type=float, default=1.0)
    ap.add_argument("--reservoir", type=int, default=4, help="pore voxels padded on each x face (4)")
    ap.add_argument("--a-water-wall", type=float, nargs="+", default=[-35.0, -30.0, -20.0])
    ap.add_argument("--a-oil-wall", type=float, default=-30.0)
    ap.add_argument("--steps", type=int, default=60000)
    ap.add_argument("--seeds", type=int, nargs="+", default=[11], help="rock: one flood per seed (11)")
    ap.add_argument("--start", type=int, default=2000)
    ap.add_argument("--emit", help="rock: write the scenes into this folder")
    ap.add_argument("--collect", help="rock: read the finished runs from this folder")
    args = ap.parse_args()
    out = mdval.out_dir("twophase")
    failures = []
    if "slit" in args.parts:
        slit(args, out, failures)
    if "rock" in args.parts:
        if args.emit:
            rock_emit(args, args.emit)
        if args.collect:
            rock_collect(args, args.collect, out, failures)
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
