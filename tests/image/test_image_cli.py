"""mdpore image info/convert/make from the command line: porosity of the POREMAPS BCC/FCC packs
(built at porosity 0.30), JSON output, HDF5 conversion that keeps the statistics, and the errors for a
wrong size, an unknown label, empty pore space and a non-percolating axis; the periodicity report and
--sizes (critical throat) on a slit.
argv: mdpore executable, poremaps_benchmarks folder."""
import glob
import json
import os
import subprocess
import sys
import tempfile

mdpore, data = sys.argv[1], sys.argv[2]
failures = []


def run(*args):
    p = subprocess.run([mdpore, "image", *args], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


with tempfile.TemporaryDirectory() as tmp:
    # make + info JSON: a slit of 6 pore layers between 2-voxel walls has porosity 6/10
    slit = os.path.join(tmp, "slit.h5")
    rc, out, err = run("make", "slit", "--width", "6", "--wall", "2", "--length", "5", "-o", slit,
                       "--voxel-size", "20nm")
    check(rc == 0, f"make slit: {err}")
    rc, out, err = run("info", slit, "--json")
    info = json.loads(out)
    check(abs(info["porosity"] - 0.6) < 1e-9, f"slit porosity {info['porosity']}")
    check(info["percolates"] == {"x": True, "y": False, "z": True}, f"slit percolation {info['percolates']}")
    check(info["unit"] == "nm" and info["voxel_size"] == 20, "voxel size kept in HDF5")
    # periodicity (always) and sizes (--sizes): the slit's end slices match along x and z; its
    # critical throat is its width along x and z, none along y
    per = info["periodicity"]
    check(per["x"]["overlap"] == 1 and per["x"]["percolates_wrap"] and not per["y"]["percolates_wrap"],
          f"slit periodicity {per['x']} {per['y']}")
    rc, out, err = run("info", slit, "--json", "--sizes", "--periodic")
    sizes = json.loads(out)["sizes"] if rc == 0 else {}
    check(sizes.get("critical_throat_voxels") == {"x": 6, "y": 0, "z": 6} and sizes.get("periodic") == [True] * 3,
          f"slit --sizes: {sizes}")
    rc, out, err = run("info", slit, "--sizes")
    check(rc == 0 and "periodic x" in out and "critical (breakthrough) diameter, voxels: x 6  y 0  z 6" in out,
          f"slit --sizes text: {out[-400:]}")
    rc, out, err = run("info", slit, "--axis", "y")
    check(rc != 0 and "axis y does not percolate" in err, f"non-percolating axis error: {err}")
    rc, out, err = run("info", slit, "--labels", "pore=7,inorganic=0-1")
    check(rc != 0 and "empty pore space" in err, f"empty pore space error: {err}")

    # convert with crop + downsample + pad, then raw round trip keeps labels via the sidecar
    raw = os.path.join(tmp, "slit.raw")
    rc, out, err = run("convert", slit, "--crop", "1:5,:,:", "--pad", "x=1", "-o", raw)
    check(rc == 0 and os.path.exists(raw + ".hdr"), f"convert to raw: {err}")
    rc, out, err = run("info", raw, "--json")
    info = json.loads(out)
    check(info["dims"] == [6, 10, 1], f"crop+pad dims {info['dims']}")
    check(abs(info["porosity"] - (4 * 6 + 2 * 10) / 60) < 1e-9, f"crop+pad porosity {info['porosity']}")

    files = sorted(glob.glob(os.path.join(data, "*.raw")))
    if not files:
        print("poremaps data not found: external-image checks skipped")
    for f in files:
        args = ["--dims", "100x100x100", "--type", "uint8", "--order", "xyz",
                "--labels", "pore=0,inorganic=1", "--voxel-size", "10um"]
        rc, out, err = run("info", f, *args, "--json")
        check(rc == 0, f"info {f}: {err}")
        info = json.loads(out)
        print(os.path.basename(f)[:14], "porosity", info["porosity"], "connected x",
              info["connected_porosity"]["x"], "isolated", info["isolated"])
        check(abs(info["porosity"] - 0.30) < 0.005, f"{f}: porosity {info['porosity']} not ~0.30")
        check(all(info["percolates"].values()), f"{f}: must percolate along all axes")
        h5 = os.path.join(tmp, "pack.h5")
        rc, out, err = run("convert", f, *args, "-o", h5)
        rc, out2, err = run("info", h5, "--json")
        check(json.loads(out2)["porosity"] == info["porosity"], "HDF5 conversion changed the porosity")
        rc, out, err = run("info", f, "--dims", "100x100x99")
        check(rc != 0 and "file has 1000000 bytes" in err, f"size mismatch error: {err}")
        rc, out, err = run("info", f, "--dims", "100x100x100", "--labels", "pore=0")
        check(rc != 0 and "has label 1" in err, f"unknown label error: {err}")

print(f"{len(failures)} failures")
sys.exit(1 if failures else 0)
