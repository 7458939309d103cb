#!/usr/bin/python3
"""Draw a triangle mesh (fdrmesh GPKG, Triangle .node/.ele, SMS .2dm) to a PNG, colored per triangle."""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fdrplot  # noqa: E402

KIND_COLORS = ["#000000", "#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#8c564b"]


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("mesh", help="mesh file: .gpkg, .2dm, or .node (with .ele next to it)")
    p.add_argument("-o", "--output", required=True, help="PNG to write")
    p.add_argument("--ele", help=".ele file when it is not <stem>.ele")
    p.add_argument("--color", choices=["r_over_f", "min_angle", "depth", "none"], default="min_angle",
                   help="per-triangle color (default min_angle)")
    p.add_argument("--spacing", help="spacing expression f(x,y) as given to fdrmesh (e.g. paper-f1, "
                   "'2*paper-f1', '0.1+0.05*abs(x)'); needed for r_over_f on non-GPKG inputs")
    p.add_argument("--origin", default="0,0",
                   help="X,Y of the mesher's local frame: f is evaluated at (x-X, y-Y) (default 0,0)")
    p.add_argument("--bound", type=float, help="B: draw the R/f(c) colorbar with a mark at B")
    p.add_argument("--size", type=float, default=8.0, help="figure size in inches (default 8)")
    p.add_argument("--dpi", type=int, default=150, help="resolution (default 150)")
    p.add_argument("--title", help="title prefix (default: the file name)")
    p.add_argument("--edges", choices=["auto", "on", "off"], default="auto",
                   help="draw every mesh edge (auto: only below 200000 triangles)")
    return p.parse_args(argv)


def shifted_spacing(expr, origin):
    if not expr:
        return None
    f = fdrplot.spacing_function(expr)
    ox, oy = (float(v) for v in origin.split(","))
    return lambda x, y: f(np.asarray(x) - ox, np.asarray(y) - oy)


def boundary_edges(tris):
    """Edges used by exactly one triangle: the outer boundary and hole boundaries."""
    e = np.sort(np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(e, axis=0, return_counts=True)
    return uniq[count == 1]


def draw(mesh, args):
    f = shifted_spacing(args.spacing, args.origin)
    angles, _, _, _ = fdrplot.triangle_metrics(mesh)
    nt = len(mesh.tris)
    fig, ax = plt.subplots(figsize=(args.size, args.size), dpi=args.dpi)
    tri = Triangulation(mesh.xy[:, 0], mesh.xy[:, 1], mesh.tris)

    values, label, cmap, vmin, vmax = None, None, None, None, None
    if args.color == "min_angle":
        values, label, cmap, vmin, vmax = angles.min(1), "minimum angle (deg)", "RdYlGn", 0.0, 60.0
    elif args.color == "r_over_f":
        values = fdrplot.r_over_f(mesh, f)
        if values is None:
            raise fdrplot.MeshError(f"{mesh.source}: --color r_over_f needs --spacing (no R_over_f field)")
        label, cmap, vmin = "R / f(c)", "viridis", 0.0
        finite = values[np.isfinite(values)]
        vmax = max(float(finite.max()) if finite.size else 1.0, args.bound or 0.0)
    elif args.color == "depth":
        if mesh.z is None:
            raise fdrplot.MeshError(f"{mesh.source}: --color depth needs z values (none in the file)")
        values, label, cmap = mesh.z[mesh.tris].mean(1), "z (mean of corners)", "viridis"
        vmin, vmax = float(np.nanmin(values)), float(np.nanmax(values))

    draw_edges = args.edges == "on" or (args.edges == "auto" and nt < 200000)
    lw = max(0.05, min(0.6, 60.0 / np.sqrt(max(nt, 1))))
    if values is not None:
        pc = ax.tripcolor(tri, facecolors=np.ma.masked_invalid(values), cmap=cmap, vmin=vmin, vmax=vmax,
                          edgecolors="none")
        cb = fig.colorbar(pc, ax=ax, shrink=0.8, pad=0.02)
        cb.set_label(label)
        if args.color == "r_over_f" and args.bound:
            cb.ax.axhline(args.bound, color="red", lw=1.5)
    if draw_edges:
        ax.triplot(tri, color="0.25" if values is not None else "0.1", lw=lw)

    # Boundary: hull and holes thin black; constrained edges thicker, one color per kind.
    be = boundary_edges(mesh.tris)
    if len(be):
        ax.add_collection(LineCollection(mesh.xy[be], colors="black", linewidths=1.0, zorder=3))
    kinds = sorted({str(k) for _, _, k in mesh.segments})
    for n, kind in enumerate(kinds):
        segs = [(mesh.xy[a], mesh.xy[b]) for a, b, k in mesh.segments if str(k) == kind]
        ax.add_collection(LineCollection(segs, colors=KIND_COLORS[n % len(KIND_COLORS)], linewidths=2.2,
                                         zorder=4, label=f"constrained: {kind}"))
    if len(kinds) > 1:
        ax.legend(loc="upper right", fontsize="small")

    amin = float(angles.min()) if nt else float("nan")
    amax = float(angles.max()) if nt else float("nan")
    name = args.title or os.path.basename(mesh.source)
    ax.set_title(f"{name}\nN = {len(mesh.xy)} vertices, {nt} triangles\n"
                 f"\u03b8min = {amin:.2f}\u00b0, \u03b8max = {amax:.2f}\u00b0", fontsize="medium")
    ax.set_aspect("equal")
    ax.autoscale_view()
    fig.tight_layout()
    fig.savefig(args.output, dpi=args.dpi)
    plt.close(fig)


def main(argv=None):
    args = parse_args(argv)
    try:
        mesh = fdrplot.read_mesh(args.mesh, args.ele)
        if len(mesh.tris) == 0:
            raise fdrplot.MeshError(f"{args.mesh}: the mesh has no triangles")
        draw(mesh, args)
    except (fdrplot.MeshError, OSError) as e:
        print(f"ERROR: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
