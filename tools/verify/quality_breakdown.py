#!/usr/bin/python3
"""Where does a mesh's mean quality go? Reads the `nodes` (f) and `triangles` (n1..n3, R_over_f)
layers of an fdrmesh GeoPackage and splits the quality deficit (the sum of 1 - q over the
triangles, q the mean-ratio quality, so the shares add up to 100 % of 1 - mean q) by:
  * the triangle's distance to the mesh boundary in rings (0: a vertex on the boundary),
  * whether it has an edge on the boundary, and that edge's length over f,
  * at its boundary vertices, how far the mean angle of their fans is from 60 degrees, and how far
    their number of triangles is from the one that would bring it nearest 60,
  * the grading of f over its three vertices (max f / min f),
  * its R/f(c) (near B the refinement bound limits the shape; far below it the triangle was
    shaped by the input's vertices, not by refinement),
  * the degree of its worst vertex (|degree - 6|),
  * its quality.

  quality_breakdown.py OUT.gpkg [--json FILE]
"""
import json
import sys
from collections import defaultdict

import numpy as np


def read(path):
    """(xy, f, tv, rf) from an fdrmesh GeoPackage: node positions and f, triangle corners as node
    rows, each triangle's R/f(c)."""
    from osgeo import ogr
    ogr.UseExceptions()
    ds = ogr.Open(path)
    ids, xy, f = [], [], []
    for ft in ds.GetLayerByName("nodes"):
        g = ft.GetGeometryRef()
        ids.append(ft.GetField("id"))
        xy.append((g.GetX(), g.GetY()))
        f.append(ft.GetField("f"))
    row = {int(i): k for k, i in enumerate(ids)}
    tv, rf = [], []
    for ft in ds.GetLayerByName("triangles"):
        tv.append((row[ft.GetField("n1")], row[ft.GetField("n2")], row[ft.GetField("n3")]))
        rf.append(ft.GetField("R_over_f"))
    return np.array(xy, dtype=float), np.array(f, dtype=float), np.array(tv, dtype=int), np.array(rf, dtype=float)


def quality(xy, tv):
    """Mean-ratio quality 4 sqrt(3) A / (sum of squared edges) of each triangle."""
    a, b, c = xy[tv[:, 0]], xy[tv[:, 1]], xy[tv[:, 2]]
    area = 0.5 * np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    l2 = ((b - c) ** 2).sum(1) + ((c - a) ** 2).sum(1) + ((a - b) ** 2).sum(1)
    return 4 * np.sqrt(3) * area / l2


def classes(xy, f, tv, max_ring=8):
    """Per triangle: ring from the boundary, boundary edge length over f (NaN: none), f grading,
    worst |degree - 6|."""
    n, nv = len(tv), len(xy)
    count = defaultdict(int)
    for t in tv:
        for k in range(3):
            u, w = int(t[k]), int(t[(k + 1) % 3])
            count[(min(u, w), max(u, w))] += 1
    on_bnd = np.zeros(nv, bool)
    deg = np.zeros(nv, int)
    adj = defaultdict(list)
    for (u, w), cnt in count.items():
        deg[u] += 1
        deg[w] += 1
        adj[u].append(w)
        adj[w].append(u)
        if cnt == 1:
            on_bnd[u] = on_bnd[w] = True
    dist = np.full(nv, max_ring + 1)
    front = list(np.nonzero(on_bnd)[0])
    dist[front] = 0
    for d in range(1, max_ring + 1):
        nxt = []
        for u in front:
            for w in adj[u]:
                if dist[w] > d:
                    dist[w] = d
                    nxt.append(w)
        front = nxt
    blen = np.full(n, np.nan)  # the shorter boundary edge over the mean f at its ends
    for i, t in enumerate(tv):
        for k in range(3):
            u, w = int(t[k]), int(t[(k + 1) % 3])
            if count[(min(u, w), max(u, w))] == 1:
                r = np.sqrt(((xy[u] - xy[w]) ** 2).sum()) / (0.5 * (f[u] + f[w]))
                blen[i] = r if np.isnan(blen[i]) else min(blen[i], r)
    # At each boundary vertex, its angle in the mesh shared by its triangles: how far the mean
    # from 60 degrees (NaN: not on the boundary). Far from 60, no smoothing of the interior can
    # make its fan's triangles equilateral.
    a, b, c = xy[tv[:, 0]], xy[tv[:, 1]], xy[tv[:, 2]]
    ang_sum = np.zeros(nv)
    fan = np.zeros(nv, int)
    for k, (p, q, r) in enumerate(((a, b, c), (b, c, a), (c, a, b))):
        u, w = q - p, r - p
        ang = np.degrees(np.arccos(np.clip((u * w).sum(1) / np.sqrt((u * u).sum(1) * (w * w).sum(1)), -1, 1)))
        np.add.at(ang_sum, tv[:, k], ang)
        np.add.at(fan, tv[:, k], 1)
    off = np.where(on_bnd, np.abs(ang_sum / np.maximum(fan, 1) - 60.0), np.nan)
    # The number of triangles that would bring the fan's mean angle nearest 60 degrees; a fan with
    # another number has a topology (vertex count near the coast) smoothing cannot change.
    best = np.maximum(1, np.round(ang_sum / 60.0)).astype(int)
    fan_extra = np.where(on_bnd, np.abs(fan - best), -1)
    fan_count = fan_extra[tv].max(1).astype(float)
    fan_count[fan_count < 0] = np.nan
    fan_off = np.nanmax(np.where(on_bnd[tv], off[tv], -1.0), axis=1)
    fan_off[fan_off < 0] = np.nan
    return {"ring": dist[tv].min(1), "boundary_edge_over_f": blen, "fan_angle_off_60": fan_off,
            "fan_count_off_best": fan_count,
            "f_grading": f[tv].max(1) / np.maximum(f[tv].min(1), 1e-300),
            "worst_degree_off": np.abs(deg[tv] - 6).max(1)}


def breakdown(xy, f, tv, rf):
    """The tables: {name: [{class, pct_tri, mean_q, pct_deficit}]} and the mean quality."""
    q = quality(xy, tv)
    c = classes(xy, f, tv)
    deficit = 1 - q
    total = deficit.sum()
    out = {"triangles": len(tv), "mean_q": float(q.mean()), "tables": {}}

    def table(name, labels, masks):
        rows = []
        for lab, m in zip(labels, masks):
            if m.any():
                rows.append({"class": lab, "pct_tri": float(100 * m.mean()), "mean_q": float(q[m].mean()),
                             "pct_deficit": float(100 * deficit[m].sum() / total) if total > 0 else 0.0})
        out["tables"][name] = rows

    def binned(name, x, edges):
        table(name, ["%.2f-%.2f" % (edges[k], edges[k + 1]) for k in range(len(edges) - 1)],
              [(x >= edges[k]) & (x < edges[k + 1]) for k in range(len(edges) - 1)])

    ring = c["ring"]
    table("rings from boundary", ["ring %d" % k for k in range(6)] + ["ring 6+"],
          [ring == k for k in range(6)] + [ring >= 6])
    bl = c["boundary_edge_over_f"]
    table("boundary edge", ["shorter than f/2", "other", "none"], [bl < 0.5, bl >= 0.5, np.isnan(bl)])
    binned("boundary edge / f", bl, [0, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, np.inf])
    binned("boundary fan |mean angle - 60|", c["fan_angle_off_60"], [0, 5, 10, 15, 20, 30, np.inf])
    fc = c["fan_count_off_best"]
    table("boundary fan triangles vs best", ["best", "1 off", "2+ off"], [fc == 0, fc == 1, fc >= 2])
    binned("f grading max/min", c["f_grading"], [1.0, 1.05, 1.1, 1.2, 1.4, 2.0, np.inf])
    binned("R/f(c)", rf, [0, 0.5, 0.7, 0.8, 0.9, 0.95, 1.0, np.inf])
    wd = c["worst_degree_off"]
    table("worst |degree-6|", ["0", "1", "2", "3", "4+"], [wd == 0, wd == 1, wd == 2, wd == 3, wd >= 4])
    binned("quality", q, [0, 0.6, 0.8, 0.9, 0.95, 0.98, 1.01])
    return out


def main():
    out = breakdown(*read(sys.argv[1]))
    print("%d triangles, mean q %.4f" % (out["triangles"], out["mean_q"]))
    for name, rows in out["tables"].items():
        print("-- " + name)
        print("%18s %7s %7s %9s" % ("class", "tri %", "mean q", "deficit %"))
        for r in rows:
            print("%18s %7.2f %7.4f %9.2f" % (r["class"], r["pct_tri"], r["mean_q"], r["pct_deficit"]))
    if "--json" in sys.argv:
        with open(sys.argv[sys.argv.index("--json") + 1], "w") as fh:
            json.dump(out, fh, indent=1)


if __name__ == "__main__":
    main()
