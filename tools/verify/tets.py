#!/usr/bin/python3
"""Independent checker of a written tetrahedral mesh (VTU), for the 3D mesher's tests.

usage: tets.py MESH.vtu [--spacing EXPR] [--bound B] [--max-radius-edge Q] [--min-dihedral DEG]
               [--no-delaunay] [--fields-tol REL] [--plc IN.poly|IN.smesh|IN.off] [--json OUT.json]

Reads the VTU itself (inline ASCII or base64 arrays, raw appended data; compressed or base64-appended
files through meshio) with numpy/scipy only, and checks:
  valid      every tetrahedron has positive volume (signs near zero decided exactly with fractions),
             every triangle is a face of at most two tetrahedra, and the boundary (faces of one
             tetrahedron, oriented outward) is closed: each directed boundary edge meets its reverse;
  delaunay   no mesh vertex strictly inside any tetrahedron's circumsphere: a k-d tree gives the
             vertex nearest to each circumcentre, and a suspect (nearer than the radius) is
             confirmed with an exact in-sphere determinant;
  quality    radius-edge ratio (circumradius / shortest edge), R/f(c) with the spacing EXPR (x, y, z
             and numpy's abs, sin, cos, sqrt, exp, minimum, maximum, hypot; or a number) at the
             circumcentre, edge length / f at the edge's midpoint (min, max, mean), dihedral angles (min, max, tetrahedra whose smallest angle is under 5 and
             10 degrees, a histogram of those smallest angles);
  conformity with --plc: every input facet is a union of mesh faces (the faces in it add up to its
             area) and every boundary face lies in a facet (conformity.py);
  fields     the mesher's own cell data r_over_f, radius_edge, min_dihedral_deg, when the VTU has
             them, against the recomputed values (largest relative difference).
Prints one line, writes the figures as JSON with --json, exits 1 when a check or a given bound fails.
"""
import argparse
import base64
import json
import re
import sys
import xml.etree.ElementTree as ET
from fractions import Fraction

import numpy as np
from scipy.spatial import cKDTree

import conformity

DTYPES = {"Int8": "i1", "UInt8": "u1", "Int16": "i2", "UInt16": "u2", "Int32": "i4", "UInt32": "u4",
          "Int64": "i8", "UInt64": "u8", "Float32": "f4", "Float64": "f8"}
VTK_TETRA = 10
HIST_EDGES = [0, 5, 10, 15, 20, 30, 40, 50, 60, 70.5288]  # 70.53 deg: the regular tetrahedron's angle


# ------------------------------------------------------------------ reading
def _split_appended(raw):
    """The XML part of the file (AppendedData emptied) and the bytes after its '_' marker."""
    start = raw.find(b"<AppendedData")
    if start < 0:
        return raw, None, None
    tag_end = raw.index(b">", start)
    encoding = re.search(rb'encoding="(\w+)"', raw[start:tag_end + 1])
    under = raw.index(b"_", tag_end)
    stop = raw.rfind(b"</AppendedData>")
    xml = raw[:start] + b"</VTKFile>"
    return xml, raw[under + 1:stop], (encoding.group(1).decode() if encoding else "raw")


def read_vtu(path):
    """Points (n, 3) float64, tetrahedra (m, 4) int64 and the cell data arrays of a VTU file."""
    with open(path, "rb") as f:
        raw = f.read()
    xml, appended, app_encoding = _split_appended(raw)
    root = ET.fromstring(xml)
    if root.get("compressor") or (appended is not None and app_encoding != "raw"):
        return _read_with_meshio(path)
    order = "<" if root.get("byte_order", "LittleEndian") == "LittleEndian" else ">"
    head = np.dtype(order + ("u8" if root.get("header_type") == "UInt64" else "u4"))

    def array(da):
        dt = np.dtype(order + DTYPES[da.get("type")])
        fmt = da.get("format", "ascii")
        if fmt == "ascii":
            return np.array((da.text or "").split(), dtype=dt)
        if fmt == "appended":
            at = int(da.get("offset"))
            n = int(np.frombuffer(appended[at:at + head.itemsize], head)[0])
            return np.frombuffer(appended[at + head.itemsize:at + head.itemsize + n], dt)
        text = re.sub(r"\s+", "", da.text or "")
        head_chars = 4 * ((head.itemsize + 2) // 3)
        n = int(np.frombuffer(base64.b64decode(text[:head_chars])[:head.itemsize], head)[0])
        if n and text[head_chars - 1] == "=":  # header and data encoded apart
            body = base64.b64decode(text[head_chars:])[:n]
        else:
            body = base64.b64decode(text)[head.itemsize:head.itemsize + n]
        return np.frombuffer(body, dt)

    piece = root.find("UnstructuredGrid/Piece")
    points = array(piece.find("Points/DataArray")).astype(np.float64).reshape(-1, 3)
    cells = {da.get("Name"): array(da) for da in piece.find("Cells").findall("DataArray")}
    types = cells["types"].astype(np.int64)
    ends = cells["offsets"].astype(np.int64)
    starts = np.concatenate([[0], ends[:-1]])
    keep = types == VTK_TETRA
    tets = cells["connectivity"].astype(np.int64)[starts[keep][:, None] + np.arange(4)]
    cell_data = {}
    cd = piece.find("CellData")
    if cd is not None:
        for da in cd.findall("DataArray"):
            cell_data[da.get("Name")] = array(da)[keep]
    return points, tets, cell_data


def _read_with_meshio(path):
    import meshio
    m = meshio.read(path)
    blocks = [i for i, c in enumerate(m.cells) if c.type == "tetra"]
    tets = np.vstack([m.cells[i].data for i in blocks]).astype(np.int64)
    cell_data = {k: np.concatenate([v[i] for i in blocks]) for k, v in m.cell_data.items()}
    return np.asarray(m.points[:, :3], np.float64), tets, cell_data


# ------------------------------------------------------------------ exact signs
def _det_exact(rows):
    """Determinant of a small matrix of Fractions (Laplace along the first row)."""
    if len(rows) == 1:
        return rows[0][0]
    total = Fraction(0)
    for j, a in enumerate(rows[0]):
        if a:
            minor = [r[:j] + r[j + 1:] for r in rows[1:]]
            total += (-1) ** j * a * _det_exact(minor)
    return total


def orient_exact(a, b, c, d):
    rows = [[Fraction(float(p[k])) - Fraction(float(a[k])) for k in range(3)] for p in (b, c, d)]
    return _det_exact(rows)


def inside_sphere_exact(a, b, c, d, e):
    """> 0 when e is strictly inside the circumsphere of the positively oriented (a, b, c, d)."""
    rows = []
    for p in (a, b, c, d):
        q = [Fraction(float(p[k])) - Fraction(float(e[k])) for k in range(3)]
        rows.append(q + [q[0] * q[0] + q[1] * q[1] + q[2] * q[2]])
    # det[p - e, |p - e|^2] is negative for e inside when det[b - a, c - a, d - a] > 0.
    return -_det_exact(rows)


# ------------------------------------------------------------------ checks
def signed_volumes6(P, T):
    a = P[T[:, 0]]
    u, v, w = P[T[:, 1]] - a, P[T[:, 2]] - a, P[T[:, 3]] - a
    det = np.einsum("ij,ij->i", u, np.cross(v, w))
    # A forward error bound of the double determinant: signs below it are decided exactly.
    av, aw = np.abs(v), np.abs(w)
    perm = np.einsum("ij,ij->i", np.abs(u), av[:, [1, 2, 0]] * aw[:, [2, 0, 1]] + av[:, [2, 0, 1]] * aw[:, [1, 2, 0]])
    unsure = np.nonzero(np.abs(det) <= 1e-14 * perm)[0]
    sign = np.sign(det)
    for i in unsure:
        sign[i] = np.sign(float(orient_exact(*P[T[i]])))
    return det, sign


def face_counts(T):
    faces = np.concatenate([T[:, [1, 2, 3]], T[:, [0, 3, 2]], T[:, [0, 1, 3]], T[:, [0, 2, 1]]])
    key = np.sort(faces, axis=1)
    uniq, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return faces, counts[inverse.ravel()], counts


def boundary_open_edges(faces, per_face_count):
    """Directed edges of the outward boundary faces that have no reverse partner (0 when closed)."""
    b = faces[per_face_count == 1]
    if len(b) == 0:
        return 0
    e = np.concatenate([b[:, [0, 1]], b[:, [1, 2]], b[:, [2, 0]]])
    fwd, nf = np.unique(e, axis=0, return_counts=True)
    rev, nr = np.unique(e[:, ::-1], axis=0, return_counts=True)
    a = {tuple(k): n for k, n in zip(fwd.tolist(), nf.tolist())}
    r = {tuple(k): n for k, n in zip(rev.tolist(), nr.tolist())}
    return sum(abs(a.get(k, 0) - r.get(k, 0)) for k in set(a) | set(r)) // 2


def circumspheres(P, T):
    a = P[T[:, 0]]
    M = np.stack([P[T[:, k]] - a for k in (1, 2, 3)], axis=1)
    rhs = 0.5 * np.einsum("ijk,ijk->ij", M, M)
    ok = np.abs(np.linalg.det(M)) > 0
    rel = np.zeros_like(a)
    rel[ok] = np.linalg.solve(M[ok], rhs[ok][..., None])[..., 0]
    rel[~ok] = np.inf
    return a + rel, np.linalg.norm(rel, axis=1)


def delaunay_violations(P, T, centre, R):
    tree = cKDTree(P)
    finite = np.isfinite(R)
    d = np.full(len(T), np.inf)
    idx = np.zeros(len(T), dtype=np.int64)
    d[finite], idx[finite] = tree.query(centre[finite], k=1)
    suspects = np.nonzero(finite & (d < R * (1 - 1e-9)))[0]
    confirmed = [i for i in suspects if idx[i] not in T[i] and inside_sphere_exact(*P[T[i]], P[idx[i]]) > 0]
    return len(confirmed), confirmed[:10]


def dihedral_angles(P, T):
    """(m, 6) dihedral angles in degrees at the six edges of each tetrahedron."""
    V = [P[T[:, k]] for k in range(4)]
    # Outward normal of the face opposite vertex k.
    opp = {0: (1, 2, 3), 1: (0, 3, 2), 2: (0, 1, 3), 3: (0, 2, 1)}
    n = {}
    for k, (i, j, l) in opp.items():
        nk = np.cross(V[j] - V[i], V[l] - V[i])
        n[k] = nk / np.linalg.norm(nk, axis=1)[:, None]
    out = []
    for k, l in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)):  # the edge opposite both faces
        c = np.clip(np.einsum("ij,ij->i", n[k], n[l]), -1.0, 1.0)
        out.append(180.0 - np.degrees(np.arccos(c)))
    return np.stack(out, axis=1)


def spacing_at(expr, centre):
    env = {name: getattr(np, name) for name in ("abs", "sin", "cos", "sqrt", "exp", "minimum", "maximum", "hypot")}
    env.update(x=centre[:, 0], y=centre[:, 1], z=centre[:, 2], pi=np.pi)
    value = eval(compile(expr, "<spacing>", "eval"), {"__builtins__": {}}, env)  # noqa: S307 (test tool)
    return np.broadcast_to(np.asarray(value, np.float64), (len(centre),))


def field_differences(cell_data, computed):
    """Largest relative difference between the mesher's own per-tetrahedron figures in the VTU
    (r_over_f, radius_edge, min_dihedral_deg) and this script's, for those present."""
    out = {}
    for name, mine in computed.items():
        if name in cell_data and len(cell_data[name]) == len(mine) and len(mine):
            theirs = np.asarray(cell_data[name], np.float64)
            out[name] = float((np.abs(theirs - mine) / np.maximum(np.abs(mine), 1e-300)).max())
    return out


def edge_over_f(P, T, spacing):
    """Each mesh edge's length over f at its midpoint: min, max, mean (the size the mesh follows)."""
    e = np.concatenate([T[:, [i, j]] for i, j in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))])
    e = np.unique(np.sort(e, axis=1), axis=0)
    if len(e) == 0:
        return {}
    ratio = np.linalg.norm(P[e[:, 0]] - P[e[:, 1]], axis=1) / spacing_at(spacing, 0.5 * (P[e[:, 0]] + P[e[:, 1]]))
    return {"edge_over_f_min": float(ratio.min()), "edge_over_f_max": float(ratio.max()),
            "edge_over_f_mean": float(ratio.mean())}


def check(P, T, spacing=None, delaunay=True, cell_data=None):
    det, sign = signed_volumes6(P, T)
    faces, per_face, counts = face_counts(T)
    centre, R = circumspheres(P, T)
    edges = np.stack([np.linalg.norm(P[T[:, i]] - P[T[:, j]], axis=1)
                      for i, j in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))], axis=1)
    ang = dihedral_angles(P, T)
    smallest = ang.min(axis=1)
    hist, _ = np.histogram(smallest, bins=HIST_EDGES + [180])
    r = {
        "vertices": int(len(P)), "tetrahedra": int(len(T)),
        "nonpositive_volume": int((sign <= 0).sum()),
        "faces_shared_gt2": int((counts > 2).sum()),
        "boundary_faces": int((per_face == 1).sum()),
        "boundary_open_edges": int(boundary_open_edges(faces, per_face)),
        "volume": float(np.abs(det).sum() / 6),
        "radius_edge_max": float((R / edges.min(axis=1)).max()) if len(T) else 0.0,
        "dihedral_min": float(ang.min()) if len(T) else 0.0,
        "dihedral_max": float(ang.max()) if len(T) else 0.0,
        "dihedral_lt5": int((smallest < 5).sum()), "dihedral_lt10": int((smallest < 10).sum()),
        "dihedral_hist": {"edges_deg": HIST_EDGES + [180], "counts": hist.tolist()},
    }
    r["valid"] = r["nonpositive_volume"] == 0 and r["faces_shared_gt2"] == 0 and r["boundary_open_edges"] == 0
    if delaunay:
        r["not_delaunay"], r["not_delaunay_first"] = delaunay_violations(P, T, centre, R)
        r["not_delaunay_first"] = [int(i) for i in r["not_delaunay_first"]]
    computed = {"radius_edge": R / edges.min(axis=1), "min_dihedral_deg": smallest}
    if spacing is not None:
        computed["r_over_f"] = R / spacing_at(spacing, centre)
        r["r_over_f_max"] = float(computed["r_over_f"].max()) if len(T) else 0.0
        r.update(edge_over_f(P, T, spacing))
    if cell_data is not None:
        r["field_rel_diff"] = field_differences(cell_data, computed)
    return r


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("--spacing", help="f(x, y, z) for R/f at circumcentres")
    ap.add_argument("--bound", type=float, help="fail when R/f(c) > B")
    ap.add_argument("--max-radius-edge", type=float, help="fail when a radius-edge ratio exceeds Q")
    ap.add_argument("--min-dihedral", type=float, help="fail when a dihedral angle is under DEG degrees")
    ap.add_argument("--no-delaunay", action="store_true", help="skip the empty-circumsphere test")
    ap.add_argument("--fields-tol", type=float,
                    help="fail when the VTU's r_over_f / radius_edge / min_dihedral_deg cell data differ from "
                         "the recomputed values by more than this relative amount")
    ap.add_argument("--plc", help="the input PLC the mesh must conform to")
    ap.add_argument("--json")
    a = ap.parse_args(argv)
    P, T, cell_data = read_vtu(a.mesh)
    r = check(P, T, a.spacing, not a.no_delaunay, cell_data)
    ok = r["valid"] and r.get("not_delaunay", 0) == 0
    if a.plc:
        c = r["conformity"] = conformity.conformity(P, T, a.plc)
        ok = ok and c["facets_not_conforming"] == 0 and c["boundary_faces_off_facets"] == 0
    if a.bound is not None and "r_over_f_max" in r:
        ok = ok and r["r_over_f_max"] <= a.bound * (1 + 1e-9)
    if a.max_radius_edge is not None:
        ok = ok and r["radius_edge_max"] <= a.max_radius_edge * (1 + 1e-9)
    if a.min_dihedral is not None:
        ok = ok and r["dihedral_min"] >= a.min_dihedral
    if a.fields_tol is not None:
        ok = ok and all(d <= a.fields_tol for d in r["field_rel_diff"].values())
    r["ok"] = bool(ok)
    print(f'{a.mesh}: {r["tetrahedra"]} tetrahedra, {r["vertices"]} vertices; valid {r["valid"]}'
          + (f', delaunay {r["not_delaunay"] == 0} ({r["not_delaunay"]} violated)' if "not_delaunay" in r else "")
          + f', radius-edge max {r["radius_edge_max"]:.4f}'
          + (f', R/f max {r["r_over_f_max"]:.4f}' if "r_over_f_max" in r else "")
          + f', dihedral {r["dihedral_min"]:.2f}..{r["dihedral_max"]:.2f} deg'
          + f' (<5: {r["dihedral_lt5"]}, <10: {r["dihedral_lt10"]}), volume {r["volume"]:.9g}'
          + "".join(f", {k} as written within {d:.1e}" for k, d in r["field_rel_diff"].items())
          + (f', facets conforming {len(r["conformity"]["facets"]) - r["conformity"]["facets_not_conforming"]}'
             f'/{len(r["conformity"]["facets"])} ({r["conformity"]["boundary_faces_off_facets"]} boundary faces '
             f'off facets)' if "conformity" in r else "")
          + ("" if ok else "  FAILED"))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(r, f, indent=1, default=lambda o: o.item() if hasattr(o, "item") else str(o))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
