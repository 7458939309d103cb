"""Whether a tetrahedral mesh conforms to its input PLC (TetGen .poly/.smesh, or .off): every
input facet must be a union of mesh faces, so the mesh faces lying in a facet (in its plane, inside
its polygons and outside its holes) must add up to the facet's area; and every boundary face of
the mesh must lie in some facet. A reader of its own for the input (not the C++ one under test).

Planes and insides are decided in floating point with a tolerance relative to the PLC's size: the
mesher's Steiner points on facets are rounded, so exact coplanarity cannot be asked of them."""
import os

import numpy as np

PLANE_TOL = 1e-9  # distance to a facet's plane, relative to the PLC's bounding-box diagonal
AREA_TOL = 1e-9   # relative area difference


# ------------------------------------------------------------------ reading the PLC
def _data_lines(path):
    with open(path) as f:
        for raw in f:
            words = raw.split("#", 1)[0].replace(",", " ").split()
            if words:
                yield words


def _nodes(lines, first, path):
    n = int(first[0])
    if n == 0:
        sib = os.path.splitext(path)[0] + ".node"
        it = _data_lines(sib)
        return _nodes(it, next(it), sib)
    rows = [next(lines) for _ in range(n)]
    base = int(rows[0][0])
    return np.array([[float(v) for v in r[1:4]] for r in rows]), base


def read_plc(path):
    """(points (n, 3), facets) with each facet a dict: polygons (lists of 0-based ids), holes (points)."""
    ext = os.path.splitext(path)[1].lower()
    lines = _data_lines(path)
    if ext == ".off":
        head = next(lines)
        counts = head[1:] if len(head) > 1 else next(lines)
        nv, nf = int(counts[0]), int(counts[1])
        P = np.array([[float(v) for v in next(lines)[:3]] for _ in range(nv)])
        facets = []
        for _ in range(nf):
            w = next(lines)
            facets.append({"polygons": [[int(v) for v in w[1:1 + int(w[0])]]], "holes": []})
        return P, facets
    P, base = _nodes(lines, next(lines), path)
    nf = int(next(lines)[0])
    facets = []
    for _ in range(nf):
        w = next(lines)
        if ext == ".smesh":
            facets.append({"polygons": [[int(v) - base for v in w[1:1 + int(w[0])]]], "holes": []})
            continue
        npoly, nhole = int(w[0]), int(w[1]) if len(w) > 1 else 0
        polys = []
        for _ in range(npoly):
            q = next(lines)
            polys.append([int(v) - base for v in q[1:1 + int(q[0])]])
        holes = [[float(v) for v in next(lines)[1:4]] for _ in range(nhole)]
        facets.append({"polygons": polys, "holes": holes})
    return P, facets


# ------------------------------------------------------------------ facet geometry
def _plane(P, facet):
    """Unit normal, offset and the two coordinates kept when projecting (largest normal part dropped)."""
    n = np.zeros(3)
    for poly in facet["polygons"]:
        if len(poly) >= 3:
            Q = P[poly]
            n += np.cross(Q, np.roll(Q, -1, axis=0)).sum(axis=0)  # Newell's normal
    n /= np.linalg.norm(n)
    keep = [k for k in range(3) if k != int(np.argmax(np.abs(n)))]
    return n, float(n @ P[facet["polygons"][0][0]]), keep


def _inside(poly2, pts2):
    """Even-odd point-in-polygon for many points."""
    x, y = pts2[:, 0], pts2[:, 1]
    inside = np.zeros(len(pts2), bool)
    for (x0, y0), (x1, y1) in zip(poly2, np.roll(poly2, -1, axis=0)):
        crosses = (y0 > y) != (y1 > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            xc = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
        inside ^= crosses & (x < xc)
    return inside


def _area2(poly2):
    x, y = poly2[:, 0], poly2[:, 1]
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def facet_region(P, facet):
    """The facet's plane, its area, and a membership test for points of that plane."""
    n, d, keep = _plane(P, facet)
    stretch = 1.0 / abs(n[3 - sum(keep)])  # projected areas grow back by 1 / |n . dropped axis|
    polys = [P[p][:, keep] for p in facet["polygons"] if len(p) >= 3]
    own = [_area2(q) for q in polys]
    # A hole point makes the smallest polygon around it a hole.
    is_hole = [False] * len(polys)
    for h in np.array(facet["holes"], float).reshape(-1, 3)[:, keep]:
        around = [i for i, q in enumerate(polys) if _inside(q, h[None])[0]]
        if around:
            is_hole[min(around, key=lambda i: own[i])] = True
    # Polygons inside no other solid polygon add their area; hole polygons take theirs away.
    top = [not any(j != i and not is_hole[j] and _inside(polys[j], polys[i].mean(axis=0)[None])[0]
                   for j in range(len(polys))) for i in range(len(polys))]
    area = stretch * (sum(a for a, t, h in zip(own, top, is_hole) if t and not h)
                      - sum(a for a, h in zip(own, is_hole) if h))

    def contains(pts):
        p2 = pts[:, keep]
        inside = np.zeros(len(pts), bool)
        for q, h in zip(polys, is_hole):
            if not h:
                inside |= _inside(q, p2)
        for q, h in zip(polys, is_hole):
            if h:
                inside &= ~_inside(q, p2)
        return inside

    return n, d, area, contains


# ------------------------------------------------------------------ the check
def conformity(P, T, plc_path):
    """Per facet: its area and the area of the mesh faces lying in it; boundary faces in no facet."""
    Q, facets = read_plc(plc_path)
    scale = float(np.linalg.norm(Q.max(axis=0) - Q.min(axis=0)))
    faces = np.concatenate([T[:, [1, 2, 3]], T[:, [0, 2, 3]], T[:, [0, 1, 3]], T[:, [0, 1, 2]]])
    key, counts = np.unique(np.sort(faces, axis=1), axis=0, return_counts=True)
    A, B, C = P[key[:, 0]], P[key[:, 1]], P[key[:, 2]]
    areas = 0.5 * np.linalg.norm(np.cross(B - A, C - A), axis=1)
    centroid = (A + B + C) / 3
    covered = np.zeros(len(key), bool)
    rows = []
    for i, facet in enumerate(facets):
        if not any(len(p) >= 3 for p in facet["polygons"]):
            continue
        n, d, area, contains = facet_region(Q, facet)
        on_plane = np.ones(len(key), bool)
        for V in (A, B, C):
            on_plane &= np.abs(V @ n - d) <= PLANE_TOL * scale
        cand = np.nonzero(on_plane)[0]
        mine = cand[contains(centroid[cand])]
        covered[mine] = True
        got = float(areas[mine].sum())
        rows.append({"facet": i, "area": float(area), "mesh_area": got,
                     "ok": abs(got - area) <= AREA_TOL * max(area, scale * scale * 1e-12)})
    stray = (counts == 1) & ~covered
    return {"facets": rows, "facets_not_conforming": sum(not r["ok"] for r in rows),
            "boundary_faces_off_facets": int(stray.sum()), "boundary_area_off_facets": float(areas[stray].sum())}
