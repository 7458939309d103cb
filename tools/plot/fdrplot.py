"""Shared helpers for the fdrmesh plot scripts: mesh readers, spacing expressions, metrics."""
import math
import os
import re

import numpy as np

PRESETS = {
    # Figure 2 of the FDR paper, same definitions as fdr::sizing::PaperF1Field / PaperF2Field.
    "paper-f1": "((abs(x-5)+abs(y-5))*0.1+0.1)",
    "paper-f2": "((abs(sin(x+y))+abs(cos(x+y)))*0.1)",
}


class MeshError(Exception):
    """A mesh or expression file that cannot be read; the message names file and line."""


class Mesh:
    """Vertices (n,2), optional z (n,), triangles (t,3) 0-based, constrained polylines.

    segments: list of (i, j, kind) vertex-index pairs of constrained edges (kind: str or int).
    tri_fields: per-triangle arrays read from the file (GPKG: area, min_angle, R_over_f).
    node_fields: per-vertex arrays read from the file (GPKG: f, conformity), NaN where unset.
    """

    def __init__(self, xy, tris, z=None, segments=None, tri_fields=None, source="", crs_wkt=None,
                 node_fields=None):
        self.crs_wkt = crs_wkt  # CRS of xy (GPKG: the layers' SRS), None when unknown
        self.xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        self.tris = np.asarray(tris, dtype=np.int64).reshape(-1, 3)
        self.z = None if z is None else np.asarray(z, dtype=float)
        self.segments = segments or []
        self.tri_fields = tri_fields or {}
        self.node_fields = node_fields or {}
        self.source = source
        if len(self.tris) and (self.tris.min() < 0 or self.tris.max() >= len(self.xy)):
            raise MeshError(f"{source}: a triangle references a vertex outside 0..{len(self.xy) - 1}")


# ----------------------------------------------------------------------------- spacing

_TOKEN = re.compile(r"\s*(?:(\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?)|([A-Za-z_][A-Za-z_0-9]*)|(\*\*|[-+*/^(),]))")
_FUNCS = {"abs": "np.abs", "sin": "np.sin", "cos": "np.cos", "tan": "np.tan", "sqrt": "np.sqrt",
          "exp": "np.exp", "log": "np.log", "min": "_min", "max": "_max"}


def _min(*a):
    r = a[0]
    for b in a[1:]:
        r = np.minimum(r, b)
    return r


def _max(*a):
    r = a[0]
    for b in a[1:]:
        r = np.maximum(r, b)
    return r


def spacing_function(expr):
    """Compile the fdrmesh --spacing expression into f(x, y) over numpy arrays.

    Syntax: numbers, x, y, + - * / ^ ( ) and abs sin cos tan sqrt exp log min max, with the
    presets paper-f1 and paper-f2 usable as operands (so "2*paper-f1" works). Anything else is
    rejected with the position of the offending character.
    """
    text = expr
    for name, body in PRESETS.items():
        text = re.sub(r"(?<![A-Za-z0-9_])" + re.escape(name) + r"(?![A-Za-z0-9_])", body, text)
    out, pos = [], 0
    while pos < len(text):
        if text[pos:].strip() == "":
            break
        m = _TOKEN.match(text, pos)
        if not m:
            raise MeshError(f"spacing expression '{expr}': unexpected character '{text[pos:].strip()[0]}'")
        num, ident, op = m.groups()
        if num is not None:
            out.append(num)
        elif ident is not None:
            if ident in ("x", "y"):
                out.append(ident)
            elif ident in _FUNCS:
                out.append(_FUNCS[ident])
            else:
                raise MeshError(f"spacing expression '{expr}': unknown name '{ident}'")
        else:
            out.append("**" if op in ("^", "**") else op)
        pos = m.end()
    code = " ".join(out)
    try:
        compiled = compile(code, "<spacing>", "eval")
    except SyntaxError as e:
        raise MeshError(f"spacing expression '{expr}': syntax error ({e.msg})") from None
    env = {"np": np, "_min": _min, "_max": _max, "__builtins__": {}}

    def f(x, y):
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        with np.errstate(all="ignore"):
            v = eval(compiled, env, {"x": x, "y": y})  # noqa: S307 - tokens whitelisted above
        return np.broadcast_to(np.asarray(v, dtype=float), np.broadcast(x, y).shape).copy()

    return f


# ----------------------------------------------------------------------------- readers

def _data_lines(path):
    """Yield (line_number, fields) of non-empty lines with '#' comments removed."""
    with open(path, encoding="utf-8", errors="replace") as fh:
        for n, line in enumerate(fh, 1):
            line = line.split("#", 1)[0].strip()
            if line:
                yield n, line.split()


def _read_triangle_node(path):
    it = _data_lines(path)
    try:
        n0, head = next(it)
    except StopIteration:
        raise MeshError(f"{path}: empty .node file") from None
    try:
        nv, dim, nattr, nmark = (int(v) for v in (head + ["0", "0", "0"])[:4])
    except ValueError:
        raise MeshError(f"{path}:{n0}: bad header '{' '.join(head)}'") from None
    if dim != 2:
        raise MeshError(f"{path}:{n0}: dimension {dim}, expected 2")
    ids, xy, attr = [], [], []
    for _ in range(nv):
        try:
            n, f = next(it)
        except StopIteration:
            raise MeshError(f"{path}: expected {nv} vertices, found {len(ids)}") from None
        try:
            ids.append(int(f[0]))
            xy.append((float(f[1]), float(f[2])))
            attr.append(float(f[3]) if nattr > 0 else 0.0)
        except (ValueError, IndexError):
            raise MeshError(f"{path}:{n}: bad vertex line '{' '.join(f)}'") from None
    base = ids[0] if ids else 0
    return base, np.array(xy).reshape(-1, 2), (np.array(attr) if nattr > 0 else None)


def _read_triangle_ele(path, base, nv):
    it = _data_lines(path)
    try:
        n0, head = next(it)
    except StopIteration:
        raise MeshError(f"{path}: empty .ele file") from None
    try:
        nt, per = int(head[0]), int(head[1])
    except (ValueError, IndexError):
        raise MeshError(f"{path}:{n0}: bad header '{' '.join(head)}'") from None
    if per < 3:
        raise MeshError(f"{path}:{n0}: {per} nodes per triangle")
    tris = []
    for _ in range(nt):
        try:
            n, f = next(it)
        except StopIteration:
            raise MeshError(f"{path}: expected {nt} triangles, found {len(tris)}") from None
        try:
            t = [int(v) - base for v in f[1:4]]
        except ValueError:
            raise MeshError(f"{path}:{n}: bad triangle line '{' '.join(f)}'") from None
        if len(t) != 3 or min(t) < 0 or max(t) >= nv:
            raise MeshError(f"{path}:{n}: triangle '{' '.join(f)}' references a missing vertex")
        tris.append(t)
    return np.array(tris, dtype=np.int64).reshape(-1, 3)


def _read_triangle_segments(path, base, nv):
    """Segments of a sibling .poly (vertices in the .node file) or .edge file with marker != 0."""
    segs = []
    if path.endswith(".edge"):
        it = _data_lines(path)
        n0, head = next(it, (0, ["0"]))
        nmark = int(head[1]) if len(head) > 1 else 0
        for n, f in it:
            if nmark and len(f) >= 4 and int(f[3]) != 0:
                segs.append((int(f[1]) - base, int(f[2]) - base, int(f[3])))
        return [s for s in segs if 0 <= s[0] < nv and 0 <= s[1] < nv]
    it = _data_lines(path)
    n0, head = next(it, (0, ["0"]))
    if int(head[0]) != 0:
        return []  # a .poly with its own vertices is an input file, not this mesh's segments
    n1, shead = next(it, (0, ["0"]))
    nseg = int(shead[0])
    nmark = int(shead[1]) if len(shead) > 1 else 0
    for _ in range(nseg):
        n, f = next(it)
        segs.append((int(f[1]) - base, int(f[2]) - base, int(f[3]) if nmark and len(f) > 3 else 1))
    return [s for s in segs if 0 <= s[0] < nv and 0 <= s[1] < nv]


def read_triangle(node_path, ele_path=None):
    stem = node_path[: -len(".node")] if node_path.endswith(".node") else node_path
    ele_path = ele_path or stem + ".ele"
    for p in (node_path, ele_path):
        if not os.path.exists(p):
            raise MeshError(f"{p}: no such file")
    base, xy, z = _read_triangle_node(node_path)
    tris = _read_triangle_ele(ele_path, base, len(xy))
    segs = []
    for side in (stem + ".poly", stem + ".edge"):
        if os.path.exists(side):
            try:
                segs = _read_triangle_segments(side, base, len(xy))
            except (ValueError, IndexError, StopIteration):
                raise MeshError(f"{side}: cannot read its segments") from None
            if segs:
                break
    return Mesh(xy, tris, z=z, segments=segs, source=node_path)


def read_2dm(path):
    """SMS 2DM: ND id x y z, E3T id n1 n2 n3 mat, NS nodestrings (last node negative)."""
    nodes, elems, strings, cur = {}, [], [], []
    for n, f in _data_lines(path):
        card = f[0]
        try:
            if card == "ND":
                nodes[int(f[1])] = (float(f[2]), float(f[3]), float(f[4]) if len(f) > 4 else 0.0)
            elif card == "E3T":
                elems.append((n, int(f[2]), int(f[3]), int(f[4])))
            elif card in ("E4Q", "E6T", "E8Q", "E9Q"):
                raise MeshError(f"{path}:{n}: element type {card} is not a linear triangle")
            elif card == "NS":
                for v in (int(t) for t in f[1:] if re.fullmatch(r"-?\d+", t)):
                    cur.append(abs(v))
                    if v < 0:
                        strings.append(cur)
                        cur = []
        except (ValueError, IndexError):
            raise MeshError(f"{path}:{n}: bad {card} line '{' '.join(f)}'") from None
    if not nodes:
        raise MeshError(f"{path}: no ND lines (not a 2DM mesh?)")
    ids = sorted(nodes)
    index = {i: k for k, i in enumerate(ids)}
    xyz = np.array([nodes[i] for i in ids])
    tris = []
    for n, a, b, c in elems:
        try:
            tris.append((index[a], index[b], index[c]))
        except KeyError as e:
            raise MeshError(f"{path}:{n}: E3T references missing node {e.args[0]}") from None
    segs = []
    for k, s in enumerate(strings + ([cur] if cur else [])):
        segs += [(index[a], index[b], k + 1) for a, b in zip(s, s[1:]) if a in index and b in index]
    return Mesh(xyz[:, :2], np.array(tris).reshape(-1, 3), z=xyz[:, 2], segments=segs, source=path)


def read_gpkg(path):
    """fdrmesh GeoPackage: layers nodes (z, f, conformity), triangles (area, min_angle, R_over_f), boundaries (kind)."""
    from osgeo import ogr  # only GPKG needs GDAL

    ogr.UseExceptions()
    try:
        ds = ogr.Open(path)
    except RuntimeError as e:
        raise MeshError(f"{path}: cannot open ({e})") from None
    if ds is None:
        raise MeshError(f"{path}: cannot open")
    index, xy, z = {}, [], []
    node_vals = {}  # stored per-node fields: the run's own spacing, so no --spacing is needed to judge it

    def vid(x, y):
        key = (x, y)
        if key not in index:
            index[key] = len(xy)
            xy.append(key)
            z.append(math.nan)
            for v in node_vals.values():
                v.append(math.nan)
        return index[key]

    nodes = ds.GetLayerByName("nodes")
    if nodes is not None:
        ndefn = nodes.GetLayerDefn()
        has_z = ndefn.GetFieldIndex("z") >= 0
        node_vals.update({n: [] for n in ("f", "conformity") if ndefn.GetFieldIndex(n) >= 0})
        for feat in nodes:
            g = feat.GetGeometryRef()
            v = vid(g.GetX(), g.GetY())
            if has_z and feat.IsFieldSetAndNotNull("z"):
                z[v] = feat.GetFieldAsDouble("z")
            for n, vals_n in node_vals.items():
                if feat.IsFieldSetAndNotNull(n):
                    vals_n[v] = feat.GetFieldAsDouble(n)
    tl = ds.GetLayerByName("triangles")
    if tl is None:
        raise MeshError(f"{path}: no layer 'triangles'")
    defn = tl.GetLayerDefn()
    fields = [n for n in ("area", "min_angle", "R_over_f") if defn.GetFieldIndex(n) >= 0]
    tris, vals = [], {n: [] for n in fields}
    for feat in tl:
        g = feat.GetGeometryRef()
        ring = g.GetGeometryRef(0) if g is not None and g.GetGeometryCount() else None
        if ring is None or ring.GetPointCount() < 4:
            raise MeshError(f"{path}: layer triangles, feature {feat.GetFID()}: not a triangle polygon")
        pts = [ring.GetPoint_2D(i) for i in range(3)]
        tris.append([vid(*p) for p in pts])
        for n in fields:
            vals[n].append(feat.GetFieldAsDouble(n) if feat.IsFieldSetAndNotNull(n) else math.nan)
    segs = []
    bl = ds.GetLayerByName("boundaries")
    if bl is not None:
        has_kind = bl.GetLayerDefn().GetFieldIndex("kind") >= 0
        for feat in bl:
            kind = feat.GetFieldAsString("kind") if has_kind else "boundary"
            g = feat.GetGeometryRef()
            parts = [g.GetGeometryRef(i) for i in range(g.GetGeometryCount())] if g.GetGeometryCount() else [g]
            for part in parts:
                p = [vid(*part.GetPoint_2D(i)) for i in range(part.GetPointCount())]
                segs += [(a, b, kind) for a, b in zip(p, p[1:])]
    zz = np.array(z)
    srs = tl.GetSpatialRef()
    return Mesh(np.array(xy).reshape(-1, 2), np.array(tris).reshape(-1, 3),
                z=None if np.all(np.isnan(zz)) else zz, segments=segs,
                tri_fields={n: np.array(v) for n, v in vals.items()}, source=path,
                crs_wkt=srs.ExportToWkt() if srs is not None else None,
                node_fields={n: np.array(v) for n, v in node_vals.items() if not np.all(np.isnan(v))})


def read_mesh(path, ele=None):
    low = path.lower()
    if low.endswith(".gpkg"):
        return read_gpkg(path)
    if low.endswith(".2dm"):
        return read_2dm(path)
    if low.endswith(".node") or low.endswith(".ele"):
        stem = path[:-5]
        return read_triangle(stem + ".node", ele)
    raise MeshError(f"{path}: unknown mesh format (expected .gpkg, .2dm, .node/.ele)")


# ----------------------------------------------------------------------------- vector overlays, windows

def _srs(text):
    from osgeo import osr

    s = osr.SpatialReference()
    if s.SetFromUserInput(text) != 0:
        raise MeshError(f"unknown CRS '{text[:60]}'")
    s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)  # x = easting / longitude
    return s


def _transform(src, dst):
    from osgeo import osr

    return osr.CoordinateTransformation(src, dst)


def _box_through(ct, box, n=21):
    """Bounding box of `box` (xmin, ymin, xmax, ymax) mapped by ct, its edges densified."""
    x0, y0, x1, y1 = box
    t = np.linspace(0.0, 1.0, n)
    xs = np.concatenate([x0 + (x1 - x0) * t, np.full(n, x1), x1 - (x1 - x0) * t, np.full(n, x0)])
    ys = np.concatenate([np.full(n, y0), y0 + (y1 - y0) * t, np.full(n, y1), y1 - (y1 - y0) * t])
    pts = np.array(ct.TransformPoints(np.c_[xs, ys].tolist()))[:, :2]
    return (float(pts[:, 0].min()), float(pts[:, 1].min()), float(pts[:, 0].max()), float(pts[:, 1].max()))


def parse_box(text, option):
    try:
        v = [float(t) for t in text.split(",")]
    except ValueError:
        v = []
    if len(v) != 4 or not (v[0] < v[2] and v[1] < v[3]):
        raise MeshError(f"{option} '{text}': expected XMIN,YMIN,XMAX,YMAX with XMIN < XMAX and YMIN < YMAX")
    return tuple(v)


def lonlat_box_to_crs(box, crs_wkt):
    """A lon/lat box (W, S, E, N degrees) as a box in crs_wkt (bounding box of its densified edges)."""
    if not crs_wkt:
        raise MeshError("--bbox-lonlat needs the mesh's CRS (stored in fdrmesh GeoPackages; else give --crs)")
    return _box_through(_transform(_srs("EPSG:4326"), _srs(crs_wkt)), box)


def split_source(spec):
    """FILE or FILE:LAYER -> (path, layer or None); a path that exists as given wins."""
    if os.path.exists(spec):
        return spec, None
    if ":" in spec:
        path, layer = spec.rsplit(":", 1)
        if os.path.exists(path):
            return path, layer or None
    raise MeshError(f"{spec}: no such file")


def read_lines(spec, crs_wkt=None, box=None, allow_unknown_crs=False):
    """Line work (polygon rings, lines) of an OGR source FILE[:LAYER], reprojected to crs_wkt.

    Returns a list of (n, 2) arrays. `box` (in crs_wkt) limits the features read (spatial filter).
    A layer without SRS is taken as it is; a layer with one needs crs_wkt (MeshError) unless
    allow_unknown_crs (then its coordinates are taken as they are).
    """
    from osgeo import ogr

    ogr.UseExceptions()
    path, layer = split_source(spec)
    try:
        ds = ogr.Open(path)
    except RuntimeError as e:
        raise MeshError(f"{path}: cannot open ({e})") from None
    if ds is None:
        raise MeshError(f"{path}: cannot open")
    lyr = ds.GetLayerByName(layer) if layer else ds.GetLayer(0)
    if lyr is None:
        names = [ds.GetLayer(i).GetName() for i in range(ds.GetLayerCount())]
        raise MeshError(f"{path}: no layer '{layer}' (layers: {', '.join(names)})")
    src = lyr.GetSpatialRef()
    ct = None
    if src is not None and not crs_wkt and not allow_unknown_crs:
        raise MeshError(f"{spec}: the layer has a CRS but the mesh's CRS is unknown (give --crs)")
    if src is not None and crs_wkt:
        src.SetAxisMappingStrategy(0)  # OAMS_TRADITIONAL_GIS_ORDER
        dst = _srs(crs_wkt)
        if not src.IsSame(dst):
            ct = _transform(src, dst)
            if box is not None:
                inv = _box_through(_transform(dst, src), box)
                lyr.SetSpatialFilterRect(*inv)
        elif box is not None:
            lyr.SetSpatialFilterRect(*box)
    elif box is not None:
        lyr.SetSpatialFilterRect(*box)
    out = []

    def walk(g):
        if g is None:
            return
        if g.GetGeometryCount() > 0:
            for i in range(g.GetGeometryCount()):
                walk(g.GetGeometryRef(i))
        elif g.GetPointCount() > 1:
            out.append(np.array(g.GetPoints())[:, :2])

    for feat in lyr:
        g = feat.GetGeometryRef()
        if g is None:
            continue
        g = g.Clone()
        if ct is not None:
            g.Transform(ct)
        walk(g)
    return out


def read_repairs(path):
    """(x, y, kind) of the repairs layer of an fdrmesh GeoPackage ([] when there is none)."""
    if not path.lower().endswith(".gpkg"):
        return []
    from osgeo import ogr

    ds = ogr.Open(path)
    lyr = ds.GetLayerByName("repairs") if ds is not None else None
    if lyr is None:
        return []
    out = []
    for feat in lyr:
        g = feat.GetGeometryRef()
        if g is not None:
            out.append((g.GetX(), g.GetY(), feat.GetFieldAsString("kind")))
    return out


# ----------------------------------------------------------------------------- metrics

def triangle_metrics(mesh):
    """Per-triangle angles (deg, (t,3)), circumcenters (t,2), circumradius, shortest edge."""
    p = mesh.xy[mesh.tris]  # (t, 3, 2)
    a, b, c = p[:, 0], p[:, 1], p[:, 2]

    def ang(apex, u, v):
        d1, d2 = u - apex, v - apex
        cr = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
        return np.degrees(np.arctan2(cr, np.einsum("ij,ij->i", d1, d2)))

    angles = np.stack([ang(a, b, c), ang(b, c, a), ang(c, a, b)], axis=1)
    d, e = b - a, c - a
    den = 2.0 * (d[:, 0] * e[:, 1] - d[:, 1] * e[:, 0])
    d2, e2 = (d * d).sum(1), (e * e).sum(1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = (e[:, 1] * d2 - d[:, 1] * e2) / den
        uy = (d[:, 0] * e2 - e[:, 0] * d2) / den
    center = a + np.stack([ux, uy], axis=1)
    radius = np.hypot(ux, uy)
    edges = np.stack([np.hypot(*(b - c).T), np.hypot(*(c - a).T), np.hypot(*(a - b).T)], axis=1)
    return angles, center, radius, edges


def nearest_neighbour(xy):
    """Distance from every vertex to the nearest other vertex (exact)."""
    n = len(xy)
    if n < 2:
        return np.full(n, np.inf)
    try:
        from scipy.spatial import cKDTree

        d, _ = cKDTree(xy).query(xy, k=2)
        return d[:, 1]
    except ImportError:
        # Blocked brute force keeps memory at ~block*n doubles without scipy.
        out = np.empty(n)
        for s in range(0, n, 512):
            blk = xy[s:s + 512]
            dd = ((blk[:, None, :] - xy[None, :, :]) ** 2).sum(-1)
            dd[np.arange(len(blk)), np.arange(s, s + len(blk))] = np.inf
            out[s:s + 512] = np.sqrt(dd.min(1))
        return out


def conformity(mesh, f=None):
    """c(x) = min(nn/f, f/nn) per vertex (FDR paper, Definition 2.1).

    Without f, the file's own f per node is used (an fdrmesh GeoPackage stores the run's spacing,
    which a raster-driven run has no expression for); None when the file stores none.
    """
    if f is None:
        fv = mesh.node_fields.get("f")
        if fv is None:
            return None
    else:
        fv = f(mesh.xy[:, 0], mesh.xy[:, 1])
    nn = nearest_neighbour(mesh.xy)
    with np.errstate(divide="ignore", invalid="ignore"):
        c = np.minimum(nn / fv, fv / nn)
    return c[np.isfinite(c)]


def r_over_f(mesh, f):
    """R/f(c) per triangle: from the file's R_over_f field, else from f at the circumcenter."""
    if f is None:
        v = mesh.tri_fields.get("R_over_f")
        return None if v is None else np.asarray(v)
    _, center, radius, _ = triangle_metrics(mesh)
    with np.errstate(divide="ignore", invalid="ignore"):
        return radius / f(center[:, 0], center[:, 1])
