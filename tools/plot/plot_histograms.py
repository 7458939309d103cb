#!/usr/bin/python3
"""FDR paper Figure 3: min-angle, max-angle and conformity histograms of one or more meshes, to PNG."""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fdrplot  # noqa: E402
from plot_mesh import shifted_spacing  # noqa: E402


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("meshes", nargs="+", help="mesh files (.gpkg, .2dm, .node); overlaid in each panel")
    p.add_argument("-o", "--output", required=True, help="PNG to write")
    p.add_argument("--labels", help="comma-separated legend labels, one per mesh (default: file names)")
    p.add_argument("--spacing", help="spacing expression f(x,y) (as for fdrmesh) for the conformity panel; "
                   "default: the f an fdrmesh GeoPackage stores per node")
    p.add_argument("--origin", default="0,0", help="X,Y of the mesher's local frame (f at (x-X, y-Y))")
    p.add_argument("--title", default="Mesh angle quality and spacing conformity")
    p.add_argument("--dpi", type=int, default=120)
    return p.parse_args(argv)


def legend_corner(values, lo, hi):
    """The upper corner away from the bulk of the values: a histogram legend must not cover its bars."""
    v = np.concatenate([np.asarray(x, dtype=float).ravel() for x in values]) if values else np.zeros(0)
    v = v[np.isfinite(v)]
    return "upper left" if len(v) and np.median(v) > 0.5 * (lo + hi) else "upper right"


def finish_panel(ax, values, lo, hi):
    """Legend in the corner away from the bars, with headroom above the tallest bar for it."""
    ax.set_xlim(lo, hi)
    ax.set_ylim(0, ax.get_ylim()[1] * 1.3)
    ax.legend(fontsize="small", loc=legend_corner(values, lo, hi))


def third_panel_kind(meshes, f):
    """What the third panel shows: conformity when f is known (given, or stored per node by the
    run), else R/f(c) when every file stores it per triangle, else nothing."""
    if f is not None or all("f" in m.node_fields for m in meshes):
        return "conformity"
    if all("R_over_f" in m.tri_fields for m in meshes):
        return "r_over_f"
    return None


def draw_third(ax, kind, mesh, label, f):
    """One mesh's histogram in the third panel; returns the values drawn (None: nothing)."""
    if kind == "conformity":
        c = fdrplot.conformity(mesh, f)
        wc = np.full(len(c), 100.0 / max(len(c), 1))
        ax.hist(c, bins=np.linspace(0, 1, 41), weights=wc, histtype="step", lw=1.6,
                label=f"{label} (min {c.min():.2f}, mean {c.mean():.2f})")
        return c
    elif kind == "r_over_f":
        v = np.asarray(mesh.tri_fields["R_over_f"], dtype=float)
        v = v[np.isfinite(v)]
        wv = np.full(len(v), 100.0 / max(len(v), 1))
        ax.hist(v, bins=np.linspace(0, max(1.5, float(v.max()) if len(v) else 1.0), 41), weights=wv,
                histtype="step", lw=1.6, label=f"{label} (max {v.max():.3f}, mean {v.mean():.3f})")
        return v
    return None


def label_third(ax, kind, values):
    if kind == "conformity":
        ax.set_xlabel("conformity c(x) = min(nn/f, f/nn) per vertex")
        ax.set_ylabel("% of vertices")
        finish_panel(ax, values, 0, 1)
    elif kind == "r_over_f":
        ax.set_xlabel("R/f(c) of a triangle (as stored in the file)")
        ax.set_ylabel("% of triangles")
        finish_panel(ax, values, 0, ax.get_xlim()[1])
    else:
        ax.set_xlabel("conformity c(x) = min(nn/f, f/nn) per vertex")
        ax.text(0.5, 0.5, "no --spacing given and no f stored in the file:\nconformity not computed",
                ha="center", va="center", transform=ax.transAxes)


def main(argv=None):
    args = parse_args(argv)
    labels = args.labels.split(",") if args.labels else [os.path.basename(m) for m in args.meshes]
    if len(labels) != len(args.meshes):
        print(f"ERROR: --labels has {len(labels)} entries for {len(args.meshes)} meshes", file=sys.stderr)
        return 1
    try:
        f = shifted_spacing(args.spacing, args.origin)
        meshes = [fdrplot.read_mesh(m) for m in args.meshes]
    except (fdrplot.MeshError, OSError) as e:
        print(f"ERROR: {e}", file=sys.stderr)
        return 1

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5), dpi=args.dpi)
    ax_min, ax_max, ax_third = axes
    bins_min = np.arange(0, 62, 2.0)
    bins_max = np.arange(60, 182, 2.0)
    third = third_panel_kind(meshes, f)
    mins, maxs, thirds = [], [], []
    for mesh, label in zip(meshes, labels):
        angles, _, _, _ = fdrplot.triangle_metrics(mesh)
        nt = max(len(angles), 1)
        w = np.full(len(angles), 100.0 / nt)  # percent of triangles, so meshes of any size compare
        amin, amax = angles.min(1), angles.max(1)
        mins.append(amin)
        maxs.append(amax)
        ax_min.hist(amin, bins=bins_min, weights=w, histtype="step", lw=1.6,
                    label=f"{label} (min {amin.min():.1f}\u00b0)")
        ax_max.hist(amax, bins=bins_max, weights=w, histtype="step", lw=1.6,
                    label=f"{label} (max {amax.max():.1f}\u00b0)")
        thirds.append(draw_third(ax_third, third, mesh, label, f))
    ax_min.set_xlabel("minimum angle of a triangle (deg)")
    ax_max.set_xlabel("maximum angle of a triangle (deg)")
    for ax in (ax_min, ax_max):
        ax.set_ylabel("% of triangles")
    finish_panel(ax_min, mins, 0, 60)
    finish_panel(ax_max, maxs, 60, 180)
    label_third(ax_third, third, thirds)
    fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=args.dpi)
    plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main())
