"""fdrmesh Python module: the same mesh as the CLI and the C++ API bit for bit, callable spacing,
GIS runs, writers, errors. Run by CTest (`python_module`) with PYTHONPATH=build/python."""
import os
import subprocess
import threading

import numpy as np
import pytest

import fdrmesh

FDRMESH = os.environ.get("FDRMESH", "fdrmesh")
API_DUMP = os.environ.get("FDR_API_DUMP")
TESTDATA = os.environ.get("FDR_TESTDATA", os.path.join(os.path.dirname(__file__), "../../../testdata"))
SQUARE = os.path.join(TESTDATA, "poly", "square10.poly")
HOLE = os.path.join(TESTDATA, "poly", "square_with_hole.poly")


def read_node_ele(base):
    """Vertices (17-digit text as written by the CLI) and 0-based triangles of base.node/.ele."""
    def rows(path):
        out = []
        for line in open(path):
            line = line.split("#", 1)[0].split()
            if line:
                out.append(line)
        return out
    node, ele = rows(base + ".node"), rows(base + ".ele")
    n, first = int(node[0][0]), None
    v = np.array([[float(r[1]), float(r[2])] for r in node[1:n + 1]])
    ids = [int(r[0]) for r in node[1:n + 1]]
    first = ids[0]
    t = np.array([[int(x) - first for x in r[1:4]] for r in ele[1:int(ele[0][0]) + 1]])
    return v, t


@pytest.mark.parametrize("poly,spacing", [(SQUARE, "paper-f1"), (HOLE, None), (SQUARE, "0.35")])
def test_same_mesh_as_cli_and_cpp(tmp_path, poly, spacing):
    base = str(tmp_path / "cli")
    cmd = [FDRMESH, "mesh", poly, "-o", base + ".node", "-q"] + (["--spacing", spacing] if spacing else [])
    subprocess.run(cmd, check=True)
    v_cli, t_cli = read_node_ele(base)

    v, s, h, vm, sm = fdrmesh.read_poly(poly, markers=True)
    m = fdrmesh.triangulate(v, s, h, spacing=None if spacing is None else
                            (float(spacing) if spacing[0].isdigit() else spacing),
                            segment_markers=sm, vertex_markers=vm)
    assert np.array_equal(m.triangles, t_cli)
    assert np.array_equal(m.vertices, v_cli)  # exact: 17 significant digits round-trip

    # The mesh written by Python is the CLI's file, byte for byte.
    m.write(str(tmp_path / "py.node"))
    for ext in (".node", ".ele"):
        assert open(str(tmp_path / ("py" + ext))).read() == open(base + ext).read()

    # The C++ API (fdr::triangulate) prints the same vertices and triangles.
    if API_DUMP and spacing:
        out = subprocess.run([API_DUMP, poly, spacing], check=True, capture_output=True, text=True).stdout.split("\n")
        nv, nt = map(int, out[0].split())
        v_cpp = np.array([[float(x) for x in line.split()] for line in out[1:1 + nv]])
        t_cpp = np.array([[int(x) for x in line.split()] for line in out[1 + nv:1 + nv + nt]])
        assert np.array_equal(v_cpp, m.vertices) and np.array_equal(t_cpp, m.triangles)


def test_mesh_arrays_and_report():
    v, s, h = fdrmesh.read_poly(SQUARE)
    assert v.dtype == np.float64 and v.shape[1] == 2 and s.shape[1] == 2 and h.shape == (0, 2)
    m = fdrmesh.triangulate(v, s, h, spacing="paper-f1")
    t = m.triangles
    assert t.shape[1] == 3 and not t.flags.writeable and not t.flags.owndata  # a view, no copy
    assert m.local_vertices.base is not None
    p = m.vertices[t]
    area2 = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 1, 1] - p[:, 0, 1]) * (p[:, 2, 0] - p[:, 0, 0])
    assert (area2 > 0).all()  # counter-clockwise
    assert m.report["triangles"] == len(t) and m.report["vertices"] == len(m.vertices)
    assert m.report["bad_triangles"] == 0
    assert m.segments.shape == (len(m.segment_markers), 2) and len(m.segment_kinds) == len(m.segments)
    assert m.depths is None and m.crs_wkt is None
    assert abs(m.report["area"] - 100.0) < 1e-9


def test_callable_spacing_is_sampled_once_vectorised():
    calls = []

    def f(x, y):
        calls.append(np.shape(x))
        return 0.2 + 0.05 * x

    v = np.array([[0, 0], [10, 0], [10, 10], [0, 10]], float)
    s = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])
    m = fdrmesh.triangulate(v, s, spacing=f, resolution=64)
    assert len(calls) == 1 and len(calls[0]) == 2 and calls[0][1] >= 64
    assert m.report["bad_triangles"] == 0
    # Finer where f is small: more vertices in the left tenth than in the right tenth.
    x = m.vertices[:, 0]
    assert (x < 1).sum() > 2 * (x > 9).sum()
    # A constant callable equals a constant spacing in size.
    m2 = fdrmesh.triangulate(v, s, spacing=lambda x, y: 1.0)
    assert m2.report["bad_triangles"] == 0 and m2.report["max_R_over_f"] <= 1.0


def test_two_threads():
    v, s, h = fdrmesh.read_poly(SQUARE)
    out = []
    th = [threading.Thread(target=lambda: out.append(fdrmesh.triangulate(v, s, h, spacing=0.2))) for _ in range(2)]
    for t in th:
        t.start()
    for t in th:
        t.join()
    assert len(out) == 2 and np.array_equal(out[0].triangles, out[1].triangles)


def test_warning_when_alpha_b_too_large():
    v, s, h = fdrmesh.read_poly(SQUARE)
    with pytest.warns(RuntimeWarning, match="alpha"):
        fdrmesh.triangulate(v, s, spacing="0.3 + 0.9 * x", bound=1.5)


def test_errors():
    with pytest.raises(fdrmesh.InputUnreadableError) as e:
        fdrmesh.read_poly(os.path.join(TESTDATA, "poly", "does_not_exist.poly"))
    assert e.value.exit_code == 3 and "does_not_exist.poly" in str(e.value)
    v, s, h = fdrmesh.read_poly(SQUARE)
    with pytest.raises(fdrmesh.UsageError) as e:
        fdrmesh.triangulate(v, s, spacing=1, bound=-1)
    assert e.value.exit_code == 2 and isinstance(e.value, ValueError) and isinstance(e.value, fdrmesh.Error)
    with pytest.raises(fdrmesh.WorkLimitError) as e:
        fdrmesh.triangulate(v, s, spacing=0.01, max_steiner=100)
    assert e.value.exit_code == 7
    with pytest.raises(fdrmesh.SpacingError):
        fdrmesh.triangulate(v, s, spacing=lambda x, y: -1.0 + 0 * x)
    with pytest.raises(fdrmesh.InputMalformedError):
        fdrmesh.triangulate(v, [[0, 99]], spacing=1)
    with pytest.raises(fdrmesh.GeometryError):
        fdrmesh.triangulate(np.array([[0, 0], [2, 2], [0, 2], [2, 0]], float), [[0, 1], [2, 3]], spacing=1)
    with pytest.raises(fdrmesh.UsageError):
        fdrmesh.mesh(SQUARE, no_such_option=1)
    # The same message as the command line.
    cli = subprocess.run([FDRMESH, "mesh", SQUARE, "--bound", "abc"], capture_output=True, text=True)
    with pytest.raises(fdrmesh.UsageError) as e:
        fdrmesh.mesh(SQUARE, bound="abc")
    assert cli.returncode == 2 and cli.stderr.strip() == f"ERROR 2: {e.value}"



def test_convex_hull_meshes_a_point_set():
    # Triangle's -c (issue 10): the convex hull of the vertices bounds the domain.
    pts = np.array([[0, 0], [4, 0], [4, 3], [0, 3], [2, 1.5], [1, 2]], dtype=float)
    with pytest.raises(fdrmesh.GeometryError):
        fdrmesh.triangulate(pts, np.array([[4, 5]]), spacing=1)  # a dangling breakline: no domain
    m = fdrmesh.triangulate(pts, np.array([[4, 5]]), spacing=1, convex_hull=True)
    a = m.vertices[m.triangles]
    area = 0.5 * np.abs((a[:, 1, 0] - a[:, 0, 0]) * (a[:, 2, 1] - a[:, 0, 1]) - (a[:, 1, 1] - a[:, 0, 1]) * (a[:, 2, 0] - a[:, 0, 0]))
    assert abs(area.sum() - 12.0) < 1e-9


def test_mesh_poly_equals_cli(tmp_path):
    base = str(tmp_path / "cli")
    subprocess.run([FDRMESH, "mesh", SQUARE, "--spacing", "paper-f2", "--min-angle", "20", "-o", base + ".node", "-q"],
                   check=True)
    m = fdrmesh.mesh(SQUARE, spacing="paper-f2", min_angle=20.0)
    v_cli, t_cli = read_node_ele(base)
    assert np.array_equal(m.triangles, t_cli) and np.array_equal(m.vertices, v_cli)


GOM = os.path.join(TESTDATA, "gulf_of_maine")


@pytest.mark.skipif(not os.path.isdir(GOM), reason="testdata/gulf_of_maine absent")
def test_mesh_gis_equals_cli_and_writes_every_format(tmp_path):
    g = os.path.join(GOM, "gulf_of_maine.gpkg")
    tif = os.path.join(GOM, "gulf_of_maine_etopo5.tif")
    base = str(tmp_path / "cli")
    subprocess.run([FDRMESH, "mesh", g, "--layer", "water", "--open-boundary", g, "--open-boundary-layer",
                    "open_boundary", "--raster", tif, "--hmin", "3000", "-o", base + ".node", "-q"], check=True)
    m = fdrmesh.mesh(g, layer="water", open_boundary=g, open_boundary_layer="open_boundary", raster=tif, hmin=3000)
    v_cli, t_cli = read_node_ele(base)
    assert np.array_equal(m.triangles, t_cli)
    assert np.array_equal(m.vertices, v_cli)
    assert m.depths is not None and np.isfinite(m.depths).all() and len(m.depths) == len(m.vertices)
    assert m.crs_wkt and m.crs_name
    assert {"land", "open"} <= set(m.segment_kinds) <= {"land", "island", "open", "breakline", "none"}
    assert isinstance(m.repairs, list) and m.report["triangles"] == len(m.triangles)
    m.write(str(tmp_path / "py.node"))
    for ext in (".node", ".ele"):
        assert open(str(tmp_path / ("py" + ext))).read() == open(base + ext).read()
    for name in ("m.gpkg", "m.2dm", "m.14", "m.msh", "m.nc", "m.vtu"):
        m.write(str(tmp_path / name))
        assert os.path.getsize(str(tmp_path / name)) > 0
    m.write(str(tmp_path / "forced.txt"), format="2DM")
    assert open(str(tmp_path / "forced.txt")).readline().startswith("MESH2D")


def test_mesh_options_from_the_cli_table(tmp_path):
    assert {"layer", "raster", "hmin", "hmax", "open_boundary", "breaklines", "t_srs", "output", "check"} <= set(
        fdrmesh.MESH_OPTIONS)
    a, b = str(tmp_path / "a.2dm"), str(tmp_path / "b.node")
    m = fdrmesh.mesh(SQUARE, spacing=0.5, output=[a, b], check=True, report=str(tmp_path / "r.json"))
    assert m.written == [a, b, str(tmp_path / "r.json")] and os.path.exists(str(tmp_path / "b.ele"))
    land = os.path.join(TESTDATA, "chesapeake", "shp", "chesapeake_mouth_land.shp")
    if os.path.exists(land):
        m = fdrmesh.mesh(land=land, extent=(-76.6, 36.75, -75.6, 37.75))
        assert len(m.triangles) > 0 and m.crs_wkt
        with pytest.raises(fdrmesh.UsageError):
            fdrmesh.mesh(land=land, extent=(-75.6, 36.75, -76.6, 37.75))  # XMIN > XMAX, the CLI's check


def test_smooth_as_the_cli(tmp_path):
    """triangulate(smooth=N) runs the CLI's smoothing stage (the same core function as --smooth N)."""
    base = str(tmp_path / "cli")
    subprocess.run([FDRMESH, "mesh", SQUARE, "--spacing", "paper-f1", "--smooth", "3", "-o", base + ".node", "-q"],
                   check=True)
    v_cli, t_cli = read_node_ele(base)
    v, s, h = fdrmesh.read_poly(SQUARE)
    m = fdrmesh.triangulate(v, s, h, spacing="paper-f1", smooth=3)
    assert np.array_equal(m.triangles, t_cli) and np.array_equal(m.vertices, v_cli)
    with pytest.raises(fdrmesh.UsageError):
        fdrmesh.triangulate(v, s, h, spacing="paper-f1", smooth=101)
