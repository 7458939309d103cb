#!/usr/bin/python3
"""Draw a global mesh (fort.14 or hgrid.ll in lon/lat, as fdrmesh --global writes them) in an
orthographic view of the globe and, beside it, a lon/lat window (a coast zoom) to one PNG.

Usage: plot_globe.py MESH.14 -o OUT.png [--centre=LON,LAT] [--zoom=XMIN,YMIN,XMAX,YMAX] [--colors N]
"""
import argparse
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402


def read_lonlat_mesh(path):
    """Nodes (lon, lat, depth), triangles (0-based) and land boundary node lists of a fort.14/hgrid."""
    with open(path) as f:
        f.readline()
        ne, nn = (int(t) for t in f.readline().split()[:2])
        xy = np.empty((nn, 2))
        for i in range(nn):
            t = f.readline().split()
            xy[i] = float(t[1]), float(t[2])
        tri = np.empty((ne, 3), dtype=np.int64)
        for k in range(ne):
            t = f.readline().split()
            tri[k] = int(t[2]) - 1, int(t[3]) - 1, int(t[4]) - 1
        nope = int(f.readline().split()[0])
        f.readline()
        for _ in range(nope):
            n = int(f.readline().split()[0])
            for _ in range(n):
                f.readline()
        nbou = int(f.readline().split()[0])
        f.readline()
        coast = []
        for _ in range(nbou):
            n = int(f.readline().split()[0])
            coast.append([int(f.readline().split()[0]) - 1 for _ in range(n)])
    return xy, tri, coast


def orthographic(lon, lat, lon0, lat0):
    """Unit-disc coordinates of the orthographic view centred at (lon0, lat0) and visibility."""
    l, p = np.radians(lon - lon0), np.radians(lat)
    p0 = math.radians(lat0)
    x = np.cos(p) * np.sin(l)
    y = math.cos(p0) * np.sin(p) - math.sin(p0) * np.cos(p) * np.cos(l)
    vis = math.sin(p0) * np.sin(p) + math.cos(p0) * np.cos(p) * np.cos(l) > 0
    return x, y, vis


def edges_of(tri):
    e = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    e.sort(axis=1)
    return np.unique(e, axis=0)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mesh")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--centre", default="-30,20", help="LON,LAT the globe is seen from")
    ap.add_argument("--zoom", default="-10,48,12,62", help="lon/lat window XMIN,YMIN,XMAX,YMAX")
    ap.add_argument("--dpi", type=int, default=150)
    ap.add_argument("--colors", type=int, default=0, help="quantize the PNG to this many colours (0: no)")
    a = ap.parse_args()
    xy, tri, coast = read_lonlat_mesh(a.mesh)
    lon0, lat0 = (float(v) for v in a.centre.split(","))
    z = [float(v) for v in a.zoom.split(",")]
    fig, (g, w) = plt.subplots(1, 2, figsize=(16, 8))
    e = edges_of(tri)
    x, y, vis = orthographic(xy[:, 0], xy[:, 1], lon0, lat0)
    keep = vis[e[:, 0]] & vis[e[:, 1]]
    seg = np.stack([np.column_stack([x[e[keep, 0]], y[e[keep, 0]]]), np.column_stack([x[e[keep, 1]], y[e[keep, 1]]])], axis=1)
    g.add_collection(LineCollection(seg, linewidths=0.1, colors="#1f77b4"))
    for ring in coast:
        r = np.array(ring)
        ok = vis[r[:-1]] & vis[r[1:]]
        s = np.stack([np.column_stack([x[r[:-1]], y[r[:-1]]]), np.column_stack([x[r[1:]], y[r[1:]]])], axis=1)[ok]
        g.add_collection(LineCollection(s, linewidths=0.4, colors="#d62728"))
    g.add_patch(plt.Circle((0, 0), 1, fill=False, lw=0.8))
    g.set_xlim(-1.02, 1.02)
    g.set_ylim(-1.02, 1.02)
    g.set_aspect("equal")
    g.axis("off")
    g.set_title(f"{len(tri)} triangles, orthographic view from ({lon0:g}, {lat0:g})")
    # The window: edges whose both ends lie in it, in lon/lat with the parallel's cos as aspect.
    inside = (xy[:, 0] >= z[0]) & (xy[:, 0] <= z[2]) & (xy[:, 1] >= z[1]) & (xy[:, 1] <= z[3])
    k = inside[e[:, 0]] | inside[e[:, 1]]
    k &= np.abs(xy[e[:, 0], 0] - xy[e[:, 1], 0]) < 180
    seg = np.stack([xy[e[k, 0]], xy[e[k, 1]]], axis=1)
    w.add_collection(LineCollection(seg, linewidths=0.2, colors="#1f77b4"))
    for ring in coast:
        r = np.array(ring)
        s = np.stack([xy[r[:-1]], xy[r[1:]]], axis=1)
        s = s[np.abs(s[:, 0, 0] - s[:, 1, 0]) < 180]
        w.add_collection(LineCollection(s, linewidths=0.6, colors="#d62728"))
    w.set_xlim(z[0], z[2])
    w.set_ylim(z[1], z[3])
    w.set_aspect(1 / math.cos(math.radians(0.5 * (z[1] + z[3]))))
    w.set_title(f"lon/lat window {a.zoom} (coast red)")
    fig.tight_layout()
    fig.savefig(a.output, dpi=a.dpi)
    if a.colors > 0:  # a palette PNG: a fraction of the size for line drawings
        from PIL import Image
        Image.open(a.output).convert("RGB").quantize(colors=a.colors).save(a.output, optimize=True)


if __name__ == "__main__":
    main()
