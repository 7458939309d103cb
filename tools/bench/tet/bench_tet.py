#!/usr/bin/env python3
"""3D benchmark: fdrmesh, TetGen 1.5 and CGAL Mesh_3 on the same inputs at about the same
tetrahedron count, each run as a measured child process (wall clock, user+sys, peak RSS).

fdrmesh's count at spacing H is the target. TetGen gets the volume bound of a regular tetrahedron
of edge H, then one correction step from its count; CGAL gets cell_size = H, then one correction
step of H by the cube root of the count ratio. A row more than 10 % off the target is marked.

usage: tools/bench/tet/bench_tet.py [--build build] [--size quick|large]
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))

# (name, .poly under testdata/3d, H for quick, H for large)
INPUTS = [
    ("cube10", "cube10.poly", 0.5, 0.165),
    ("box_cavity", "box_cavity.poly", 0.15, 0.05),
]


def run_child(args, cwd):
    """Runs args with output captured to a file; returns (wall s, user+sys s, peak MiB, output text)."""
    log = os.path.join(cwd, "child.log")
    with open(log, "w") as out:
        t0 = time.monotonic()
        proc = subprocess.Popen(args, cwd=cwd, stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
        _, status, ru = os.wait4(proc.pid, 0)
        wall = time.monotonic() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
    with open(log) as f:
        text = f.read()
    if proc.returncode != 0:
        sys.exit(f"bench_tet: {' '.join(args)} exited with {proc.returncode}:\n{text[-2000:]}")
    return wall, ru.ru_utime + ru.ru_stime, ru.ru_maxrss / 1024.0, text


def read_poly(path):
    """Vertices and facet polygons of a TetGen .poly with one polygon per facet (the test inputs)."""
    lines = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].split()
            if line:
                lines.append(line)
    nv = int(lines[0][0])
    verts = {int(l[0]): tuple(float(x) for x in l[1:4]) for l in lines[1:1 + nv]}
    first = min(verts)
    nf = int(lines[1 + nv][0])
    polys, i = [], 2 + nv
    for _ in range(nf):
        npoly = int(lines[i][0])
        for k in range(npoly):
            ids = [int(x) - first for x in lines[i + 1 + k][1:]]
            polys.append(ids)
        i += 1 + npoly
    return [verts[k] for k in sorted(verts)], polys


def write_off(poly_path, off_path):
    """The .poly's facets as a triangle surface (fan of each convex polygon) for CGAL."""
    verts, polys = read_poly(poly_path)
    tris = [(p[0], p[j], p[j + 1]) for p in polys for j in range(1, len(p) - 1)]
    with open(off_path, "w") as f:
        f.write(f"OFF\n{len(verts)} {len(tris)} 0\n")
        for v in verts:
            f.write("%r %r %r\n" % v)
        for t in tris:
            f.write("3 %d %d %d\n" % t)


def fdrmesh_row(binary, poly, h, tmp):
    wall, cpu, rss, _ = run_child([binary, "mesh", poly, "--spacing", repr(h), "-o", "out.vtu", "-q"], tmp)
    with open(os.path.join(tmp, "out.vtu"), "rb") as f:
        head = f.read(4096).decode("latin-1")
    tets = int(re.search(r'NumberOfCells="(\d+)"', head).group(1))
    return {"tool": "fdrmesh", "param": f"spacing {h:g}", "tets": tets, "wall": wall, "cpu": cpu, "rss": rss}


def tetgen_once(poly, vol, tmp):
    local = os.path.join(tmp, "in.poly")
    shutil.copy(poly, local)
    wall, cpu, rss, _ = run_child(["tetgen", "-pq2.0a%.6gQ" % vol, "in.poly"], tmp)
    with open(os.path.join(tmp, "in.1.ele")) as f:
        tets = int(f.readline().split()[0])
    return {"tool": "tetgen -pq2.0aV", "param": "V %.4g" % vol, "tets": tets, "wall": wall, "cpu": cpu, "rss": rss}


def tetgen_row(poly, h, target, tmp):
    vol = h ** 3 / (6 * math.sqrt(2))
    row = tetgen_once(poly, vol, tmp)
    return tetgen_once(poly, vol * row["tets"] / target, tmp)


def cgal_once(binary, off, h, mode, tmp):
    wall, cpu, rss, text = run_child([binary, off, repr(h), mode], tmp)
    tets = int(re.search(r"tetrahedra (\d+)", text).group(1))
    name = "cgal mesh_3" if mode == "plain" else "cgal mesh_3+perturb+exude"
    return {"tool": name, "param": "cell_size %.4g" % h, "tets": tets, "wall": wall, "cpu": cpu, "rss": rss}


def cgal_rows(binary, off, h, target, tmp):
    first = cgal_once(binary, off, h, "plain", tmp)
    h2 = h * (first["tets"] / target) ** (1.0 / 3.0)
    return [first, cgal_once(binary, off, h2, "plain", tmp), cgal_once(binary, off, h2, "optimise", tmp)]


def format_row(name, r, target):
    off = r["tets"] / target - 1
    mark = "" if abs(off) <= 0.10 else "  (count off by more than 10 %)"
    return (f"{name:<11} {r['tool']:<26} {r['param']:<18} {r['tets']:>9} tets ({off:+6.1%})  "
            f"wall {r['wall']:7.2f} s  user+sys {r['cpu']:7.2f} s  peak {r['rss']:7.1f} MiB  "
            f"{r['rss'] * 1048576 / r['tets']:7.0f} B/tet{mark}")


def programs(build, who):
    """fdrmesh and cgal_mesh3_bench of the build folder `build` (an absolute path or one relative to
    the checkout); exits naming `who` when one of them, or tetgen, is missing."""
    build = os.path.join(ROOT, build)
    fdr = os.path.join(build, "bin", "fdrmesh")
    cgal = os.path.join(build, "tools", "bench", "tet", "cgal_mesh3_bench")
    for exe in (fdr, cgal):
        if not os.access(exe, os.X_OK):
            sys.exit(f"{who}: {exe} not built")
    if not shutil.which("tetgen"):
        sys.exit(f"{who}: tetgen not on PATH (Debian package tetgen)")
    return fdr, cgal


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--size", choices=["quick", "large"], default="quick")
    args = ap.parse_args()
    fdr, cgal = programs(args.build, "bench_tet")
    print("3D benchmark: tetrahedra at about fdrmesh's count; wall = whole process, user+sys and peak RSS")
    print("  (ru_maxrss) from wait4 of each child, B/tet = peak / tetrahedra; TetGen and CGAL take one")
    print("  correction step from a first run (the first CGAL run, cell_size = H, is shown too)")
    for name, file, hq, hl in INPUTS:
        h = hq if args.size == "quick" else hl
        poly = os.path.join(ROOT, "testdata", "3d", file)
        with tempfile.TemporaryDirectory(prefix="bench_tet_") as tmp:
            off = os.path.join(tmp, "in.off")
            write_off(poly, off)
            fr = fdrmesh_row(fdr, poly, h, tmp)
            rows = [fr, tetgen_row(poly, h, fr["tets"], tmp)] + cgal_rows(cgal, off, h, fr["tets"], tmp)
            for r in rows:
                print(format_row(name, r, fr["tets"]), flush=True)


if __name__ == "__main__":
    main()
