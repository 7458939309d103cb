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
    p.add_argument("--spacing", help="spacing expression f(x,y) (as for fdrmesh) for the conformity panel")
    p.add_argument("--origin", default="0,0", help="X,Y of the mesher's local frame (f at (x-X, y-Y))")
    p.add_argument("--title", default="Mesh angle quality and spacing conformity")
    p.add_argument("--dpi", type=int, default=120)
    return p.parse_args(argv)


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
    ax_min, ax_max, ax_conf = axes
    bins_min = np.arange(0, 62, 2.0)
    bins_max = np.arange(60, 182, 2.0)
    bins_conf = np.linspace(0, 1, 41)
    for mesh, label in zip(meshes, labels):
        angles, _, _, _ = fdrplot.triangle_metrics(mesh)
        nt = max(len(angles), 1)
        w = np.full(len(angles), 100.0 / nt)  # percent of triangles, so meshes of any size compare
        amin, amax = angles.min(1), angles.max(1)
        ax_min.hist(amin, bins=bins_min, weights=w, histtype="step", lw=1.6,
                    label=f"{label} (min {amin.min():.1f}\u00b0)")
        ax_max.hist(amax, bins=bins_max, weights=w, histtype="step", lw=1.6,
                    label=f"{label} (max {amax.max():.1f}\u00b0)")
        if f is not None:
            c = fdrplot.conformity(mesh, f)
            wc = np.full(len(c), 100.0 / max(len(c), 1))
            ax_conf.hist(c, bins=bins_conf, weights=wc, histtype="step", lw=1.6,
                         label=f"{label} (min {c.min():.2f}, mean {c.mean():.2f})")
    ax_min.set_xlabel("minimum angle of a triangle (deg)")
    ax_max.set_xlabel("maximum angle of a triangle (deg)")
    ax_conf.set_xlabel("conformity c(x) = min(nn/f, f/nn) per vertex")
    for ax in (ax_min, ax_max):
        ax.set_ylabel("% of triangles")
        ax.legend(fontsize="small", loc="upper left")
    ax_conf.set_ylabel("% of vertices")
    if f is None:
        ax_conf.text(0.5, 0.5, "no --spacing given:\nconformity not computed", ha="center", va="center",
                     transform=ax_conf.transAxes)
    else:
        ax_conf.legend(fontsize="small", loc="upper left")
    ax_min.set_xlim(0, 60)
    ax_max.set_xlim(60, 180)
    ax_conf.set_xlim(0, 1)
    fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.output, dpi=args.dpi)
    plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main())
