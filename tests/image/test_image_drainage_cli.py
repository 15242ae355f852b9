"""mdpore image drainage from the command line (docs/relperm.md section 2) on a slit of 10 pore
layers (2-voxel walls, 5 um voxels): the CSV's columns against the definitions (Pc = 2 gamma cos / r,
r = R rc_per_voxel; the depleted column r - 1.15 rc; Pa = the reduced Pc x kT / rc^3 at 298.15 K with
rc = voxel / rc_per_voxel; J = 2 sqrt(k / phi) / r with k in mD converted through rc), the entry at
R = w / 2, the PNG, --at / --write-image (its labelled voxels equal the step's non-wetting voxels), and
the refusals of a label the image uses, --at without --write-image and an unknown axis.
argv: mdpore executable."""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

mdpore = sys.argv[1]
failures = []
KB, T = 1.380649e-23, 298.15


def run(*args):
    p = subprocess.run([mdpore, "image", *args], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what)


def close(a, b, rel=1e-5):
    return abs(a - b) <= rel * abs(b)


with tempfile.TemporaryDirectory() as tmp:
    slit = os.path.join(tmp, "slit.h5")
    rc, out, err = run("make", "slit", "--width", "10", "--wall", "2", "--length", "12", "--depth", "3",
                       "-o", slit, "--voxel-size", "5um")
    check(rc == 0, f"make slit: {err}")
    h, gc, md, phi = 0.4, 8.67, 250.0, 0.5
    outdir = os.path.join(tmp, "a", "b")
    rc, out, err = run("drainage", slit, "--axis", "x", "--rc-per-voxel", str(h), "--k", f"{md}mD",
                       "--phi", str(phi), "-o", outdir)
    check(rc == 0, f"drainage: {err}")
    check("breakthrough (non-wetting spans the axis) at R 5 voxels" in out, f"breakthrough line: {out}")
    with open(os.path.join(outdir, "pc_morph.csv")) as f:
        lines = f.read().splitlines()
    comments = [ln for ln in lines if ln.startswith("#")]
    rows = list(csv.DictReader([ln for ln in lines if not ln.startswith("#")]))
    check(any("gamma_cos = 8.67" in c for c in comments), "gamma cos stated")
    check(any("interpretation, not a measurement" in c for c in comments), "depletion stated")
    check(os.path.getsize(os.path.join(outdir, "pc_morph.png")) > 1000, "PNG written")
    rc_m = 5e-6 / h
    pa = KB * T / rc_m ** 3
    k_rc2 = md * 1e-3 * 9.869233e-13 / rc_m ** 2
    radii = [float(r["radius_vox"]) for r in rows]
    check(radii == [5.0, 4.0, 3.0, 2.0, 1.0], f"radii {radii}")
    for r in rows:
        R = float(r["radius_vox"])
        rr = R * h
        pc = 2 * gc / rr
        check(close(float(r["radius_rc"]), rr), f"radius_rc {r['radius_rc']} at R {R}")
        check(close(float(r["pc"]), pc), f"pc {r['pc']} vs {pc}")
        check(close(float(r["pc_Pa"]), pc * pa), f"pc_Pa {r['pc_Pa']} vs {pc * pa}")
        check(close(float(r["J"]), 2 * math.sqrt(k_rc2 / phi) / rr), f"J {r['J']}")
        if rr > 1.15:
            check(close(float(r["pc_depleted"]), 2 * gc / (rr - 1.15)), f"pc_depleted {r['pc_depleted']}")
        else:
            check(r["pc_depleted"] == "" and r["pc_depleted_Pa"] == "", "pc_depleted empty at r <= 1.15")
        check(float(r["Snw"]) == 1.0 and r["nw_spans"] == "1", f"slit fully drained at R {R}")
    # the phases nearest Snw 0.6: the slit is all or nothing, so the step at Snw 1 (R 5)
    img = os.path.join(tmp, "nw.h5")
    rc, out, err = run("drainage", slit, "--axis", "x", "--no-plot", "-o", tmp, "--at", "0.6",
                       "--write-image", img)
    check(rc == 0 and "Snw 1.0000 (target 0.6) at R 5" in out, f"--at: {out} {err}")
    rc, out, err = run("info", img, "--json")
    info = json.loads(out) if rc == 0 else {}
    check(info.get("label_map") == "pore=0,3;inorganic=1", f"label map {info.get('label_map')}")
    check(info.get("pore_voxels") == 10 * 12 * 3, f"pore voxels {info.get('pore_voxels')}")
    # refusals
    rc, out, err = run("drainage", img, "--axis", "x", "--at", "0.5", "--write-image",
                       os.path.join(tmp, "x.h5"), "-o", tmp, "--no-plot")
    check(rc != 0 and "label 3" in err and "expected a label the image does not use" in err,
          f"nw label in use: rc {rc} {err}")
    rc, out, err = run("drainage", slit, "--axis", "x", "--at", "0.5")
    check(rc == 2 and "go together" in err, f"--at alone: {err}")
    rc, out, err = run("drainage", slit, "--axis", "w")
    check(rc == 2 and "expected x, y, z or none" in err, f"bad axis: {err}")
    bare = os.path.join(tmp, "bare.h5")  # no physical voxel size
    run("make", "slit", "--width", "4", "--length", "4", "-o", bare)
    rc, out, err = run("drainage", bare, "--axis", "x", "--k", "1mD", "--phi", "0.3", "-o", tmp)
    check(rc == 2 and "needs the voxel size" in err, f"mD without a voxel size: {err}")

print("FAILED" if failures else "ok", len(failures), "failures")
sys.exit(1 if failures else 0)
