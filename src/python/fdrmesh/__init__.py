"""fdrmesh: Functional Delaunay Refinement meshes from Python (numpy in, numpy out).

    import numpy as np, fdrmesh
    v = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    s = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])
    m = fdrmesh.triangulate(v, s, spacing=lambda x, y: 0.02 + 0.1 * x)
    m.vertices, m.triangles, m.report["max_R_over_f"]; m.write("square.2dm")

The meshes are the same, bit for bit, as the command line's (`fdrmesh mesh`) for the same inputs
and options. Errors raise fdrmesh.Error subclasses carrying .exit_code and the CLI's message.
"""
import json as _json
import numbers as _numbers
import warnings as _warnings

import numpy as _np

from . import _core
from ._core import __version__
from ._core import (Error, InternalError, UsageError, InputUnreadableError, InputMalformedError,
                    GeometryError, SpacingError, WorkLimitError, OutputError, CrsError, CheckError,
                    CancelledError)

__all__ = ["read_poly", "triangulate", "tetrahedralize", "mesh", "Mesh", "Error", "UsageError", "InputUnreadableError",
           "InputMalformedError", "GeometryError", "SpacingError", "WorkLimitError", "OutputError",
           "CrsError", "CheckError", "CancelledError", "InternalError", "MESH_OPTIONS"]

# Long options of `fdrmesh mesh` in snake_case -> (CLI key, type, repeatable, positional),
# generated from the CLI option table (src/cli/option_table.cpp).
MESH_OPTIONS = {key.replace("-", "_"): (key, typ, rep, pos)
                for key, typ, rep, pos, _names in _core._mesh_options()}


class Mesh:
    """A finished mesh. Arrays are read-only numpy views into the C++ result (no copy), except
    `vertices` when the mesh has a local origin (then origin + local_vertices, computed once).

    vertices (n,2) float64 world coordinates; local_vertices (n,2) and origin (x0, y0);
    triangles (t,3) 0-based, counter-clockwise; segments (m,2) constrained edges with
    segment_markers (m,) int32, segment_kinds (names: land, island, open, breakline, none) and
    segment_parts (input ring/line ids); vertex_markers (n,); spacing f at the vertices (n,);
    depths (n,) elevation positive up (GIS runs with a raster, else None); crs_wkt (GIS runs);
    report: dict with the keys of the JSON report (--report); repairs: list of dicts (GIS runs);
    written: files written during a GIS run; log: (level, message) pairs.
    """

    def __init__(self, core):
        self._m = core
        self._vertices = None
        self._report = None

    @property
    def vertices(self):
        if self._vertices is None:
            local = self._m.local_vertices
            ox, oy = self._m.origin
            if ox == 0 and oy == 0:
                self._vertices = local
            else:
                w = local + _np.array([ox, oy])
                w.flags.writeable = False
                self._vertices = w
        return self._vertices

    local_vertices = property(lambda self: self._m.local_vertices)
    origin = property(lambda self: self._m.origin)
    triangles = property(lambda self: self._m.triangles)
    segments = property(lambda self: self._m.segments)
    segment_markers = property(lambda self: self._m.segment_markers)
    segment_parts = property(lambda self: self._m.segment_parts)
    segment_kinds = property(lambda self: self._m.segment_kinds)
    vertex_markers = property(lambda self: self._m.vertex_markers)
    spacing = property(lambda self: self._m.spacing)
    depths = property(lambda self: self._m._z)
    crs_wkt = property(lambda self: self._m.crs_wkt)
    crs_name = property(lambda self: self._m.crs_name)
    repairs = property(lambda self: self._m.repairs)
    written = property(lambda self: self._m.written)
    log = property(lambda self: self._m.log)

    @property
    def report(self):
        if self._report is None:
            self._report = _json.loads(self._m._report_json)
        return self._report

    def write(self, path, format=None):
        """Writes the mesh: GPKG, 2DM, FORT14, MSH, UGRID, NODE or VTU, from the extension of
        `path` or `format` (as --of). Atomic; raises OutputError / UsageError."""
        self._m.write(str(path), format or "")

    def __repr__(self):
        return (f"<fdrmesh.Mesh {len(self._m.local_vertices)} vertices, {len(self._m.triangles)} triangles"
                + (f", CRS {self.crs_name}" if self.crs_name else "") + ">")


def _result(core):
    """Mesh of a finished run; its warnings (e.g. alpha*B >= 1) become RuntimeWarnings."""
    for level, message in core.log:
        if level >= 2:  # LogLevel::kWarning, kError
            _warnings.warn(message, RuntimeWarning, stacklevel=3)
    return Mesh(core)


def read_poly(path, markers=False):
    """Reads a Triangle .poly (or .node) file: (vertices (n,2) float64, segments (m,2) int64,
    holes (h,2) float64), 0-based. markers=True adds (vertex_markers (n,), segment_markers (m,))."""
    v, s, h, vm, sm, _no_vm = _core.read_poly(str(path))
    return (v, s, h, vm, sm) if markers else (v, s, h)


def _spacing_grid(fn, vertices, resolution):
    """Samples f(x, y) once, vectorised, on cell centres of a grid over the domain's box (one cell
    of margin all round); bilinear in between (the mesher's GridField)."""
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    size = float(max(hi - lo))
    if not size > 0:
        raise UsageError("the vertices span no area")
    d = size / int(resolution)
    nx = int(_np.ceil((hi[0] - lo[0]) / d)) + 2
    ny = int(_np.ceil((hi[1] - lo[1]) / d)) + 2
    x0, y0 = float(lo[0] - d), float(lo[1] - d)
    xs = x0 + (_np.arange(nx) + 0.5) * d
    ys = y0 + (_np.arange(ny) + 0.5) * d
    X, Y = _np.meshgrid(xs, ys)  # (ny, nx): row j is y_j, so values are row-major v[j*nx + i]
    vals = _np.broadcast_to(_np.asarray(fn(X, Y), dtype=_np.float64), X.shape)
    label = f"python {getattr(fn, '__name__', 'callable')} on a {nx}x{ny} grid"
    return (nx, ny, x0, y0, d, d, _np.ascontiguousarray(vals).ravel(), label)



def _spacing_arguments(spacing, v, resolution, default_spec, sample_grid):
    """(grid, spec) for the core from a `spacing` argument: None (the CLI's default), a number, a
    --spacing string or a callable sampled on a grid."""
    if spacing is None:
        return None, default_spec(v)
    if callable(spacing):
        return sample_grid(spacing, v, resolution), ""
    if isinstance(spacing, _numbers.Real) and not isinstance(spacing, bool):
        return None, repr(float(spacing))  # shortest round-trip form: the same double as on the command line
    if isinstance(spacing, str):
        return None, spacing
    raise UsageError(f"spacing must be None, a number, a string or a callable, not {type(spacing).__name__}")

def triangulate(vertices, segments=None, holes=None, spacing=None, bound=1.0, min_angle=0.0,
                max_steiner=20_000_000, convex_hull=False, *, segment_markers=None, vertex_markers=None,
                resolution=256, check=False, smooth=0):
    """Meshes a PSLG by Functional Delaunay Refinement: every triangle gets R/f(c) <= bound.

    vertices (n,2), segments (m,2) 0-based vertex pairs, holes (h,2) seed points (Triangle .poly
    semantics). spacing f: None (a twentieth of the box diagonal, the CLI's default), a number,
    a string as --spacing (expression in x, y or preset: "paper-f1", "0.1*paper-f2"), or a
    callable f(x, y) on numpy arrays, sampled in one call on a grid of `resolution` cells along
    the longer side of the domain. convex_hull: mesh the convex hull (--convex-hull). smooth:
    quality smoothing sweeps after refinement (--smooth; 0, the CLI's value for .poly inputs,
    keeps the FDR mesh as is).
    Returns a Mesh; the GIL is released while meshing."""
    v = _np.ascontiguousarray(vertices, dtype=_np.float64)
    grid, spec = _spacing_arguments(spacing, v, resolution, _core.default_spacing, _spacing_grid)
    seg = None if segments is None else _np.asarray(segments, dtype=_np.int64).reshape(-1, 2)
    hol = None if holes is None else _np.asarray(holes, dtype=_np.float64).reshape(-1, 2)
    sm = None if segment_markers is None else _np.asarray(segment_markers, dtype=_np.int32)
    vm = None if vertex_markers is None else _np.asarray(vertex_markers, dtype=_np.int32)
    return _result(_core._triangulate(v, seg, hol, sm, vm, spec, grid, float(bound), float(min_angle),
                                      int(max_steiner), bool(convex_hull), bool(check), int(smooth)))


def _spacing_grid3(fn, vertices, resolution):
    """Samples f(x, y, z) once, vectorised, on cell centres of a grid over the PLC's box (one cell
    of margin all round); trilinear in between (the mesher's GridField3)."""
    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    size = float(max(hi - lo))
    if not size > 0:
        raise UsageError("the vertices span no volume")
    d = size / int(resolution)
    n = [int(_np.ceil((hi[k] - lo[k]) / d)) + 2 for k in range(3)]
    o = [float(lo[k] - d) for k in range(3)]
    axes = [o[k] + (_np.arange(n[k]) + 0.5) * d for k in range(3)]
    Z, Y, X = _np.meshgrid(axes[2], axes[1], axes[0], indexing="ij")  # x fastest: v[(k*ny + j)*nx + i]
    vals = _np.broadcast_to(_np.asarray(fn(X, Y, Z), dtype=_np.float64), X.shape)
    label = f"python {getattr(fn, '__name__', 'callable')} on a {n[0]}x{n[1]}x{n[2]} grid"
    return (n[0], n[1], n[2], o[0], o[1], o[2], d, _np.ascontiguousarray(vals).ravel(), label)


def tetrahedralize(vertices, facets, holes=None, regions=None, spacing=None, bound=0.0, *,
                   facet_markers=None, max_vertices=0, resolution=64):
    """Tetrahedralizes a 3D PLC by Functional Delaunay Refinement: every tetrahedron gets
    R/f(c) <= bound (0: the 3D default, docs/3d.md).

    vertices (n,3); facets: a list, each facet a list of 0-based vertex ids (one polygon) or a list
    of such lists (polygons; 2 ids make a segment in the facet); holes (h,3) volume hole points;
    regions (r,4) rows x, y, z, attribute (or (r,5) with a volume bound); facet_markers: one int per
    facet. spacing f: None (a twentieth of the box diagonal, the CLI's default), a number, a string
    as --spacing (an expression in x, y, z, or "paper-f1", "0.5*paper-f2"), or a callable
    f(x, y, z) on numpy arrays, sampled in one call on a grid of `resolution` cells along the
    longer side of the box. The same input and spacing give the CLI's mesh.
    Returns a dict of numpy arrays: points (n,3), tets (t,4), materials (t,), faces (f,3),
    face_markers (f,), edges (e,2), edge_markers (e,), and stats (the refinement's counts)."""
    v = _np.ascontiguousarray(vertices, dtype=_np.float64)
    grid, spec = _spacing_arguments(spacing, v, resolution, _core.default_spacing3, _spacing_grid3)
    hol = None if holes is None else _np.asarray(holes, dtype=_np.float64).reshape(-1, 3)
    reg = None if regions is None else _np.atleast_2d(_np.asarray(regions, dtype=_np.float64))
    fm = None if facet_markers is None else [int(m) for m in facet_markers]
    return _core._tetrahedralize(v, list(facets), fm, hol, reg, spec, grid, float(bound), int(max_vertices))


def _arg(value):
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _mesh_args(input, options):
    """The command line of `fdrmesh mesh INPUT ...` from snake_case options."""
    args = []
    for name, value in options.items():
        if name == "horizons":  # the plural reads better for a list; --horizon repeated
            name = "horizon"
        if name not in MESH_OPTIONS:
            raise UsageError(f"unknown option '{name}' (fdrmesh.MESH_OPTIONS lists them)")
        key, typ, repeat, positional = MESH_OPTIONS[name]
        if value is None or positional:
            continue
        if typ == "flag":
            if value:
                args.append("--" + key)
            continue
        if typ == "bbox" and not isinstance(value, str):
            value = ",".join(_arg(float(x)) for x in value)
        values = list(value) if repeat and isinstance(value, (list, tuple)) else [value]
        for x in values:
            args += ["--" + key, _arg(x)]
    if input is not None:
        args += ["--", str(input)]
    return args


def _volume(result):
    """The dict of a terrain run; its warnings become RuntimeWarnings, its report a dict."""
    for level, message in result["log"]:
        if level >= 2:  # LogLevel::kWarning, kError
            _warnings.warn(message, RuntimeWarning, stacklevel=3)
    result["report"] = _json.loads(result.pop("report_json"))
    return result


def mesh(input=None, **options):
    """Runs the GIS pipeline, as `fdrmesh mesh INPUT --option value ...`: the options are the
    command line's long options in snake_case (layer, raster, hmin, hmax, open_boundary,
    breaklines, t_srs, output=[...], report, check=True, ...; see fdrmesh.MESH_OPTIONS and
    `fdrmesh --help`). Flags take True/False, repeatable options a list, extent a 4-tuple.
    Returns a Mesh with depths, crs_wkt, segment kinds (boundaries), repairs and report.

    With dem=... it is a terrain volume (docs/terrain3d.md), as `fdrmesh mesh DOMAIN --dem DEM
    --base Z --horizon H ...`: base (an elevation or a raster), horizons (a list of rasters, from
    the top down), depth_grade, min_thickness, wells (an OGR source: points with top/bottom or
    depth_from/depth_to fields, or 3D lines), well_spacing, bound, check; without INPUT the box of
    the DEM's valid data is the domain. Returns the CLI's tetrahedra as a dict
    (world coordinates of the working CRS): points (n,3), tets (t,4), materials (t,) (layer i from
    the top is material i), faces (f,3) with face_markers (f,) (1 top, 2 base, 3 side, 4.. the
    horizons, then one per well named well_<name>), edges (e,2) with edge_markers (e,) (a well's
    pieces carry its marker), material_names and marker_names (name of material / marker m at m),
    cell_fields (r_over_f, radius_edge, min_dihedral_deg per tet), report (the JSON report, with
    `layers`), written (files of output=[...]) and log."""
    args = _mesh_args(input, options)
    if options.get("dem") is not None:
        return _volume(_core._mesh3(args))
    return _result(_core._mesh(args))
