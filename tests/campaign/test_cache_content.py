#!/usr/bin/env python3
"""ctest campaign_cache_content: the run folders of `mdpore permeability` are keyed by the content of
its inputs, not by their paths (campaign/campaign_hash.c). Nothing is simulated (--emit-scenes only:
seconds).

A raw slit image (16 x 12 x 8 voxels, 4 wall voxels per side) whose sidecar IMAGE.hdr skips 16
header bytes; the campaign's scenes name it by its absolute path (quoted by the YAML emitter).
 1. emitted twice unchanged: the same run folders (a cache hit is possible at all);
 2. the image replaced in place by one that differs only in the skipped header bytes: the scenes are
    the same text, yet every run folder changes (the bytes are hashed, not the path);
 3. the sidecar changed in place (a voxel size added, the voxels untouched): the folders change;
 4. the image replaced by an image of another slit (width 10) under the same name: the folders change
    and no earlier folder is reused.
"""
import os
import shutil
import subprocess
import sys

MDPORE = os.environ.get("MDPORE", "mdpore")
OUT = os.path.abspath(os.environ.get("MDPORE_TEST_OUT", "campaign_cache_content_out"))
failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def slit(width, header=b"\0" * 16, wall=4, nx=12, nz=8):
    ny = width + 2 * wall
    voxels = bytearray()
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                voxels.append(0 if wall <= y < wall + width else 1)
    return header + bytes(voxels), "dims: %dx%dx%d\ntype: uint8\nheader_bytes: 16\n" % (nx, ny, nz)


def write(path, data, mode="wb"):
    with open(path, mode) as f:
        f.write(data)


def emit(name):
    folder = os.path.join(OUT, name)
    shutil.rmtree(folder, ignore_errors=True)
    p = subprocess.run([MDPORE, "permeability", os.path.join(OUT, "slit.raw"), "--axis", "x",
                        "--rc-per-voxel", "0.5", "--emit-scenes", folder],
                       capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stdout + p.stderr)
    runs = [l.split()[3] for l in open(os.path.join(folder, "campaign.txt")) if l.startswith("run: ")] \
        if p.returncode == 0 else []
    scenes = sorted(open(os.path.join(r, "scene.yaml")).read().split("\n", 1)[1] for r in runs)
    return p.returncode, [os.path.basename(r) for r in runs], scenes


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    data, hdr = slit(8)
    write(os.path.join(OUT, "slit.raw"), data)
    write(os.path.join(OUT, "slit.raw.hdr"), hdr, "w")
    rc, first, scenes0 = emit("first")
    check(rc == 0 and len(first) == 5, "emitted 5 runs (exit %d)" % rc)
    check(any('image: "/' in s or "image: /" in s for s in scenes0),
          "the scenes name the image by its absolute path")
    rc, again, _ = emit("again")
    check(rc == 0 and again == first, "unchanged inputs: the same run folders")

    data2, _ = slit(8, header=b"\1" * 16)  # the same voxels, other skipped bytes
    write(os.path.join(OUT, "slit.raw"), data2)
    rc, header_changed, scenes1 = emit("header_bytes")
    check(rc == 0 and scenes1 == scenes0, "image bytes changed in place: the same scene texts")
    check(rc == 0 and not set(header_changed) & set(first),
          "image bytes changed in place: every run folder changes (%d of %d reused)"
          % (len(set(header_changed) & set(first)), len(first)))

    write(os.path.join(OUT, "slit.raw.hdr"), hdr + "voxel_size: 1 nm\n", "w")
    rc, sidecar_changed, _ = emit("sidecar")
    check(rc == 0 and not set(sidecar_changed) & set(header_changed),
          "sidecar changed in place: every run folder changes")

    data3, hdr3 = slit(10, wall=3)  # another slit, the same outer size, under the same name
    write(os.path.join(OUT, "slit.raw"), data3)
    write(os.path.join(OUT, "slit.raw.hdr"), hdr3, "w")
    rc, other, _ = emit("other_slit")
    check(rc == 0 and not set(other) & (set(first) | set(header_changed) | set(sidecar_changed)),
          "another image under the same name: no earlier run folder reused")
    print("%d failure(s)" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
