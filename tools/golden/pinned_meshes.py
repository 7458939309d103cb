#!/usr/bin/env python3
"""Pins the meshes fdrmesh writes: runs each case, hashes the written files, compares with
testdata/pinned_meshes.json. A refactor that changes no mesh keeps every hash.

  pinned_meshes.py FDRMESH [--set quick|regions|all] [--update] [--only NAME]

Shared-data cases (../shared/data) are skipped with a message when that folder is absent.
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TD = os.path.join(ROOT, "testdata")
SHARED = os.path.normpath(os.path.join(ROOT, "..", "shared", "data"))
PINS = os.path.join(TD, "pinned_meshes.json")

# name -> (set, arguments before the outputs, output suffixes)
POLY_OUT = [".2dm", ".node"]
GIS_OUT = [".2dm", ".14"]


def region(name, hmin=None):
    d = os.path.join(SHARED, name)
    args = [os.path.join(d, name + ".gpkg"), "--layer", "water",
            "--open-boundary", os.path.join(d, name + ".gpkg"), "--open-boundary-layer", "open_boundary",
            "--raster", os.path.join(d, name + "_etopo5.tif")]
    if hmin:
        args += ["--hmin", str(hmin)]
    return args


CASES = {
    "square_f1": ("quick", [os.path.join(TD, "poly", "square10.poly"), "--spacing", "0.05*paper-f1"], POLY_OUT),
    "square_f2": ("quick", [os.path.join(TD, "poly", "square10.poly"), "--spacing", "0.05*paper-f2"], POLY_OUT),
    "square_with_hole": ("quick", [os.path.join(TD, "poly", "square_with_hole.poly"), "--spacing", "0.2"], POLY_OUT),
    "wedge_1deg": ("quick", [os.path.join(TD, "poly", "wedge_1deg.poly"), "--spacing", "0.05"], POLY_OUT),
    "messy_star": ("quick", [os.path.join(TD, "poly", "messy_star.poly"), "--spacing", "0.1"], POLY_OUT),
    "chesapeake_bundled": ("quick", [
        os.path.join(TD, "chesapeake", "chesapeake_mouth_water.geojson"),
        "--open-boundary", os.path.join(TD, "chesapeake", "chesapeake_mouth_open_boundary.geojson"),
        "--raster", os.path.join(TD, "chesapeake", "chesapeake_mouth_etopo5.tif"),
        "--hmin", "150", "--dist-grade", "0.08"], GIS_OUT),
    "turku_archipelago": ("quick", [
        os.path.join(TD, "baltic_archipelago", "turku_archipelago.gpkg"), "--layer", "water",
        "--open-boundary", os.path.join(TD, "baltic_archipelago", "turku_archipelago.gpkg"),
        "--open-boundary-layer", "open_boundary",
        "--raster", os.path.join(TD, "baltic_archipelago", "turku_archipelago_etopo5.tif"),
        "--hmin", "300", "--hmax", "5000"], GIS_OUT),
    "square_1m": ("regions", [os.path.join(TD, "poly", "square10.poly"), "--spacing", "0.025*paper-f1"], POLY_OUT),
    "chesapeake_mouth": ("regions", region("chesapeake_mouth", 150) + ["--hmax", "5000"], GIS_OUT),
    "gulf_of_maine": ("regions", region("gulf_of_maine", 120) + ["--dist-grade", "0.04"], GIS_OUT),
    "west_norway": ("regions", region("west_norway", 100), GIS_OUT),
    "west_norway_h": ("regions", region("west_norway_h", 100), GIS_OUT),
}


def digest(path):
    """The file's hash with the checkout's paths replaced by names: a 2DM's MESHNAME and a fort.14's
    title hold the input's path, which differs from one clone to the next."""
    with open(path, "rb") as f:
        data = f.read()
    for real, name in ((os.path.realpath(SHARED), b"$SHARED"), (SHARED, b"$SHARED"), (ROOT, b"$ROOT")):
        data = data.replace(real.encode(), name)
    return hashlib.sha256(data).hexdigest()[:16]


def run_case(fdrmesh, name, args, outs, tmp):
    base = os.path.join(tmp, name)
    cmd = [fdrmesh, "mesh"] + args + ["-q"]
    for s in outs:
        cmd += ["-o", base + s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("%s: exit %d\n%s%s" % (" ".join(cmd), p.returncode, p.stdout, p.stderr))
    files = [base + s for s in outs]
    if ".node" in outs:
        files.append(base + ".ele")
    return {os.path.basename(f)[len(name):]: digest(f) for f in files}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("fdrmesh")
    ap.add_argument("--set", default="quick", choices=["quick", "regions", "all"])
    ap.add_argument("--update", action="store_true", help="write the hashes instead of comparing")
    ap.add_argument("--only", action="append", help="run only this case (repeatable)")
    a = ap.parse_args()
    pins = json.load(open(PINS)) if os.path.exists(PINS) else {}
    failed = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, (group, args, outs) in CASES.items():
            if a.only and name not in a.only:
                continue
            if not a.only and a.set != "all" and group != a.set:
                continue
            if not os.path.exists(args[0]):
                print("skip %s: %s not present" % (name, args[0]))
                continue
            got = run_case(a.fdrmesh, name, args, outs, tmp)
            if a.update:
                pins[name] = got
                print("pinned %s %s" % (name, got))
            elif name not in pins:
                failed.append(name)
                print("FAIL %s: no pinned hashes (run with --update)" % name)
            elif pins[name] != got:
                failed.append(name)
                print("FAIL %s: written %s, pinned %s" % (name, got, pins[name]))
            else:
                print("ok %s" % name)
    if a.update:
        with open(PINS, "w") as f:
            json.dump(pins, f, indent=1, sort_keys=True)
            f.write("\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
