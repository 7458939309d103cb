"""pytest for the plot scripts: readers, spacing expressions, PNG output, paper_figures.sh plumbing."""
import json
import os
import stat
import struct
import subprocess
import sys
import textwrap

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", ".."))
TINY = os.path.join(ROOT, "testdata", "plot")
PY = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
sys.path.insert(0, HERE)
import fdrplot  # noqa: E402


def run(script, *args, env=None):
    return subprocess.run([PY, os.path.join(HERE, script), *args], capture_output=True, text=True,
                          env=env, timeout=120)


def png_size(path):
    with open(path, "rb") as fh:
        head = fh.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return struct.unpack(">II", head[16:24])


def assert_png(path, width, height, min_kb=8):
    assert os.path.exists(path), path
    assert os.path.getsize(path) > min_kb * 1024, f"{path}: only {os.path.getsize(path)} bytes"
    assert png_size(path) == (width, height)
    import matplotlib.image as mpimg

    img = mpimg.imread(path)
    colours = np.unique((img[..., :3] * 255).astype(np.uint8).reshape(-1, 3), axis=0)
    assert len(colours) > 20, f"{path}: only {len(colours)} distinct colours"


# ---------------------------------------------------------------- library

def test_spacing_presets_and_syntax():
    f1 = fdrplot.spacing_function("paper-f1")
    assert f1(5.0, 5.0) == pytest.approx(0.1)
    assert f1(0.0, 0.0) == pytest.approx(1.1)
    f2 = fdrplot.spacing_function("paper-f2")
    assert f2(0.0, 0.0) == pytest.approx(0.1)
    assert f2(np.pi / 8, np.pi / 8) == pytest.approx(0.1 * np.sqrt(2))
    assert fdrplot.spacing_function("3*paper-f1")(5, 5) == pytest.approx(0.3)
    g = fdrplot.spacing_function("max(x, y, 1)^2 + min(abs(x), 2) - sqrt(4) + exp(0) + log(1)")
    assert g(3.0, -1.0) == pytest.approx(9 + 2 - 2 + 1)
    assert g(np.array([0.0, 3.0]), 0.0).tolist() == pytest.approx([1 + 0 - 1, 9 + 2 - 1])
    assert fdrplot.spacing_function("0.5")(np.zeros(3), np.zeros(3)).shape == (3,)
    for bad in ("__import__('os')", "x +* ", "z+1", "x; y", "x.real"):
        with pytest.raises(fdrplot.MeshError):
            fdrplot.spacing_function(bad)(1.0, 1.0)


def test_readers_agree_on_tiny_lattice():
    a = fdrplot.read_mesh(os.path.join(TINY, "tiny.node"))
    b = fdrplot.read_mesh(os.path.join(TINY, "tiny.2dm"))
    for m in (a, b):
        assert m.xy.shape == (9, 2) and m.tris.shape == (8, 3)
        angles, center, radius, edges = fdrplot.triangle_metrics(m)
        assert angles.min() == pytest.approx(45) and angles.max() == pytest.approx(90)
        assert angles.sum(1) == pytest.approx(np.full(8, 180.0))
        assert radius == pytest.approx(np.full(8, np.sqrt(0.5)))
        assert m.z is not None and m.z[4] == pytest.approx(-2.5)
    assert len(b.segments) == 8  # the closed boundary nodestring
    c = fdrplot.conformity(a, lambda x, y: np.ones_like(x))
    assert c == pytest.approx(np.ones(9))
    c = fdrplot.conformity(a, lambda x, y: np.full_like(x, 0.5))
    assert c == pytest.approx(np.full(9, 0.5))
    rf = fdrplot.r_over_f(a, lambda x, y: x + 1)
    assert sorted(rf)[0] == pytest.approx(np.sqrt(0.5) / 2.5)


def test_nearest_neighbour_exact():
    rng = np.random.default_rng(3)
    xy = rng.random((300, 2)) ** 3
    nn = fdrplot.nearest_neighbour(xy)
    d = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
    np.fill_diagonal(d, np.inf)
    assert nn == pytest.approx(d.min(1))


def test_bad_files_name_file_and_line(tmp_path):
    p = tmp_path / "bad.node"
    p.write_text("3 2 0 0\n1 0 0\n2 1 zero\n3 0 1\n")
    (tmp_path / "bad.ele").write_text("1 3 0\n1 1 2 3\n")
    with pytest.raises(fdrplot.MeshError, match=r"bad.node:3"):
        fdrplot.read_mesh(str(p))
    q = tmp_path / "m.2dm"
    q.write_text("MESH2D\nE3T 1 1 2 9 1\nND 1 0 0 0\nND 2 1 0 0\nND 3 0 1 0\n")
    with pytest.raises(fdrplot.MeshError, match=r"m.2dm:2: E3T references missing node 9"):
        fdrplot.read_mesh(str(q))
    with pytest.raises(fdrplot.MeshError, match="unknown mesh format"):
        fdrplot.read_mesh(str(tmp_path / "x.obj"))


# ---------------------------------------------------------------- scripts

@pytest.mark.parametrize("color", ["min_angle", "r_over_f", "depth", "none"])
def test_plot_mesh_node_ele(tmp_path, color):
    out = tmp_path / f"{color}.png"
    r = run("plot_mesh.py", os.path.join(TINY, "tiny.node"), "-o", str(out), "--color", color,
            "--spacing", "0.5+0.1*x^2", "--bound", "1", "--size", "6", "--dpi", "100")
    assert r.returncode == 0, r.stderr
    assert_png(str(out), 600, 600)


def test_plot_mesh_2dm(tmp_path):
    out = tmp_path / "m.png"
    r = run("plot_mesh.py", os.path.join(TINY, "tiny.2dm"), "-o", str(out), "--color", "depth")
    assert r.returncode == 0, r.stderr
    assert_png(str(out), 1200, 1200)


def test_plot_mesh_gpkg(tmp_path):
    ogr = pytest.importorskip("osgeo.ogr")
    mesh = fdrplot.read_mesh(os.path.join(TINY, "tiny.node"))
    path = str(tmp_path / "mesh.gpkg")
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    nodes = ds.CreateLayer("nodes", geom_type=ogr.wkbPoint)
    nodes.CreateField(ogr.FieldDefn("z", ogr.OFTReal))
    for (x, y), z in zip(mesh.xy, mesh.z):
        f = ogr.Feature(nodes.GetLayerDefn())
        f.SetField("z", float(z))
        f.SetGeometry(ogr.CreateGeometryFromWkt(f"POINT ({x} {y})"))
        nodes.CreateFeature(f)
    tris = ds.CreateLayer("triangles", geom_type=ogr.wkbPolygon)
    for n in ("area", "min_angle", "R_over_f"):
        tris.CreateField(ogr.FieldDefn(n, ogr.OFTReal))
    for k, t in enumerate(mesh.tris):
        p = mesh.xy[list(t) + [t[0]]]
        f = ogr.Feature(tris.GetLayerDefn())
        f.SetField("area", 0.5)
        f.SetField("min_angle", 45.0)
        f.SetField("R_over_f", 0.1 * k)
        f.SetGeometry(ogr.CreateGeometryFromWkt("POLYGON ((" + ",".join(f"{x} {y}" for x, y in p) + "))"))
        tris.CreateFeature(f)
    bl = ds.CreateLayer("boundaries", geom_type=ogr.wkbLineString)
    bl.CreateField(ogr.FieldDefn("kind", ogr.OFTString))
    for kind, wkt in (("land", "LINESTRING (0 0,2 0,2 2)"), ("open", "LINESTRING (2 2,0 2,0 0)")):
        f = ogr.Feature(bl.GetLayerDefn())
        f.SetField("kind", kind)
        f.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        bl.CreateFeature(f)
    ds = None
    m = fdrplot.read_mesh(path)
    assert m.xy.shape == (9, 2) and m.tris.shape == (8, 3)
    assert m.tri_fields["R_over_f"][7] == pytest.approx(0.7)
    assert {k for _, _, k in m.segments} == {"land", "open"}
    out = tmp_path / "g.png"
    r = run("plot_mesh.py", path, "-o", str(out), "--color", "r_over_f", "--size", "5", "--dpi", "100")
    assert r.returncode == 0, r.stderr
    assert_png(str(out), 500, 500)


def test_plot_mesh_errors(tmp_path):
    r = run("plot_mesh.py", str(tmp_path / "missing.node"), "-o", str(tmp_path / "x.png"))
    assert r.returncode == 1 and "missing.node: no such file" in r.stderr
    r = run("plot_mesh.py", os.path.join(TINY, "tiny.node"), "-o", str(tmp_path / "x.png"), "--color", "r_over_f")
    assert r.returncode == 1 and "needs --spacing" in r.stderr
    r = run("plot_mesh.py", os.path.join(TINY, "tiny.node"), "-o", str(tmp_path / "x.png"), "--color", "r_over_f",
            "--spacing", "open('x')")
    assert r.returncode == 1 and "unknown name 'open'" in r.stderr
    assert not (tmp_path / "x.png").exists()


def _utm_mesh_gpkg(path, shift, scale=1000.0):
    """tiny.node scaled and shifted into UTM 18N (EPSG:32618), written as an fdrmesh-like GPKG."""
    ogr = pytest.importorskip("osgeo.ogr")
    from osgeo import osr

    mesh = fdrplot.read_mesh(os.path.join(TINY, "tiny.node"))
    xy = mesh.xy * scale + np.array(shift)
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(32618)
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    tris = ds.CreateLayer("triangles", srs=srs, geom_type=ogr.wkbPolygon)
    for t in mesh.tris:
        p = xy[list(t) + [t[0]]]
        f = ogr.Feature(tris.GetLayerDefn())
        f.SetGeometry(ogr.CreateGeometryFromWkt("POLYGON ((" + ",".join(f"{x} {y}" for x, y in p) + "))"))
        tris.CreateFeature(f)
    rep = ds.CreateLayer("repairs", srs=srs, geom_type=ogr.wkbPoint)
    rep.CreateField(ogr.FieldDefn("kind", ogr.OFTString))
    f = ogr.Feature(rep.GetLayerDefn())
    f.SetField("kind", "island_removed")
    f.SetGeometry(ogr.CreateGeometryFromWkt(f"POINT ({xy[4][0]} {xy[4][1]})"))
    rep.CreateFeature(f)
    ds = None
    return xy


def test_coast_overlay_is_reprojected(tmp_path):
    pytest.importorskip("osgeo.ogr")
    coast = tmp_path / "coast.geojson"
    coast.write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {}, "geometry": {"type": "LineString",
                                                           "coordinates": [[-75.0, 37.0], [-74.99, 37.01]]}},
        {"type": "Feature", "properties": {}, "geometry": {"type": "Polygon", "coordinates": [
            [[-75.01, 37.0], [-75.0, 37.0], [-75.0, 37.01], [-75.01, 37.0]]]}}]}))
    lines = fdrplot.read_lines(str(coast), fdrplot._srs("EPSG:32618").ExportToWkt())
    assert len(lines) == 2 and lines[0].shape == (2, 2) and lines[1].shape == (4, 2)
    # lon -75 is UTM 18N's central meridian: easting 500 000 m; lat 37: northing ~4 095 000 m.
    assert lines[0][0][0] == pytest.approx(500000.0, abs=1e-6)
    assert 4094000 < lines[0][0][1] < 4096000
    # A spatial filter in the mesh CRS keeps only what meets the box (the polygon lies west of it).
    box = (499990.0, 4094000.0, 502000.0, 4097000.0)
    assert len(fdrplot.read_lines(str(coast), fdrplot._srs("EPSG:32618").ExportToWkt(), box)) == 2
    west = (499000.0, 4094000.0, 499500.0, 4097000.0)
    assert len(fdrplot.read_lines(str(coast), fdrplot._srs("EPSG:32618").ExportToWkt(), west)) == 1
    # FILE:LAYER
    assert len(fdrplot.read_lines(f"{coast}:coast", allow_unknown_crs=True)) == 2
    with pytest.raises(fdrplot.MeshError, match="mesh's CRS is unknown"):
        fdrplot.read_lines(f"{coast}:coast")
    with pytest.raises(fdrplot.MeshError, match="no layer 'nope'"):  # before the CRS check
        fdrplot.read_lines(f"{coast}:nope")
    with pytest.raises(fdrplot.MeshError, match="no such file"):
        fdrplot.read_lines(str(tmp_path / "missing.shp:layer"))
    # A lon/lat window in the mesh CRS.
    x0, y0, x1, y1 = fdrplot.lonlat_box_to_crs((-75.01, 37.0, -75.0, 37.01), fdrplot._srs("EPSG:32618").ExportToWkt())
    assert x1 == pytest.approx(500000.0, abs=1e-6) and 880 < x1 - x0 < 900 and 1100 < y1 - y0 < 1120


def test_plot_mesh_bbox_window(tmp_path):
    out = tmp_path / "zoom.png"
    r = run("plot_mesh.py", os.path.join(TINY, "tiny.node"), "-o", str(out), "--bbox", "0.5,0.5,1.5,1.0",
            "--size", "6", "--dpi", "100")
    assert r.returncode == 0, r.stderr
    # The panel takes the window's shape: 6 in wide, 6 * 0.5 + 1.2 in high.
    assert_png(str(out), 600, 420, min_kb=4)
    for bad, msg in ((["--bbox", "1,1,0,0"], "XMIN < XMAX"), (["--bbox", "a,b"], "expected XMIN,YMIN,XMAX,YMAX"),
                     (["--bbox-lonlat", "-75.1,37,-75,37.1"], "needs the mesh's CRS"),
                     (["--bbox", "0,0,1,1", "--bbox-lonlat", "0,0,1,1"], "either --bbox or --bbox-lonlat"),
                     (["--coast", str(tmp_path / "nope.gpkg")], "nope.gpkg: no such file")):
        r = run("plot_mesh.py", os.path.join(TINY, "tiny.node"), "-o", str(tmp_path / "x.png"), *bad)
        assert r.returncode == 1 and msg in r.stderr, (bad, r.stderr)
    assert not (tmp_path / "x.png").exists()


def test_plot_mesh_compare_with_coast_and_lonlat_window(tmp_path):
    pytest.importorskip("osgeo.ogr")
    a, b = str(tmp_path / "a.gpkg"), str(tmp_path / "b.gpkg")
    _utm_mesh_gpkg(a, (499000.0, 4094000.0))
    _utm_mesh_gpkg(b, (499000.0, 4094000.0), scale=900.0)
    coast = tmp_path / "coast.geojson"
    coast.write_text(json.dumps({"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {}, "geometry": {"type": "LineString",
                                                           "coordinates": [[-75.02, 36.99], [-74.98, 37.0]]}}]}))
    out = tmp_path / "cmp.png"
    r = run("plot_mesh.py", a, "--compare", b, "--coast", f"{coast}:coast", "--bbox-lonlat", "-75.012,36.995,-74.99,37.01",
            "--title", "default", "--compare-title", "--keep-coast", "--repairs", "--size", "4", "--dpi", "100",
            "-o", str(out))
    assert r.returncode == 0, r.stderr
    w, h = png_size(str(out))
    assert abs(w - (2 * 400 + 120)) <= 1  # two panels and the shared colorbar
    assert 300 < h <= 800
    r = run("plot_mesh.py", os.path.join(TINY, "tiny.2dm"), "--coast", str(coast), "-o", str(tmp_path / "u.png"))
    assert r.returncode == 1 and "mesh's CRS is unknown (give --crs)" in r.stderr
    # A 2DM without CRS: --crs makes the lon/lat window usable.
    r = run("plot_mesh.py", os.path.join(TINY, "tiny.2dm"), "--crs", "EPSG:32618", "--bbox-lonlat",
            "-79.5,0,-79.49,0.00001", "-o", str(tmp_path / "c.png"), "--size", "3", "--dpi", "50")
    assert r.returncode == 0, r.stderr


def test_plot_histograms(tmp_path):
    out = tmp_path / "h.png"
    r = run("plot_histograms.py", os.path.join(TINY, "tiny.node"), os.path.join(TINY, "tiny.2dm"), "-o", str(out),
            "--spacing", "paper-f1", "--labels", "node,2dm", "--dpi", "100")
    assert r.returncode == 0, r.stderr
    assert_png(str(out), 1500, 450)
    r = run("plot_histograms.py", os.path.join(TINY, "tiny.node"), "-o", str(out), "--labels", "a,b")
    assert r.returncode == 1 and "--labels has 2 entries for 1 meshes" in r.stderr


def _lattice_gpkg(path, node_f=True, r_over_f=True):
    """tiny.node as an fdrmesh-like GeoPackage storing f per node and/or R/f(c) per triangle."""
    ogr = pytest.importorskip("osgeo.ogr")
    mesh = fdrplot.read_mesh(os.path.join(TINY, "tiny.node"))
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(path)
    nodes = ds.CreateLayer("nodes", geom_type=ogr.wkbPoint)
    if node_f:
        nodes.CreateField(ogr.FieldDefn("f", ogr.OFTReal))
    for x, y in mesh.xy:
        f = ogr.Feature(nodes.GetLayerDefn())
        if node_f:
            f.SetField("f", 2.0)  # nearest neighbour 1 everywhere: conformity 0.5
        f.SetGeometry(ogr.CreateGeometryFromWkt(f"POINT ({x} {y})"))
        nodes.CreateFeature(f)
    tris = ds.CreateLayer("triangles", geom_type=ogr.wkbPolygon)
    if r_over_f:
        tris.CreateField(ogr.FieldDefn("R_over_f", ogr.OFTReal))
    for t in mesh.tris:
        p = mesh.xy[list(t) + [t[0]]]
        f = ogr.Feature(tris.GetLayerDefn())
        if r_over_f:
            f.SetField("R_over_f", 0.25)
        f.SetGeometry(ogr.CreateGeometryFromWkt("POLYGON ((" + ",".join(f"{x} {y}" for x, y in p) + "))"))
        tris.CreateFeature(f)
    ds = None


def test_histograms_use_the_spacing_stored_in_the_gpkg(tmp_path):
    """A raster-driven run has no --spacing expression: the third panel comes from the file's own f."""
    import plot_histograms

    path = str(tmp_path / "f.gpkg")
    _lattice_gpkg(path)
    m = fdrplot.read_mesh(path)
    assert m.node_fields["f"] == pytest.approx(np.full(9, 2.0))
    assert fdrplot.conformity(m) == pytest.approx(np.full(9, 0.5))
    assert plot_histograms.third_panel_kind([m], None) == "conformity"
    only_rf = str(tmp_path / "rf.gpkg")
    _lattice_gpkg(only_rf, node_f=False)
    m2 = fdrplot.read_mesh(only_rf)
    assert "f" not in m2.node_fields and fdrplot.conformity(m2) is None
    assert plot_histograms.third_panel_kind([m2], None) == "r_over_f"
    bare = fdrplot.read_mesh(os.path.join(TINY, "tiny.node"))
    assert plot_histograms.third_panel_kind([bare], None) is None
    assert plot_histograms.third_panel_kind([bare], lambda x, y: x) == "conformity"
    out = tmp_path / "h.png"
    r = run("plot_histograms.py", path, "-o", str(out), "--dpi", "100")
    assert r.returncode == 0, r.stderr
    assert_png(str(out), 1500, 450)
    # The legend sits away from the bars.
    assert plot_histograms.legend_corner([np.full(10, 55.0)], 0, 60) == "upper left"
    assert plot_histograms.legend_corner([np.full(10, 65.0)], 60, 180) == "upper right"


def test_legend_goes_to_an_empty_corner_or_below(tmp_path):
    """The legend never covers the mesh: an empty corner when there is one, else below the panel."""
    import plot_mesh

    # An L-shaped mesh: the lower-left quadrant of [0,2]^2 is empty.
    xy = np.array([[1, 0], [2, 0], [2, 1], [1, 1], [0, 1], [0, 2], [1, 2], [2, 2]], float)
    tris = np.array([[0, 1, 2], [0, 2, 3], [4, 3, 6], [4, 6, 5], [3, 2, 7], [3, 7, 6]])
    segs = [(0, 1, "land"), (4, 5, "open")]
    m = fdrplot.Mesh(xy, tris, segments=segs, source="L")
    keep = np.ones(len(tris), bool)
    cover = plot_mesh.corner_cover(plot_mesh.occupancy(m, keep, plot_mesh.boundary_edges(tris)),
                                   (0, 0, 2, 2), (0.3, 0.2))
    assert min(cover, key=cover.get) == "lower left" and cover["lower left"] == 0
    assert cover["upper right"] > 0.5
    out = tmp_path / "l.png"
    node = tmp_path / "l.node"
    node.write_text("8 2 0 1\n" + "".join(f"{i + 1} {x} {y} 1\n" for i, (x, y) in enumerate(xy)))
    (tmp_path / "l.ele").write_text("6 3 0\n" + "".join(f"{i + 1} {a + 1} {b + 1} {c + 1}\n"
                                                       for i, (a, b, c) in enumerate(tris)))
    (tmp_path / "l.poly").write_text("0 2 0 1\n2 1\n1 1 2 1\n2 5 6 2\n0\n")
    args = plot_mesh.parse_args([str(node), "-o", str(out), "--color", "min_angle", "--size", "5", "--dpi", "80"])
    mesh = fdrplot.read_mesh(str(node))
    if len({k for _, _, k in mesh.segments}) < 2:  # the reader found fewer than two kinds: give them
        mesh.segments = segs
    layout = plot_mesh.draw(mesh, args)
    assert layout["legends"] == ["lower left"]
    # A full square: every corner is covered, so the legend goes below the panel.
    full = fdrplot.Mesh(np.array([[0, 0], [2, 0], [2, 2], [0, 2]], float), np.array([[0, 1, 2], [0, 2, 3]]),
                        segments=segs[:1] + [(2, 3, "open")], source="square")
    layout = plot_mesh.draw(full, args)
    assert layout["legends"] == ["below"]


def test_colour_bar_beside_the_panels(tmp_path):
    """The colour bar has its own column right of the mesh, never on top of it."""
    import plot_mesh

    for extra in ([], ["--bbox", "0.5,0.5,1.5,1.0"]):
        args = plot_mesh.parse_args([os.path.join(TINY, "tiny.node"), "-o", str(tmp_path / "c.png"), "--color",
                                     "r_over_f", "--spacing", "1", "--bound", "1", "--size", "5", "--dpi", "80",
                                     *extra])
        layout = plot_mesh.draw(fdrplot.read_mesh(os.path.join(TINY, "tiny.node")), args)
        cb = layout["colorbar"]
        assert cb is not None
        for panel in layout["panels"]:
            assert cb[0] >= panel[2], (extra, cb, panel)


FAKE_FDRMESH = textwrap.dedent("""\
    #!{py}
    # Stand-in for fdrmesh in tests: a lattice mesh of the .poly's box, spacing ~ B * min f.
    import json, sys
    import numpy as np
    from matplotlib.tri import Triangulation
    sys.path.insert(0, {here!r})
    import fdrplot
    a = sys.argv[1:]
    assert a[0] == "mesh" and "-q" in a
    out, spacing, bound, report = (a[a.index(k) + 1] for k in ("-o", "--spacing", "--bound", "--report"))
    n = int(10 / (float(bound) * 0.8)) + 2
    g = np.linspace(0, 10, n)
    X, Y = np.meshgrid(g, g)
    xy = np.c_[X.ravel(), Y.ravel()]
    t = Triangulation(xy[:, 0], xy[:, 1]).triangles
    stem = out[:-5]
    with open(stem + ".node", "w") as o:
        o.write(f"{{len(xy)}} 2 0 1\\n" + "".join(f"{{i+1}} {{x}} {{y}} 0\\n" for i, (x, y) in enumerate(xy)))
    with open(stem + ".ele", "w") as o:
        o.write(f"{{len(t)}} 3 0\\n" + "".join(f"{{i+1}} {{p+1}} {{q+1}} {{r+1}}\\n" for i, (p, q, r) in enumerate(t)))
    m = fdrplot.read_mesh(stem + ".node")
    ang = fdrplot.triangle_metrics(m)[0]
    json.dump({{"vertices": len(xy), "triangles": len(t), "min_angle_deg": float(ang.min()),
               "max_angle_deg": float(ang.max()), "max_R_over_f": None,
               "conformity": {{"min": 0.5, "mean": 0.75, "p05": 0.6}}}}, open(report, "w"))
""")


def test_paper_figures_script_with_stand_in_mesher(tmp_path):
    fake = tmp_path / "fdrmesh"
    fake.write_text(FAKE_FDRMESH.format(py=PY, here=HERE))
    fake.chmod(fake.stat().st_mode | stat.S_IXUSR)
    out = tmp_path / "figs"
    env = dict(os.environ, FDR_PAPER_BOUNDS="1 sqrt2", PYTHON=PY)
    r = subprocess.run(["bash", os.path.join(HERE, "paper_figures.sh"), str(fake), str(out)],
                       capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    for f in ("f1", "f2"):
        for b in ("1", "sqrt2"):
            assert_png(str(out / f"{f}_B{b}.png"), 1200, 1200)
            assert json.load(open(out / f"{f}_B{b}.json"))["vertices"] > 0
        assert_png(str(out / f"hist_{f}.png"), 1800, 540)
    table = (out / "table.md").read_text().splitlines()
    assert table[0].startswith("| case | B | N vertices | triangles | θmin (°) | θmax (°)")
    assert len(table) == 2 + 4
    assert "| paper-f2 | 1.414 |" in table[5]
    r = subprocess.run(["bash", os.path.join(HERE, "paper_figures.sh"), str(tmp_path / "nope")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "not found or not executable" in r.stderr


@pytest.mark.skipif(not os.environ.get("FDRMESH"), reason="FDRMESH (the fdrmesh binary) not given")
def test_paper_figures_with_real_fdrmesh(tmp_path):
    """The paper's experiment end to end with the real mesher (one bound, to stay quick)."""
    env = dict(os.environ, FDR_PAPER_BOUNDS="sqrt2", PYTHON=PY, MPLBACKEND="Agg")
    out = tmp_path / "paper"
    subprocess.run(["bash", os.path.join(HERE, "paper_figures.sh"), os.environ["FDRMESH"], str(out)], check=True, env=env,
                   capture_output=True, timeout=300)
    table = (out / "table.md").read_text()
    rows = [r for r in table.splitlines() if r.startswith("| paper-f")]
    assert len(rows) == 2
    for r in rows:
        cells = [c.strip() for c in r.strip("|").split("|")]
        assert int(cells[2]) > 50                 # vertices
        assert float(cells[4]) >= 19.0            # theta min of pure FDR
        assert float(cells[6]) <= 1.4143          # max R/f(c) <= B = sqrt(2)
    for png in ["f1_Bsqrt2.png", "f2_Bsqrt2.png", "hist_f1.png", "hist_f2.png"]:
        assert (out / png).stat().st_size > 10000
