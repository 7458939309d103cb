#!/usr/bin/env python3
"""Dihedral angles of fdrmesh (with and without sliver removal), TetGen 1.5 (its default mesh
optimisation -O2/7, none -O0, and a 10-degree dihedral bound -q2.0/10) and CGAL Mesh_3 (plain
and perturb + exude) on bench_tet.py's inputs at
about fdrmesh's tetrahedron count: the smallest dihedral angle and the tetrahedra whose smallest
angle is under 5, 10 and 15 degrees, with each run's user+sys time.

usage: tools/bench/tet/dihedral_compare.py [--build build] [--size quick|large]
"""
import argparse
import math
import os
import re
import shutil
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import bench_tet  # noqa: E402

sys.path.insert(0, os.path.join(bench_tet.ROOT, "tools", "verify"))
import tets as verify_tets  # noqa: E402


def min_dihedral_deg(points, tets):
    """Each tetrahedron's smallest dihedral angle in degrees (the checker's six angles; either
    orientation), for an (n, 3) array of points and an (m, 4) array of tetrahedra."""
    return verify_tets.dihedral_angles(points, tets).min(axis=1)


def summary(angles):
    return {"tets": int(len(angles)), "min": float(angles.min()) if len(angles) else 0.0,
            "under5": int((angles < 5).sum()), "under10": int((angles < 10).sum()), "under15": int((angles < 15).sum())}


def read_tetgen(stem):
    """Points and 0-based tetrahedra of TetGen's STEM.node / STEM.ele."""
    def rows(path):
        with open(path) as f:
            lines = [l.split("#", 1)[0].split() for l in f]
        lines = [l for l in lines if l]
        n = int(lines[0][0])
        return lines[1:1 + n]
    nodes = rows(stem + ".node")
    index = {int(r[0]): i for i, r in enumerate(nodes)}
    pts = np.array([[float(x) for x in r[1:4]] for r in nodes])
    tets = np.array([[index[int(x)] for x in r[1:5]] for r in rows(stem + ".ele")])
    return pts, tets


def fdrmesh_run(binary, poly, h, extra, tmp):
    _, cpu, _, _ = bench_tet.run_child([binary, "mesh", poly, "--spacing", repr(h), "-o", "d.vtu", "-q", *extra], tmp)
    pts, tets, _ = verify_tets.read_vtu(os.path.join(tmp, "d.vtu"))
    return dict(summary(min_dihedral_deg(pts, tets)), cpu=cpu)


def tetgen_run(poly, vol, opt, tmp, quality="2.0"):
    shutil.copy(poly, os.path.join(tmp, "in.poly"))
    _, cpu, _, _ = bench_tet.run_child(["tetgen", "-pq%sa%.6g%sQ" % (quality, vol, opt), "in.poly"], tmp)
    pts, tets = read_tetgen(os.path.join(tmp, "in.1"))
    return dict(summary(min_dihedral_deg(pts, tets)), cpu=cpu)


def cgal_run(binary, off, h, mode, tmp):
    _, cpu, _, text = bench_tet.run_child([binary, off, repr(h), mode], tmp)
    m = re.search(r"tetrahedra (\d+)\s+dihedral min (\S+) under5 (\d+) under10 (\d+) under15 (\d+)", text)
    return {"tets": int(m.group(1)), "min": float(m.group(2)), "under5": int(m.group(3)), "under10": int(m.group(4)),
            "under15": int(m.group(5)), "cpu": cpu}


def format_row(name, tool, r):
    return (f"{name:<11} {tool:<28} {r['tets']:>9} tets  min {r['min']:6.2f} deg  under 5: {r['under5']:>6}  "
            f"under 10: {r['under10']:>6}  under 15: {r['under15']:>6}  user+sys {r['cpu']:7.2f} s")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(bench_tet.ROOT, "build"))
    ap.add_argument("--size", choices=["quick", "large"], default="quick")
    args = ap.parse_args()
    fdr, cgal = bench_tet.programs(args.build, "dihedral_compare")
    print("smallest dihedral angle per tetrahedron: the minimum and the tetrahedra under 5, 10, 15 degrees")
    for name, file, hq, hl in bench_tet.INPUTS:
        h = hq if args.size == "quick" else hl
        poly = os.path.join(bench_tet.ROOT, "testdata", "3d", file)
        with tempfile.TemporaryDirectory(prefix="dihedral_") as tmp:
            off = os.path.join(tmp, "in.off")
            bench_tet.write_off(poly, off)
            on = fdrmesh_run(fdr, poly, h, [], tmp)
            print(format_row(name, "fdrmesh", on), flush=True)
            print(format_row(name, "fdrmesh --no-sliver-removal", fdrmesh_run(fdr, poly, h, ["--no-sliver-removal"], tmp)),
                  flush=True)
            target = on["tets"]
            vol = h ** 3 / (6 * math.sqrt(2))
            vol *= tetgen_run(poly, vol, "", tmp)["tets"] / target  # one correction step, as bench_tet.py
            for q, opt, tool in (("2.0", "", "tetgen -pq2.0aV (-O2/7)"), ("2.0", "O0", "tetgen -pq2.0aVO0"),
                                 ("2.0/10", "", "tetgen -pq2.0/10aV (-O2/7)")):
                print(format_row(name, tool, tetgen_run(poly, vol, opt, tmp, q)), flush=True)
            h2 = h * (cgal_run(cgal, off, h, "plain", tmp)["tets"] / target) ** (1.0 / 3.0)
            for mode, tool in (("plain", "cgal mesh_3"), ("optimise", "cgal mesh_3+perturb+exude")):
                print(format_row(name, tool, cgal_run(cgal, off, h2, mode, tmp)), flush=True)


if __name__ == "__main__":
    main()
