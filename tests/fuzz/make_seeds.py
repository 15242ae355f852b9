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

total = sum(os.path.getsize(os.path.join(dp, f)) for dp, _, fs in os.walk(CORPUS) for f in fs)
print("corpus: %d bytes" % total)
