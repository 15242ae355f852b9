#!/usr/bin/env python3
"""Writes the seed corpus of tests/fuzz (docs/fuzzing.md): small valid inputs (ok_*), inputs each
reader must refuse (bad_*), and copies of the repository's own scenes, tables and configs.
Regressions (inputs that once crashed or hung a reader) are added by hand as crash_* files and are
not touched here. Run from anywhere: python3 tests/fuzz/make_seeds.py"""
import os
import shutil
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CORPUS = os.path.join(HERE, "corpus")


def put(target, name, data):
    d = os.path.join(CORPUS, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def copy(target, name, src):
    with open(os.path.join(ROOT, src), "rb") as f:
        put(target, name, f.read())


# ---- scene: the repository's cases and test scenes (their expected outcome: the replay names it)
for f in sorted(os.listdir(os.path.join(ROOT, "cases"))):
    if f.endswith(".yaml"):
        copy("scene", "ok_case_" + f, os.path.join("cases", f))
for f in ("ci_slab.yaml", "restart_small.yaml", "flux_slit.yaml"):
    copy("scene", "ok_test_" + f, os.path.join("tests/engine/scenes", f))
bad = os.path.join(ROOT, "tests/engine/bad_scenes")
for f in sorted(os.listdir(bad)):
    if f.endswith(".yaml"):
        copy("scene", "bad_" + f, os.path.join("tests/engine/bad_scenes", f))
put("scene", "bad_deep_nesting.yaml", "a: " + "[" * 5000 + "]" * 5000 + "\n")
put("scene", "bad_deep_block_nesting.yaml", "".join(" " * i + "k%d:\n" % i for i in range(300)))
put("scene", "bad_empty.yaml", "")
# a geometry scene with every block of its own (patches, fluid_region): read, not built
put("scene", "ok_geometry_patches.yaml",
    "box: {hi: [4, 4, 2]}\nspecies: [{name: liquid}, {name: wall, frozen: true}]\n"
    "pairs: {default: {A: -40, B: 25, gamma: 4.5, rd: 0.75}}\n"
    "effects: {mdpd_attraction: , mdpd_repulsion: , dpd_thermostat: , bounce_back: }\n"
    "geometry: {image: slit.h5, rc_per_voxel: 0.5, flow_axis: x,\n"
    "  species: {fluid: liquid, inorganic: wall}, patches: {file: patches.h5, seed: 2},\n"
    "  fluid_region: {lo: [0, 0, 0], hi: [4, 4, 2]}}\n"
    "initial: {temperature: 1}\nrun: {dt: 0.01, steps: 10}\n")
put("scene", "bad_procs_overflow.yaml",
    "box: {hi: [10, 10, 10], procs: [4294967297, 1, 1]}\nspecies: [{name: a}]\n"
    "effects: {}\nrun: {dt: 0.01, steps: 1}\ninitial: {fill: [{species: a, density: 3}]}\n")

# ---- raw image + sidecar: "sidecar text", a line "%%", the voxel bytes
slit = bytes([1] * 48 + [0] * 96 + [1] * 48)  # 8 x 6 x 4, x fastest
put("image_raw", "ok_slit_8x6x4", "dims: 8 6 4\ntype: uint8\nvoxel_size: 10 nm\n%%\n".encode() + slit)
put("image_raw", "ok_uint16_big_zyx",
    "dims: 2x3x2\ntype: uint16\nbyte_order: big\naxis_order: zyx\nheader_bytes: 4\n"
    "labels: pore=0,inorganic=1,organic=7\n%%\n".encode()
    + b"HEAD" + b"".join(struct.pack(">H", v) for v in [0, 1, 7, 0, 1, 7, 0, 0, 1, 1, 7, 7]))
put("image_raw", "ok_int32", "dims: 2,2,1\ntype: int32\n%%\n".encode() + struct.pack("<4i", 0, 1, 2, 0))
put("image_raw", "bad_short_file", "dims: 8 6 4\n%%\n".encode() + slit[:-1])
put("image_raw", "bad_label_out_of_range", "dims: 2 1 1\ntype: int16\n%%\n".encode() + struct.pack("<2h", 0, 300))
put("image_raw", "bad_dims_overflow", "dims: 1000000000 1000000000 1000000000\n%%\n".encode() + slit)
put("image_raw", "bad_header_bytes_overflow",
    "dims: 2 2 2\nheader_bytes: 9223372036854775800\n%%\n".encode() + slit[:8])
put("image_raw", "bad_unknown_key", "dims: 2 2 2\ncolour: red\n%%\n".encode() + slit[:8])
put("image_raw", "bad_no_dims", "type: uint8\n%%\n".encode() + slit[:8])


# ---- TIFF: hand-written little-endian strips, one IFD per page
def tiff(pages, bps=8, w=None, h=None, truncate=None):
    out = bytearray(b"II*\x00" + struct.pack("<I", 0))
    prev_next = 4
    for k, page in enumerate(pages):
        ph, pw = len(page), len(page[0])
        pw, ph = w or pw, h or ph
        data = b"".join(struct.pack("<B" if bps == 8 else "<H", v) for row in page for v in row)
        off = len(out)
        out += data
        if len(out) % 2:
            out += b"\x00"
        tags = [(256, 4, pw), (257, 4, ph), (258, 3, bps), (259, 3, 1), (262, 3, 1), (273, 4, off),
                (277, 3, 1), (278, 4, ph), (279, 4, len(data)), (284, 3, 1)]
        if len(pages) > 1:
            tags.append((297, 3, k | (len(pages) << 16)))
        ifd = len(out)
        struct.pack_into("<I", out, prev_next, ifd)
        out += struct.pack("<H", len(tags))
        for tag, typ, val in sorted(tags):
            if typ == 3 and tag != 297:
                out += struct.pack("<HHIHH", tag, typ, 1, val, 0)
            elif tag == 297:
                out += struct.pack("<HHIHH", tag, typ, 2, val & 0xFFFF, val >> 16)
            else:
                out += struct.pack("<HHII", tag, typ, 1, val)
        prev_next = len(out)
        out += struct.pack("<I", 0)
    if truncate:
        out = out[:truncate]
    return bytes(out)


p0 = [[0, 1, 1, 0], [0, 0, 1, 2], [2, 2, 0, 0]]
p1 = [[1, 1, 1, 1], [0, 0, 0, 0], [2, 0, 2, 0]]
put("image_tiff", "ok_one_page", tiff([p0]))
put("image_tiff", "ok_two_pages", tiff([p0, p1]))
put("image_tiff", "ok_16bit", tiff([p0, p1], bps=16))
put("image_tiff", "bad_16bit_label_300", tiff([[[0, 300]]], bps=16))
put("image_tiff", "bad_pages_differ", tiff([p0, [[0, 1], [1, 0]]]))
two = tiff([p0, p1, p0])
put("image_tiff", "bad_truncated_stack", two[: len(two) - 60])
put("image_tiff", "bad_huge_page", tiff([p0], w=1 << 20, h=1 << 20))

# ---- HDF5: parameter bytes of fuzz_image_hdf5.c (type, rank, flags, dims, 3 attributes, voxels)
def h5(tsel, rank, flags, dims, attrs, voxels):
    b = bytes([tsel, rank, flags] + list(dims) + [0] * (4 - len(dims)))
    for kind, val in attrs:
        b += bytes([kind, len(val)]) + val
    return b + bytes(voxels)


vs = struct.pack("<d", 5e-9)
ok_attrs = [(1, vs), (4, b"m"), (4, b"pore=0,inorganic=1,organic=2")]
put("image_hdf5", "ok_uint8_2x3x4", h5(0, 3, 0, [2, 3, 4], ok_attrs, [0, 1, 2, 0, 0, 1]))
put("image_hdf5", "ok_int64_vlen_attrs", h5(3, 3, 1, [1, 2, 2], [(1, vs), (5, b"nm"), (0, b"")], [0] * 8 + [1] + [0] * 7))
put("image_hdf5", "bad_rank2", h5(0, 2, 0, [3, 3], ok_attrs, [0]))
put("image_hdf5", "bad_float", h5(4, 3, 0, [1, 1, 1], ok_attrs, [0, 0, 0, 0]))
put("image_hdf5", "bad_voxel_size_string", h5(0, 3, 0, [1, 1, 1], [(4, b"ten"), (0, b""), (0, b"")], [0]))
put("image_hdf5", "bad_voxel_size_vector", h5(0, 3, 0, [1, 1, 1], [(2, vs * 3), (0, b""), (0, b"")], [0]))
put("image_hdf5", "bad_voxel_size_negative", h5(0, 3, 0, [1, 1, 1], [(1, struct.pack("<d", -1)), (0, b""), (0, b"")], [0]))
put("image_hdf5", "bad_unit_int", h5(0, 3, 0, [1, 1, 1], [(0, b""), (3, b"\x01\x00\x00\x00"), (0, b"")], [0]))
put("image_hdf5", "bad_huge_shape", h5(0, 3, 3, [40, 8, 8], [(0, b""), (0, b""), (0, b"")], [0]))
put("image_hdf5", "bad_no_labels_dataset", h5(0, 3, 4, [1, 1, 1], [(0, b""), (0, b""), (0, b"")], [0]))

# ---- flow table: the repository's cases and small variants
for f in ("darcy_forcing_sweep.csv", "shale_forcing_sweep.csv"):
    copy("flow_table", "ok_" + f, os.path.join("cases/upscale", f))
head = ("# mdpore flow table v1\n# sample: s\n# axis: x\n# length_unit: rc\n# unit_system: reduced\n"
        "# viscosity: 1.5\n# density: 3\n")
put("flow_table", "ok_small.csv", head + "pressure_gradient,darcy_velocity,darcy_velocity_stderr,run_length\n"
    "0.01,0.002,1e-4,10000\n0.02,0.004,1e-4,10000\n")
put("flow_table", "bad_nan.csv", head + "pressure_gradient,darcy_velocity,darcy_velocity_stderr,run_length\n"
    "nan,0.002,1e-4,10000\n")
put("flow_table", "bad_zero_stderr.csv", head + "pressure_gradient,darcy_velocity,darcy_velocity_stderr,run_length\n"
    "0.01,0.002,0,10000\n")
put("flow_table", "bad_no_rows.csv", head + "pressure_gradient,darcy_velocity,darcy_velocity_stderr,run_length\n")

# ---- LAMMPS data, against the fuzz entry's scene: species 1 (mass 1), 2 (mass 2), box [0, 10]^3
lmp = ("LAMMPS data file\n\n3 atoms\n2 atom types\n\n0 10 xlo xhi\n0 10 ylo yhi\n0 10 zlo zhi\n\n"
       "Masses\n\n1 1\n2 2\n\nAtoms # atomic\n\n1 1 0.5 0.5 0.5\n2 2 1.5 2.5 3.5 0 0 0\n3 1 9 9 9\n")
put("lammps_data", "ok_three_atoms.lmp", lmp)
put("lammps_data", "ok_velocities.lmp", lmp + "\nVelocities\n\n3 0 0 1\n1 0.1 0.2 0.3\n2 0 0 0\n")
put("lammps_data", "bad_duplicate_id.lmp", lmp.replace("3 1 9 9 9", "2 1 9 9 9"))
put("lammps_data", "bad_huge_count.lmp", lmp.replace("3 atoms", "4000000000000 atoms"))
put("lammps_data", "bad_nan_position.lmp", lmp.replace("3 1 9 9 9", "3 1 nan 9 9"))
put("lammps_data", "bad_short_atoms.lmp", lmp.replace("3 1 9 9 9\n", ""))
put("lammps_data", "bad_box.lmp", lmp.replace("0 10 xlo", "0 11 xlo"))

# ---- darcy config: the repository's cases and small variants (last byte odd: --upscale)
for f in ("layered_2d.yaml", "from_fit_3d.yaml"):
    copy("darcy_config", f, os.path.join("cases/upscale", f))
dc = ("units: reduced\nfluid: {viscosity: 1}\ngrid: {cells: [4, 3], size: [4, 3]}\n"
      "boundary: {x-: {pressure: 1}, x+: {pressure: 0}}\nlaws: {uniform: {law: darcy, k: 0.5}}\n"
      "output: {json: out.json}\n")
put("darcy_config", "ok_uniform_2d.yaml", dc)
put("darcy_config", "ok_sources_3d.yaml", dc.replace("[4, 3], size: [4, 3]", "[2, 2, 2], size: [1, 1, 1]")
    + "sources: [{block: [1, 1, 1], rate: 0.1}]\n")
put("darcy_config", "ok_upscale.yaml",
    dc.replace("boundary: {x-: {pressure: 1}, x+: {pressure: 0}}\n", "") + "upscale: {conditions: [fixed]}\n# upscale")
put("darcy_config", "bad_huge_grid.yaml", dc.replace("[4, 3], size: [4, 3]", "[100000, 100000, 5], size: [1, 1, 1]"))
put("darcy_config", "bad_blocks_count.yaml", dc.replace("{uniform: {law: darcy, k: 0.5}}", "{blocks: [{law: darcy, k: 1}]}"))
put("darcy_config", "bad_viscosity_nan.yaml", dc.replace("viscosity: 1}", "viscosity: .nan}"))
put("darcy_config", "bad_k_overflow.yaml", dc.replace("k: 0.5}}", "k: 1e400}}"))

# ---- relative-permeability table (mdpore fit relperm): a relperm.csv as mdpore relperm writes it
kr_head = ("# mdpore relperm: Sw = water particles / all liquid particles; rc = 8.2e-10 m; T = 298.15 K\n"
           "# M: 1\nSw,Sw_err,krw,krw_err,kro,kro_err,Ca,Snw_connected,Snw_disconnected,pc,pc_err\n")
kr_rows = ("0.249584,0,0.0443912,0.0443,0.460486,0.0622,0.04817,0.75,0,,\n"
           "0.748752,0,0.571163,0.129,0.33984,0.0703,0.1062,0.25,0,,\n")
put("kr_table", "ok_slit_quick.csv", kr_head + kr_rows)
put("kr_table", "ok_no_errors.csv", "Sw,krw,kro\n0.2,0.01,0.7\n0.5,0.2,0.2\n0.8,0.6,0.01\n")
put("kr_table", "ok_equal_sw_and_bump.csv",
    "Sw,krw,krw_err,kro,kro_err\n0.2,0.01,0.01,0.7,0.01\n0.2,0.03,0.01,0.6,0.01\n"
    "0.4,0.5,0.004,0.3,0.01\n0.6,0.2,0.01,0.1,0.01\n1,0.9,0.01,0,0.01\n")
put("kr_table", "ok_sw_zero_one.csv", "Sw,krw,krw_err,kro,kro_err\n0,0,0.01,1,0.01\n1,1,0.01,0,0.01\n")
put("kr_table", "bad_nan.csv", kr_head + kr_rows.replace("0.0443912", "nan"))
put("kr_table", "bad_unsorted.csv", kr_head + "".join(reversed(kr_rows.splitlines(True))))
put("kr_table", "bad_no_kro.csv", "Sw,krw\n0.2,0.1\n")
put("kr_table", "bad_short_row.csv", kr_head + "0.2,0,0.1\n")
put("kr_table", "bad_sw_above_one.csv", kr_head + kr_rows.replace("0.748752", "1.5"))
put("kr_table", "bad_negative_kr.csv", kr_head + kr_rows.replace("0.0443912", "-1"))
put("kr_table", "bad_long_line.csv", kr_head + "0.2," + "0" * 5000 + ",0.1,0.01,0.5,0.01,0,0,0,,\n")
put("kr_table", "bad_empty.csv", "")
put("kr_table", "bad_bad_metadata.csv", kr_head.replace("# M: 1", "# rc_m: -5") + kr_rows)

# ---- Pc(Sw) curve (mdpore fit relperm --pc-morph): the pc_morph.csv of mdpore image drainage
copy("pc_curve", "ok_rock_imbibition.csv", "validation/results/relperm/rock/pc_imbibition/pc_morph.csv")
pc_head = "# mdpore image drainage\nstep,radius_vox,radius_rc,Sw,Snw,trapped,nw_spans,pc,pc_depleted,pc_Pa,pc_depleted_Pa,J\n"
put("pc_curve", "ok_reduced.csv", pc_head + "0,4,4,1,0,0,0,4.3,,,,\n1,2,2,0.5,0.5,0,1,8.7,,,,\n"
    "2,1,1,0.1,0.9,0,1,17.3,,,,\n")
put("pc_curve", "bad_no_pc.csv", "Sw,Snw\n0.5,0.5\n0.2,0.8\n")
put("pc_curve", "bad_one_row.csv", pc_head + "0,4,4,1,0,0,0,4.3,,,,\n")
put("pc_curve", "bad_nan.csv", pc_head + "0,4,4,nan,0,0,0,4.3,,,,\n1,2,2,0.5,0.5,0,1,8.7,,,,\n")
put("pc_curve", "bad_sw_above_one.csv", pc_head + "0,4,4,1.5,0,0,0,4.3,,,,\n1,2,2,0.5,0.5,0,1,8.7,,,,\n")
put("pc_curve", "bad_long_line.csv", pc_head + "0,4,4,1," + "0" * 5000 + ",0,0,4.3,,,,\n1,2,2,0.5,0.5,0,1,8.7,,,,\n")

# ---- relperm campaign manifests (mdpore relperm --collect): campaign.txt, a line %%, relperm_runs.txt
rp_camp = ("# mdpore permeability campaign v1\nsample: slit\ninput: slit.raw\nimage: slit.raw\n"
           "porosity: 0.66666666666666663\nrc_per_voxel: 1\nh_hydraulic: 8\npercolates: 1 0 1\n"
           "fluid_density: 6.2000000000000002\nviscosity: 5.4100000000000001\nviscosity_source: mDPD\n"
           "wall_density: 4\nfill_density: 6.2650000000000006\nwall_adsorption: 0.26000000000000001\n"
           "pair_rng: philox\nlength_unit_m: 8.1999999999999996e-10\nlength_source: mDPD water\n"
           "temperature_K: 298.14999999999998\ntarget_error: 0.02\nnp: 1\nkT: 1\ndrive: body\n"
           "reservoir: 0\nboundary: periodic auto auto\nsides: periodic\nseam_continuity: 1 1.22222 1\n"
           "throat_voxels: 8 0 8\nmin_throat: 4\nrc_per_voxel_source: --rc-per-voxel\n"
           "particles_estimate: 691.2\nregime: nanopore\n"
           "run: x 0.02 work/runs/x-7a6f923c7e8b4cd1\nrun: x 0.02 work/runs/x-7f204d247d677fd6\n"
           "run: x 0.02 work/runs/x-1c2633ef17ee1706\nrun: x 0.02 work/runs/x-d92853d8c5ca4816\n")
rp_runs = ("# mdpore relperm campaign v1\naxis: x\nwetting: water\nviscosity_ratio: 1\nM: 1 0\n"
           "mode: given\ntrapping: 1\ng: 0.02\nnw_label: 3\nboundary: periodic\n"
           "rp: two nan 0.75 0.75 0 nan\nrp: two nan 0.25 0.25 0 nan\nrp: water 1 nan nan nan nan\n"
           "rp: oil 0 nan nan nan nan\n")
put("relperm_manifest", "ok_slit_quick", rp_camp + "%%\n" + rp_runs)
put("relperm_manifest", "ok_drainage_m2", rp_camp + "%%\n" + rp_runs.replace("mode: given", "mode: drainage")
    .replace("viscosity_ratio: 1\nM: 1 0", "viscosity_ratio: 2\nM: 2.2309999999999999 0.023")
    .replace("two nan 0.75 0.75 0 nan", "two 0.25 0.75 0.7 0.05 3.5"))
for name, old, new in (("axis_q", "axis: x", "axis: q"), ("axis_twice", "axis: x", "axis: x\naxis: y"),
                       ("no_axis", "axis: x\n", ""), ("g_nan", "g: 0.02", "g: nan"),
                       ("g_inf", "g: 0.02", "g: 1e400"), ("m_negative", "M: 1 0", "M: -1 0"),
                       ("ratio_3", "viscosity_ratio: 1", "viscosity_ratio: 3"),
                       ("wetting_gas", "wetting: water", "wetting: gas"),
                       ("mode_unknown", "mode: given", "mode: flooding"),
                       ("label_0", "nw_label: 3", "nw_label: 0"),
                       ("boundary_auto", "boundary: periodic", "boundary: auto"),
                       ("role_gas", "rp: oil 0", "rp: gas 0"),
                       ("run_short", "rp: oil 0 nan nan nan nan", "rp: oil 0 nan"),
                       ("run_sw_2", "rp: water 1 nan", "rp: water 2 nan"),
                       ("run_missing", "rp: oil 0 nan nan nan nan\n", ""),
                       ("unknown_key", "trapping: 1", "trapping: 1\ncolour: red"),
                       ("head", "# mdpore relperm campaign v1", "# mdpore relperm campaign v0")):
    put("relperm_manifest", "bad_" + name, rp_camp + "%%\n" + rp_runs.replace(old, new, 1))
put("relperm_manifest", "bad_too_many_runs", rp_camp + "%%\n" + rp_runs + "rp: two nan 0.5 0.5 0 nan\n" * 200)
put("relperm_manifest", "bad_long_line", rp_camp + "%%\n" + rp_runs.replace("g: 0.02", "g: 0.0" + "0" * 3000 + "2"))
put("relperm_manifest", "bad_no_campaign", rp_runs)

# ---- mdpore permeability / relperm command lines: argv tokens, one a line (the parser only)
img = "/dev/null"  # any readable file stands for the IMAGE (the parser checks only that)
for name, args in (("axis_x", ["IMG", "--axis", "x"]),
                   ("all_options", ["IMG", "--axis", "all", "--gradients", "0.05,0.1,0.2", "--dt", "0.005",
                                    "--np", "2", "--jobs", "auto", "--rc-per-voxel", "0.5", "--min-throat", "3",
                                    "--voxel-size", "1e-9", "--viscosity", "5", "--wall-density", "4",
                                    "--wall-adsorption", "0", "--rng", "fast", "--temperature", "300",
                                    "--seed", "7", "--flux-every", "20", "--models", "darcy,power",
                                    "--sample", "s", "--boundary", "mirror", "--sides", "mirror",
                                    "--density-tolerance", "0.1", "--require-target", "--force"]),
                   ("target_error_k", ["IMG", "--axis", "y", "--target-error-k", "0.1", "--max-steps", "4000",
                                       "--round-steps", "1000", "--budget-steps", "20000"]),
                   ("pressure", ["IMG", "--axis", "z", "--drive", "pressure", "--reservoir", "6",
                                 "--n-gradients", "7", "--velocity-range", "0.01,0.1", "--accuracy", "fast"]),
                   ("collect", ["--collect", "somewhere", "--models", "darcy"]),
                   ("help", ["--help"])):
    put("campaign_args", "ok_" + name, "\n".join(img if a == "IMG" else a for a in args) + "\n")
for name, args in (("relperm", ["IMG", "--axis", "x", "--saturations", "0.3,0.6", "--mode", "imbibition",
                                "--no-trapping", "--wetting", "oil", "--viscosity-ratio", "2", "--steps", "100",
                                "--jobs", "2", "--boundary", "mirror", "WORK"]),
                   ("relperm_collect", ["--collect", "somewhere"])):
    put("campaign_args", "ok_" + name, "relperm\n" + "\n".join(img if a == "IMG" else a for a in args) + "\n")
for name, args in (("no_axis", ["IMG"]), ("no_input", ["--axis", "x"]), ("axis_w", ["IMG", "--axis", "w"]),
                   ("unknown", ["IMG", "--axis", "x", "--colour", "red"]),
                   ("no_value", ["IMG", "--axis"]), ("missing_file", ["/nonexistent/rock.raw", "--axis", "x"]),
                   ("gradients_nan", ["IMG", "--axis", "x", "--gradients", "0.1,nan"]),
                   ("gradients_zero", ["IMG", "--axis", "x", "--gradients", "0,0.1"]),
                   ("n_gradients_huge", ["IMG", "--axis", "x", "--n-gradients", "99999999999999999999"]),
                   ("np_overflow", ["IMG", "--axis", "x", "--np", "4294967297"]),
                   ("jobs_65", ["IMG", "--axis", "x", "--jobs", "65"]),
                   ("dt_inf", ["IMG", "--axis", "x", "--dt", "inf"]),
                   ("velocity_reversed", ["IMG", "--axis", "x", "--velocity-range", "0.2,0.1"]),
                   ("models_typo", ["IMG", "--axis", "x", "--models", "darcy,forchheimr"]),
                   ("round_steps_alone", ["IMG", "--axis", "x", "--round-steps", "100"]),
                   ("round_steps_above_max", ["IMG", "--axis", "x", "--target-error-k", "0.1", "--max-steps",
                                              "100", "--round-steps", "1000"]),
                   ("k_with_pressure", ["IMG", "--axis", "x", "--target-error-k", "0.1", "--drive", "pressure"]),
                   ("pressure_periodic", ["IMG", "--axis", "x", "--drive", "pressure", "--boundary", "periodic"]),
                   ("reservoir_2", ["IMG", "--axis", "x", "--reservoir", "2"]),
                   ("accuracy_sloppy", ["IMG", "--axis", "x", "--accuracy", "sloppy"]),
                   ("collect_and_input", ["IMG", "--collect", "somewhere"]),
                   ("two_inputs", ["IMG", "IMG", "--axis", "x"])):
    put("campaign_args", "bad_" + name, "\n".join(img if a == "IMG" else a for a in args) + "\n")
for name, args in (("no_workdir", ["IMG", "--axis", "x"]),
                   ("saturation_1", ["IMG", "--axis", "x", "--saturations", "0.5,1", "W"]),
                   ("ratio_3", ["IMG", "--axis", "x", "--viscosity-ratio", "3", "W"]),
                   ("nw_label_256", ["IMG", "--axis", "x", "--nw-label", "256", "W"]),
                   ("scene_input", ["case.yaml", "--axis", "x", "W"]),
                   ("ok_boundary_reservoir", ["IMG", "--axis", "x", "--boundary", "reservoir", "W"])):
    put("campaign_args", "bad_relperm_" + name,
        "relperm\n" + "\n".join(img if a == "IMG" else a for a in args) + "\n")

# ---- a campaign folder read back: campaign.txt, a line %%, rounds.txt, a line %%, summary.json
camp = ("# mdpore permeability campaign v1\nsample: s\ninput: /none/s.raw\nimage: \nporosity: 0.5\n"
        "rc_per_voxel: 0.5\nh_hydraulic: 4\npercolates: 1 1 1\nfluid_density: 6.2\nviscosity: 5\n"
        "viscosity_source: --viscosity\nlength_unit_m: 8.2e-10\nlength_source: the mDPD water mapping\n"
        "temperature_K: 298.15\ntarget_error: 0.05\nnp: 1\nkT: 1\ndrive: body\nreservoir: 0\n"
        "boundary: periodic none none\nsides: periodic\nseam_continuity: 1 nan nan\n"
        "run: x 0.016 runs/x-00\nrun: x 0.032 runs/x-01\nrun: x 0.048 runs/x-02\n")
rounds = ("# mdpore permeability rounds: round R STEP RUN (the step each run reaches in round R)\n"
          "round 1 600 runs/x-00\nround 1 600 runs/x-01\nround 1 600 runs/x-02\n"
          "round 2 1200 runs/x-00\nround 3 2400 runs/x-02\n")
summary = ('{"thermo": {"T": {"mean": 1.004, "err": 0.001}}, "pore_core_density": {"mean": 6.03, "err": 0.01}, '
           '"flux": {"axis": "x", "q": 0.064, "q_err": 0.00064, "G": 0.4, "relative_error": 0.01, '
           '"fluid_fraction": 0.48, "steady_from_step": 500, "steady": true, "plateau": true, '
           '"target_error": 0.05, "reached": true, "pressure_drop": {"dp_over_force_per_area": 1.01}}, '
           '"timing": {"loop_seconds": 1.0, "steps": 8000, "particles": 1000}, "last_step": 8000}\n')
put("campaign_folder", "ok_three_parts", camp + "%%\n" + rounds + "%%\n" + summary)
put("campaign_folder", "ok_manifest_only", camp)
put("campaign_folder", "ok_no_rounds", camp + "%%\n%%\n" + summary)
for name, old, new in (("head", "campaign v1", "campaign v0"), ("np_0", "np: 1", "np: 0"),
                       ("viscosity_nan", "viscosity: 5", "viscosity: nan"),
                       ("g_inf", "x 0.016", "x 1e400"), ("axis_w", "run: x 0.032", "run: w 0.032"),
                       ("run_twice", "runs/x-01", "runs/x-00"), ("g_twice", "x 0.032", "x 0.016"),
                       ("key_twice", "kT: 1\n", "kT: 1\nkT: 2\n"), ("unknown_key", "kT: 1", "colour: red"),
                       ("no_runs", "run: x 0.016 runs/x-00\nrun: x 0.032 runs/x-01\nrun: x 0.048 runs/x-02\n", ""),
                       ("long_line", "sample: s", "sample: " + "s" * 13000)):
    put("campaign_folder", "bad_manifest_" + name, camp.replace(old, new, 1) + "%%\n" + rounds)
put("campaign_folder", "bad_manifest_too_many_runs",
    camp + "".join("run: y %d runs/y-%d\n" % (i + 1, i) for i in range(300)))
for name, old, new in (("round_0", "round 1 600 runs/x-00", "round 0 600 runs/x-00"),
                       ("round_skipped", "round 3 2400", "round 4 2400"),
                       ("step_0", "round 2 1200", "round 2 0"),
                       ("no_run", "round 2 1200 runs/x-00", "round 2 1200"),
                       ("step_huge", "round 2 1200", "round 2 99999999999999999999"),
                       ("round_65", "round 3 2400", "round 65 2400"),
                       ("long_line", "runs/x-02\nround 2", "runs/x-02" + "2" * 9000 + "\nround 2")):
    put("campaign_folder", "bad_rounds_" + name, camp + "%%\n" + rounds.replace(old, new, 1) + "%%\n" + summary)
put("campaign_folder", "bad_rounds_65_rounds",
    camp + "%%\n" + "".join("round %d %d runs/x-00\n" % (r + 1, 100 * (r + 1)) for r in range(65)))
for name, old, new in (("q_nan", '"q": 0.064', '"q": .nan'), ("q_err_0", '"q_err": 0.00064', '"q_err": 0'),
                       ("no_flux", '"flux"', '"flow"'), ("flux_list", '"flux": {', '"flux": [{'),
                       ("G_huge", '"G": 0.4', '"G": 1e400'), ("not_json", '{"thermo"', '{{"thermo"')):
    put("campaign_folder", "bad_summary_" + name, camp + "%%\n" + rounds + "%%\n" + summary.replace(old, new, 1))

# ---- image operations whose numbers are sizes, over the entry's fixed 6x5x4 image (argv tokens)
for name, args in (("none", ["image"]), ("crop", ["image", "--crop", "1:5,:,1:3"]),
                   ("crop_open", ["image", "--crop", "2:,:3,:"]),
                   ("downsample", ["image", "--downsample", "2"]),
                   ("crop_downsample_pad", ["image", "--crop", "0:6,1:5,:", "--downsample", "2",
                                             "--pad", "x=3", "--pad", "z=1:2"]),
                   ("pad_all", ["image", "--pad", "2"]), ("mirror", ["image", "--mirror", "x,z"]),
                   ("everything", ["image", "--crop", ":,:,1:4", "--downsample", "3", "--pad", "y=2:1",
                                   "--mirror", "x,y,z"]),
                   ("pad_large", ["image", "--pad", "x=100000"])):
    put("image_ops", "ok_" + name, "\n".join(args) + "\n")
for name, args in (("crop_outside", ["image", "--crop", "0:7,:,:"]),
                   ("crop_empty", ["image", "--crop", "3:3,:,:"]),
                   ("crop_reversed", ["image", "--crop", "4:2,:,:"]),
                   ("crop_negative_end", ["image", "--crop", "0:-2,:,:"]),
                   ("crop_wraps_int", ["image", "--crop", "4294967297:4294967299,:,:"]),
                   ("downsample_0", ["image", "--downsample", "0"]),
                   ("downsample_above_dims", ["image", "--downsample", "5"]),
                   ("pad_negative", ["image", "--pad", "-1"]),
                   ("pad_int_overflow", ["image", "--pad", "x=2147483647"]),
                   ("pad_memory", ["image", "--pad", "100000"]),
                   ("pad_label_unknown", ["image", "--pad", "1:9"]),
                   ("mirror_w", ["image", "--mirror", "w"]),
                   ("mirror_memory", ["image", "--pad", "x=1000000", "--mirror", "x,y,z"])):
    put("image_ops", "bad_" + name, "\n".join(args) + "\n")
for name, args in (("ok_stack_x", ["stack", "x", "+", "--crop", "0:2,:,:", "+", "--pad", "x=3"]),
                   ("bad_stack_mismatch", ["stack", "y", "+", "--crop", "0:2,:,:"]),
                   ("bad_stack_voxel_size", ["stack", "z", "--downsample", "2", "+", "--downsample", "1"]),
                   ("bad_stack_overflow", ["stack", "x", "--pad", "x=1073741823", "+", "--pad", "x=1073741823"]),
                   ("ok_boundary_mirror", ["permeability", "--axis", "all", "--boundary", "mirror"]),
                   ("ok_boundary_sides", ["permeability", "--axis", "y", "--boundary", "mirror", "--sides", "mirror"]),
                   ("ok_boundary_reservoir", ["permeability", "--axis", "x", "--drive", "pressure",
                                           "--reservoir", "7", "--rc-per-voxel", "0.25"]),
                   ("bad_boundary_reservoir_huge", ["permeability", "--axis", "z", "--boundary", "reservoir",
                                                "--reservoir", "999999", "--rc-per-voxel", "1e-300"]),
                   ("bad_boundary_reservoir_memory", ["permeability", "--axis", "y", "--drive", "pressure",
                                                  "--reservoir", "900000", "--sides", "mirror"])):
    put("image_ops", name, "\n".join(args) + "\n")

# ---- geometry: scenes built against the entry's slit_8x6x4.raw (the geometry test scenes' image)
geo_bad = os.path.join(ROOT, "tests/engine/bad_scenes/geometry")
for f in sorted(os.listdir(geo_bad)):
    if f.endswith(".yaml"):
        copy("geometry", "bad_" + f, os.path.join("tests/engine/bad_scenes/geometry", f))
geo = ("box: {lo: [0, 0, 0], hi: [4, 3, 2]}\nspecies:\n  - {name: liquid}\n  - {name: quartz, frozen: true}\n"
       "pairs:\n  default: {A: -40, B: 25, gamma: 4.5, rc: 1.0, rd: 0.75}\n"
       "effects: {mdpd_attraction: {}, mdpd_repulsion: {}, dpd_thermostat: {}}\n"
       "geometry:\n  image: slit_8x6x4.raw\n  flow_axis: x\n  rc_per_voxel: 0.5\n"
       "  species: {fluid: liquid, inorganic: quartz}\n"
       "initial: {temperature: 1.0}\nrun: {dt: 0.01, steps: 10}\n")
put("geometry", "ok_slit.yaml", geo)
for name, old, new in (("axis_map", "hi: [4, 3, 2]", "hi: [3, 4, 2]"),
                       ("thickness", "rc_per_voxel: 0.5", "rc_per_voxel: 0.5\n  wall_thickness: 1.5"),
                       ("densities", "rc_per_voxel: 0.5", "rc_per_voxel: 0.5\n  wall_density: 4\n"
                        "  fluid_density: 7\n  min_wall_distance: 0.1\n  isolated_pores: fill"),
                       ("voxels_per_rc", "rc_per_voxel: 0.5", "voxels_per_rc: 2"),
                       ("patch_seed", "rc_per_voxel: 0.5", "rc_per_voxel: 0.5\n  patches: {seed: 9}"),
                       ("no_min_distance", "rc_per_voxel: 0.5", "rc_per_voxel: 0.5\n  min_wall_distance: 0")):
    text = geo.replace(old, new, 1)
    if name == "axis_map":
        text = text.replace("flow_axis: x", "flow_axis: y\n  axis_map: [y, x, z]")
    put("geometry", "ok_" + name + ".yaml", text)
for name, old, new in (("fluid_density_huge", "rc_per_voxel: 0.5", "rc_per_voxel: 0.5\n  fluid_density: 1e9"),
                       ("wall_density_above_patches", "rc_per_voxel: 0.5", "rc_per_voxel: 0.5\n  wall_density: 31"),
                       ("voxel_below_patches", "rc_per_voxel: 0.5", "rc_per_voxel: 0.01"),
                       ("thickness_below_voxel", "rc_per_voxel: 0.5", "rc_per_voxel: 0.5\n  wall_thickness: 0.2"),
                       ("image_is_scene", "image: slit_8x6x4.raw", "image: scene.yaml")):
    put("geometry", "bad_" + name + ".yaml", geo.replace(old, new, 1))

total = sum(os.path.getsize(os.path.join(dp, f)) for dp, _, fs in os.walk(CORPUS) for f in fs)
print("corpus: %d bytes" % total)
