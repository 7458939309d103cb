#!/usr/bin/env python3
"""Terrain benchmark: about a million tetrahedra from GIS layers (the Luxembourg DEM under its
border polygon, base -500 m, no horizons) against the same count on the cube (bench_tet.py's
cube10 case), each the whole fdrmesh process measured as a child (wall clock, user+sys, peak RSS).
The target: the GIS run within 2x the cube's time. With --horizons a third row: the whole
country with the two synthetic horizons of testdata/terrain (--hmin 1000 --hmax 4000
--vertical-tol 20, the default --min-thickness), whose thin layers set the spacing.

usage: tools/bench/tet/bench_terrain.py [--build build] [--size quick|large] [--horizons]
"""
import argparse
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_tet import ROOT, run_child  # noqa: E402

LUX = os.path.join(ROOT, "testdata", "luxembourg")
# (hmin, hmax) of the terrain run and the cube's spacing, per size: about the same count.
SIZES = {"quick": ((400, 800), 0.5), "large": ((140, 280), 0.165)}


def count_tets(vtu):
    with open(vtu, "rb") as f:
        head = f.read(4096).decode("latin-1")
    return int(re.search(r'NumberOfCells="(\d+)"', head).group(1))


def terrain_command(binary, hmin, hmax):
    return [binary, "mesh", os.path.join(LUX, "lux.shp"), "--dem", os.path.join(LUX, "elev.tif"), "--base", "-500",
            "--hmin", repr(hmin), "--hmax", repr(hmax), "-o", "out.vtu", "-q"]


def horizons_command(binary):
    terrain = os.path.join(ROOT, "testdata", "terrain")
    return [binary, "mesh", os.path.join(LUX, "lux.shp"), "--dem", os.path.join(LUX, "elev.tif"), "--base", "-500",
            "--horizon", os.path.join(terrain, "lux_h1.tif"), "--horizon", os.path.join(terrain, "lux_h2.tif"),
            "--hmin", "1000", "--hmax", "4000", "--vertical-tol", "20", "-o", "out.vtu", "-q"]


def cube_command(binary, h):
    return [binary, "mesh", os.path.join(ROOT, "testdata", "3d", "cube10.poly"), "--spacing", repr(h), "-o", "out.vtu",
            "-q"]


def measure(name, args):
    with tempfile.TemporaryDirectory(prefix="bench_terrain_") as tmp:
        wall, cpu, rss, _ = run_child(args, tmp)
        return {"name": name, "tets": count_tets(os.path.join(tmp, "out.vtu")), "wall": wall, "cpu": cpu, "rss": rss,
                "command": " ".join(os.path.relpath(a, ROOT) if os.path.isabs(a) else a for a in args[1:])}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--size", choices=sorted(SIZES), default="quick")
    ap.add_argument("--horizons", action="store_true", help="also the whole country with two horizons (minutes)")
    args = ap.parse_args()
    binary = os.path.join(ROOT, args.build, "bin", "fdrmesh")
    if not os.access(binary, os.X_OK):
        sys.exit(f"bench_terrain: {binary} not built")
    (hmin, hmax), h = SIZES[args.size]
    rows = [measure("cube10", cube_command(binary, h)), measure("luxembourg", terrain_command(binary, hmin, hmax))]
    if args.horizons:
        rows.append(measure("lux+2 horiz", horizons_command(binary)))
    print("Terrain benchmark: the same fdrmesh process on GIS layers (DEM, border, base -500 m) and on the cube;")
    print("  wall = whole process, user+sys and peak RSS (ru_maxrss) from wait4 of each child")
    for r in rows:
        print(f"{r['name']:<11} {r['tets']:>9} tets  wall {r['wall']:8.2f} s  user+sys {r['cpu']:8.2f} s  "
              f"peak {r['rss']:7.1f} MiB  {r['cpu'] * 1e6 / r['tets']:7.1f} us/tet  (fdrmesh {r['command']})")
    cube, gis = rows[:2]
    per_tet = (gis["cpu"] / gis["tets"]) / (cube["cpu"] / cube["tets"])
    print(f"GIS / cube: {gis['cpu'] / cube['cpu']:.2f}x user+sys, {per_tet:.2f}x per tetrahedron "
          f"(target <= 2x), peak {gis['rss'] / cube['rss']:.2f}x")


if __name__ == "__main__":
    main()
