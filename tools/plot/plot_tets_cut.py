#!/usr/bin/python3
"""Draw a cut-away of a tetrahedral mesh (VTU with a `material` cell array, as fdrmesh writes it)
to a PNG: the tetrahedra on one side of a vertical plane, their outer faces colored by material,
with a vertical exaggeration for terrain volumes."""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("vtu", help="tetrahedral mesh (.vtu)")
    p.add_argument("-o", "--output", required=True, help="PNG to write")
    p.add_argument("--cut", type=float, default=0.5,
                   help="keep tetrahedra whose centroid lies below this fraction of the y range (default 0.5)")
    p.add_argument("--axis", choices=["x", "y"], default="y", help="axis across which the cut is made (default y)")
    p.add_argument("--exaggeration", type=float, default=0,
                   help="vertical exaggeration (default: height drawn as a fifth of the width)")
    p.add_argument("--title", default="", help="figure title")
    p.add_argument("--zoom", type=float, default=1.0, help="zoom of the 3D box in the figure (matplotlib >= 3.6)")
    p.add_argument("--elev", type=float, default=25, help="view elevation (degrees)")
    p.add_argument("--azim", type=float, default=60, help="view azimuth (degrees)")
    return p.parse_args(argv)


def read_vtu(path):
    import meshio

    m = meshio.read(path)
    tets = np.concatenate([c.data for c in m.cells if c.type == "tetra"])
    mat = None
    for name, blocks in m.cell_data.items():
        if name == "material":
            mat = np.concatenate([np.asarray(b) for b, c in zip(blocks, m.cells) if c.type == "tetra"])
    if mat is None:
        mat = np.zeros(len(tets), dtype=int)
    return np.asarray(m.points, dtype=float), tets, mat.astype(int)


def outer_faces(tets, keep):
    """Faces of the kept tetrahedra used by one kept tetrahedron, with that tetrahedron's index."""
    idx = np.nonzero(keep)[0]
    t = tets[idx]
    faces = np.concatenate([t[:, [1, 2, 3]], t[:, [0, 3, 2]], t[:, [0, 1, 3]], t[:, [0, 2, 1]]])
    owner = np.concatenate([idx] * 4)
    key = np.sort(faces, axis=1)
    _, inv, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    once = counts[inv.reshape(-1)] == 1
    return faces[once], owner[once]


def main(argv=None):
    a = parse_args(argv if argv is not None else sys.argv[1:])
    pts, tets, mat = read_vtu(a.vtu)
    ax_i = 1 if a.axis == "y" else 0
    cen = pts[tets].mean(axis=1)
    lo, hi = pts[:, ax_i].min(), pts[:, ax_i].max()
    keep = cen[:, ax_i] <= lo + a.cut * (hi - lo)
    if not keep.any():
        sys.exit("plot_tets_cut: no tetrahedron on the kept side of the cut")
    faces, owner = outer_faces(tets, keep)
    width = max(np.ptp(pts[:, 0]), np.ptp(pts[:, 1]))
    ex = a.exaggeration if a.exaggeration > 0 else 0.2 * width / max(np.ptp(pts[:, 2]), 1e-12)
    p = pts.copy()
    p[:, 2] = (p[:, 2] - p[:, 2].min()) * ex
    mats = np.unique(mat)
    cmap = plt.get_cmap("tab10")
    colour = {m: cmap(i % 10) for i, m in enumerate(mats)}
    fig = plt.figure(figsize=(10, 6), dpi=130)
    ax = fig.add_subplot(111, projection="3d")
    polys = p[faces]
    coll = Poly3DCollection(polys, facecolors=[colour[m] for m in mat[owner]], edgecolors="k", linewidths=0.15)
    ax.add_collection3d(coll)
    ax.set_xlim(p[:, 0].min(), p[:, 0].max())
    ax.set_ylim(p[:, 1].min(), p[:, 1].max())
    ax.set_zlim(p[:, 2].min(), p[:, 2].max())
    try:
        ax.set_box_aspect((np.ptp(p[:, 0]), np.ptp(p[:, 1]), np.ptp(p[:, 2])), zoom=a.zoom)
    except TypeError:  # matplotlib before 3.6 has no zoom
        ax.set_box_aspect((np.ptp(p[:, 0]), np.ptp(p[:, 1]), np.ptp(p[:, 2])))
    ax.view_init(elev=a.elev, azim=a.azim)
    ax.set_axis_off()
    handles = [matplotlib.patches.Patch(color=colour[m], label=f"material {m}") for m in mats]
    ax.legend(handles=handles, loc="upper left")
    ax.set_title(a.title or f"{a.vtu}: {keep.sum()} of {len(tets)} tetrahedra, vertical x{ex:.3g}")
    fig.savefig(a.output, bbox_inches="tight")
    print(f"wrote {a.output}")


if __name__ == "__main__":
    main()
