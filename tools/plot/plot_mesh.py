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
from matplotlib.ticker import MaxNLocator  # noqa: E402
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
    p.add_argument("--size", type=float, default=8.0, help="figure size in inches (default 8; per panel)")
    p.add_argument("--dpi", type=int, default=150, help="resolution (default 150)")
    p.add_argument("--title", help="title prefix (default: the file name)")
    p.add_argument("--edges", choices=["auto", "on", "off"], default="auto",
                   help="draw every mesh edge (auto: only below 200000 triangles in view)")
    p.add_argument("--bbox", metavar="XMIN,YMIN,XMAX,YMAX",
                   help="draw only this window, in the mesh's coordinates (its CRS)")
    p.add_argument("--bbox-lonlat", metavar="W,S,E,N",
                   help="draw only this window given in degrees (needs the mesh CRS: GPKG, or --crs)")
    p.add_argument("--crs", help="CRS of the mesh coordinates (e.g. EPSG:32618) when the file does not "
                   "store one (2DM, node/ele)")
    p.add_argument("--coast", action="append", default=[], metavar="FILE[:LAYER]",
                   help="overlay the line work of an OGR source (e.g. the input coast), reprojected to "
                   "the mesh CRS; may be repeated")
    p.add_argument("--compare", metavar="MESH",
                   help="a second mesh drawn beside the first in the same window (e.g. before/after)")
    p.add_argument("--compare-title", help="title of the second panel (default: its file name)")
    p.add_argument("--repairs", action="store_true",
                   help="mark the repairs of an fdrmesh GeoPackage (closed water, removed islands, ...)")
    # Values that start with '-' (western longitudes, titles like "--keep-coast") belong to their option.
    argv = list(sys.argv[1:] if argv is None else argv)
    joined, i = [], 0
    while i < len(argv):
        if argv[i] in ("--bbox", "--bbox-lonlat", "--title", "--compare-title") and i + 1 < len(argv):
            joined.append(argv[i] + "=" + argv[i + 1])
            i += 2
        else:
            joined.append(argv[i])
            i += 1
    return p.parse_args(joined)


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


def window_of(mesh, args):
    """The window to draw (xmin, ymin, xmax, ymax) in the mesh's coordinates, or None."""
    if args.bbox and args.bbox_lonlat:
        raise fdrplot.MeshError("give either --bbox or --bbox-lonlat, not both")
    if args.bbox:
        return fdrplot.parse_box(args.bbox, "--bbox")
    if args.bbox_lonlat:
        box = fdrplot.parse_box(args.bbox_lonlat, "--bbox-lonlat")
        return fdrplot.lonlat_box_to_crs(box, mesh.crs_wkt)
    return None


def in_window(p0, p1, box):
    """Mask of segments p0-p1 ((n,2) each) whose bounding box meets the window."""
    if box is None:
        return np.ones(len(p0), dtype=bool)
    lo, hi = np.minimum(p0, p1), np.maximum(p0, p1)
    return (hi[:, 0] >= box[0]) & (lo[:, 0] <= box[2]) & (hi[:, 1] >= box[1]) & (lo[:, 1] <= box[3])


def triangle_values(mesh, args, f, angles):
    """(values, label, cmap, vmin, vmax) of the per-triangle color, values None for --color none."""
    if args.color == "min_angle":
        return angles.min(1), "minimum angle (deg)", "RdYlGn", 0.0, 60.0
    if args.color == "r_over_f":
        values = fdrplot.r_over_f(mesh, f)
        if values is None:
            raise fdrplot.MeshError(f"{mesh.source}: --color r_over_f needs --spacing (no R_over_f field)")
        finite = values[np.isfinite(values)]
        return values, "R / f(c)", "viridis", 0.0, max(float(finite.max()) if finite.size else 1.0, args.bound or 0.0)
    if args.color == "depth":
        if mesh.z is None:
            raise fdrplot.MeshError(f"{mesh.source}: --color depth needs z values (none in the file)")
        values = mesh.z[mesh.tris].mean(1)
        return values, "z (mean of corners)", "viridis", float(np.nanmin(values)), float(np.nanmax(values))
    return None, None, None, None, None


def draw_panel(fig, ax, mesh, args, f, box, coast, title, color_range):
    """One mesh on `ax` (restricted to `box` when given); returns the color mappable or None."""
    angles, _, _, _ = fdrplot.triangle_metrics(mesh)
    nt = len(mesh.tris)
    values, label, cmap, vmin, vmax = triangle_values(mesh, args, f, angles)
    if color_range is not None:
        vmin, vmax = color_range
    p = mesh.xy[mesh.tris]
    lo, hi = p.min(1), p.max(1)
    keep = np.ones(nt, dtype=bool) if box is None else in_window(lo, hi, box)
    tris = mesh.tris[keep]
    nview = int(keep.sum())
    pc = None
    if nview:
        tri = Triangulation(mesh.xy[:, 0], mesh.xy[:, 1], tris)
        if values is not None:
            pc = ax.tripcolor(tri, facecolors=np.ma.masked_invalid(values[keep]), cmap=cmap, vmin=vmin, vmax=vmax,
                              edgecolors="none")
        draw_edges = args.edges == "on" or (args.edges == "auto" and nview < 200000)
        lw = max(0.05, min(0.6, 60.0 / np.sqrt(max(nview, 1))))
        if draw_edges:
            ax.triplot(tri, color="0.25" if values is not None else "0.1", lw=lw)

    # Boundary: hull and holes thin black; constrained edges thicker, one color per kind.
    be = boundary_edges(mesh.tris)
    if len(be):
        be = be[in_window(mesh.xy[be[:, 0]], mesh.xy[be[:, 1]], box)]
        ax.add_collection(LineCollection(mesh.xy[be], colors="black", linewidths=1.0, zorder=3))
    kinds = sorted({str(k) for _, _, k in mesh.segments})
    handles = []
    for n, kind in enumerate(kinds):
        segs = np.array([(mesh.xy[a], mesh.xy[b]) for a, b, k in mesh.segments if str(k) == kind]).reshape(-1, 2, 2)
        segs = segs[in_window(segs[:, 0], segs[:, 1], box)]
        if not len(segs):
            continue
        lc = LineCollection(segs, colors=KIND_COLORS[n % len(KIND_COLORS)], linewidths=2.2, zorder=4,
                            label=f"constrained: {kind}")
        ax.add_collection(lc)
        handles.append(lc)
    if coast:
        lc = LineCollection(coast, colors="#ff00ff", linewidths=1.1, zorder=6, label="input coast")
        ax.add_collection(lc)
        handles.append(lc)
    if args.repairs:
        rep = [(x, y, k) for x, y, k in fdrplot.read_repairs(mesh.source)
               if box is None or (box[0] <= x <= box[2] and box[1] <= y <= box[3])]
        if rep:
            handles.append(ax.scatter([r[0] for r in rep], [r[1] for r in rep], marker="x", s=40, c="black",
                                      linewidths=1.5, zorder=7, label=f"repairs ({len(rep)})"))
    legend = (handles, occupancy(mesh, keep, be)) if len(handles) > 1 else None

    amin = float(angles.min()) if nt else float("nan")
    amax = float(angles.max()) if nt else float("nan")
    name = title or os.path.basename(mesh.source)
    text = (f"{name}\nN = {len(mesh.xy)} vertices, {nt} triangles\n"
            f"\u03b8min = {amin:.2f}\u00b0, \u03b8max = {amax:.2f}\u00b0")
    if box is not None and nview:
        av = angles[keep].min(1)
        text += (f"\nin view: {nview} triangles, \u03b8min = {av.min():.2f}\u00b0, "
                 f"{100.0 * np.mean(av < 30):.1f} % < 30\u00b0")
    ax.set_title(text, fontsize="medium")
    ax.set_aspect("equal")
    if box is not None:
        ax.set_xlim(box[0], box[2])
        ax.set_ylim(box[1], box[3])
        # Whole metres, no offset: projected coordinates read as they are.
        ax.ticklabel_format(style="plain", useOffset=False)
        ax.xaxis.set_major_locator(MaxNLocator(4))
        ax.yaxis.set_major_locator(MaxNLocator(5))
    else:
        ax.autoscale_view()
    return pc, label, legend


def occupancy(mesh, keep, boundary):
    """What covers the panel, for choosing where the legend goes: a point locator over the drawn
    triangles, and boundary midpoints with their lengths (a coast is thin but must stay visible)."""
    tris = mesh.tris[keep]
    finder = None
    if len(tris):
        used = np.unique(tris)
        local = np.searchsorted(used, tris)  # the locator wants no unused vertices
        finder = Triangulation(mesh.xy[used, 0], mesh.xy[used, 1], local).get_trifinder()
    seg = [mesh.xy[boundary]] if len(boundary) else []
    if mesh.segments:
        seg.append(mesh.xy[np.array([(a, b) for a, b, _ in mesh.segments])])
    seg = np.concatenate(seg) if seg else np.zeros((0, 2, 2))
    return finder, seg.mean(1), np.hypot(*(seg[:, 1] - seg[:, 0]).T)


CORNERS = ("upper right", "upper left", "lower left", "lower right")


def corner_cover(occ, view, size, pad=0.02, samples=(16, 10)):
    """For each corner of `view` (xmin, ymin, xmax, ymax), the fraction of a box of `size` (width,
    height as fractions of the view) in that corner that the mesh covers: a grid of sample points
    located in the triangles, plus boundary lengths counted as lines 1 % of the view wide."""
    finder, mid, length = occ
    x0, y0, x1, y1 = view
    w, h = (x1 - x0) * size[0], (y1 - y0) * size[1]
    px, py = (x1 - x0) * pad, (y1 - y0) * pad
    cover = {}
    for name in CORNERS:
        bx0 = x1 - px - w if name.endswith("right") else x0 + px
        by0 = y1 - py - h if name.startswith("upper") else y0 + py
        gx, gy = np.meshgrid(bx0 + w * (np.arange(samples[0]) + 0.5) / samples[0],
                             by0 + h * (np.arange(samples[1]) + 0.5) / samples[1])
        tri_part = 0.0 if finder is None else float(np.mean(finder(gx.ravel(), gy.ravel()) >= 0))
        on = (mid[:, 0] >= bx0) & (mid[:, 0] <= bx0 + w) & (mid[:, 1] >= by0) & (mid[:, 1] <= by0 + h)
        line_part = float(length[on].sum()) * 0.01 * (x1 - x0) / max(w * h, 1e-300)
        cover[name] = tri_part + line_part
    return cover


def place_legend(fig, ax, handles, occ, max_cover=0.03):
    """The legend goes into the emptiest corner of the panel or, when every corner holds data,
    below the panel: a legend must never hide the mesh it explains. Returns its location."""
    leg = ax.legend(handles=handles, loc="upper right", fontsize="small", framealpha=0.9)
    fig.canvas.draw()
    bb = leg.get_window_extent().transformed(ax.transAxes.inverted())
    leg.remove()
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    cover = corner_cover(occ, (x0, y0, x1, y1), (bb.width, bb.height))
    best = min(CORNERS, key=lambda k: cover[k])  # ties keep CORNERS' order
    if cover[best] <= max_cover:
        ax.legend(handles=handles, loc=best, fontsize="small", framealpha=0.9)
        return best
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.05), ncol=min(len(handles), 3),
              fontsize="small", frameon=False)
    return "below"


def draw(mesh, args, other=None):
    f = shifted_spacing(args.spacing, args.origin)
    if args.crs:
        fdrplot._srs(args.crs)  # fails early on an unknown CRS
        for m in (mesh, other):
            if m is not None and not m.crs_wkt:
                m.crs_wkt = args.crs
    box = window_of(mesh, args)
    coast = []
    for spec in args.coast:
        coast += fdrplot.read_lines(spec, mesh.crs_wkt, box)
    meshes = [mesh] + ([other] if other is not None else [])
    titles = [args.title, args.compare_title]
    # A common color range, so that both panels read against one colorbar.
    color_range = None
    if other is not None and args.color != "none":
        ranges = []
        for m in meshes:
            _, _, _, vmin, vmax = triangle_values(m, args, f, fdrplot.triangle_metrics(m)[0])
            ranges.append((vmin, vmax))
        color_range = (min(r[0] for r in ranges), max(r[1] for r in ranges))
    height = args.size
    if box is not None:  # the panel takes the window's shape (plus room for the titles)
        height = min(2 * args.size, max(0.5 * args.size, args.size * (box[3] - box[1]) / (box[2] - box[0]) + 1.2))
    # Constrained layout gives the colour bar its own column beside the panels instead of drawing it
    # over them, and keeps room for a legend placed below a panel.
    fig, axes = plt.subplots(1, len(meshes), figsize=(args.size * len(meshes) + (1.2 if other else 0), height),
                             dpi=args.dpi, squeeze=False, layout="constrained")
    axes = axes[0]
    pc, label, legends = None, None, []
    for ax, m, t in zip(axes, meshes, titles):
        p, lab, legend = draw_panel(fig, ax, m, args, f, box, coast, t, color_range)
        pc, label = (p, lab) if p is not None else (pc, label)
        legends.append(legend)
    if pc is not None:
        cb = fig.colorbar(pc, ax=list(axes), shrink=0.8, pad=0.02, location="right")
        cb.set_label(label)
        if args.color == "r_over_f" and args.bound:
            cb.ax.axhline(args.bound, color="red", lw=1.5)
    places = [place_legend(fig, ax, *legend) if legend is not None else None for ax, legend in zip(axes, legends)]
    fig.savefig(args.output, dpi=args.dpi)
    # Where things landed, in figure coordinates (x0, y0, x1, y1): the tests check that nothing overlaps.
    layout = {"panels": [tuple(ax.get_position().extents) for ax in axes],
              "colorbar": tuple(cb.ax.get_position().extents) if pc is not None else None,
              "legends": places}
    plt.close(fig)
    return layout


def main(argv=None):
    args = parse_args(argv)
    try:
        mesh = fdrplot.read_mesh(args.mesh, args.ele)
        if len(mesh.tris) == 0:
            raise fdrplot.MeshError(f"{args.mesh}: the mesh has no triangles")
        other = None
        if args.compare:
            other = fdrplot.read_mesh(args.compare)
            if len(other.tris) == 0:
                raise fdrplot.MeshError(f"{args.compare}: the mesh has no triangles")
        draw(mesh, args, other)
    except (fdrplot.MeshError, OSError) as e:
        print(f"ERROR: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
