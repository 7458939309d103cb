# A coarse global ocean mesh (GSHHG l land of the shared data, hmin 200 km, hmax 1000 km) written by
# the CLI as fort.14, hgrid.ll and GeoPackage, read back by the format parsers of
# io/tests/test_model_formats.py and checked on the sphere with an independent haversine: closed
# (every edge of two triangles or of a coast boundary), no open boundary, every node in lon/lat,
# the report's sphere figures equal to the files' own. Skipped without the shared data.
import importlib.util
import json
import math
import os
import sqlite3
import subprocess

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
LAND = os.path.join(REPO, "..", "shared", "data", "global", "gshhg_land_l.gpkg")
FDRMESH = os.environ.get("FDRMESH")
R = 6371008.8

_spec = importlib.util.spec_from_file_location("model_formats", os.path.join(REPO, "src", "io", "tests",
                                                                            "test_model_formats.py"))
formats = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(formats)


def haversine(a, b):
    p1, p2 = math.radians(a[1]), math.radians(b[1])
    dp, dl = p2 - p1, math.radians(b[0] - a[0])
    h = math.sin(dp / 2) ** 2 + math.cos(p1) * math.cos(p2) * math.sin(dl / 2) ** 2
    return 2 * R * math.asin(min(1.0, math.sqrt(h)))


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    if not FDRMESH:
        pytest.skip("set FDRMESH")
    if not os.path.exists(LAND):
        pytest.skip("shared data not present: " + LAND)
    d = tmp_path_factory.mktemp("global")
    cmd = [FDRMESH, "mesh", "--land", LAND, "--global", "--hmin", "200000", "--hmax", "1000000", "-q",
           "-o", str(d / "m.14"), "-o", str(d / "m.ll"), "-o", str(d / "m.gpkg"), "--report", str(d / "r.json")]
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with open(d / "r.json") as f:
        report = json.load(f)
    figs = {}

    def walk(o):
        if isinstance(o, dict):
            for k, v in o.items():
                if k == "coast_figures":
                    figs.update(v)
                else:
                    walk(v)
    walk(report)
    return {"dir": d, "figures": figs}


def test_closed_on_the_sphere_without_open_boundary(run):
    m = formats.parse_adcirc(run["dir"] / "m.14", schism=False)
    assert m["open"] == []
    count = {}
    for a, b, c in m["elems"]:
        for u, v in ((a, b), (b, c), (c, a)):
            k = (min(u, v), max(u, v))
            count[k] = count.get(k, 0) + 1
    assert max(count.values()) == 2
    coast = set()
    for _, nodes in m["land"]:
        for u, v in zip(nodes, nodes[1:]):
            coast.add((min(u, v), max(u, v)))
    once = {k for k, n in count.items() if n == 1}
    assert once and once <= coast
    # Every land boundary list is a closed coast ring (an island or the outer coast).
    assert all(nodes[0] == nodes[-1] for _, nodes in m["land"])


def test_lonlat_nodes_and_hgrid_ll_agree(run):
    f14 = formats.parse_adcirc(run["dir"] / "m.14", schism=False)
    ll = formats.parse_adcirc(run["dir"] / "m.ll", schism=True)
    assert len(f14["nodes"]) == len(ll["nodes"]) and f14["elems"] == ll["elems"]
    for i, (x, y, _) in f14["nodes"].items():
        assert -180 <= x <= 180 and -90 <= y <= 90
        assert ll["nodes"][i][0] == pytest.approx(x, abs=1e-7) and ll["nodes"][i][1] == pytest.approx(y, abs=1e-7)
    # The ocean reaches every longitude and the Southern Ocean and the Arctic.
    lats = [y for _, y, _ in f14["nodes"].values()]
    assert min(lats) < -60 and max(lats) > 80


def test_project_reader_keeps_the_lonlat_orientation(run):
    # `fdrmesh quality` reads the lon/lat fort.14 and hgrid.ll counter-clockwise as written: only
    # the triangles across the antimeridian (nearly 360 degrees wide in lon/lat) and around the
    # north pole come out inverted, not the whole mesh turned over by their area.
    for name in ("m.14", "m.ll"):
        r = subprocess.run([FDRMESH, "quality", str(run["dir"] / name)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        rows = {k.strip(): v.strip() for k, v in (line.split(":", 1) for line in r.stdout.splitlines() if ":" in line)}
        ntri = int(rows["vertices / triangles"].split("/")[1])
        inverted = int(rows["degenerate / inverted"].split("/")[1])
        assert ntri == run["figures"]["sphere_triangles"]
        assert inverted < 0.03 * ntri, (name, inverted, ntri)


def test_report_lengths_are_great_circle_lengths(run):
    m = formats.parse_adcirc(run["dir"] / "m.14", schism=False)
    xy = m["nodes"]
    lengths = []
    for a, b, c in m["elems"]:
        for u, v in ((a, b), (b, c), (c, a)):
            lengths.append(haversine(xy[u], xy[v]))
    f = run["figures"]
    # The files hold 15 significant digits: the lengths agree to well below a metre.
    assert min(lengths) == pytest.approx(f["sphere_shortest_edge_m"], rel=1e-6, abs=1e-3)
    assert max(lengths) == pytest.approx(f["sphere_longest_edge_m"], rel=1e-9)
    assert f["sphere_triangles"] == len(m["elems"])


def test_sphere_figures(run):
    f = run["figures"]
    assert f["sphere_boundary_edges_not_coast"] == 0
    assert f["sphere_edges_over_two_triangles"] == 0
    assert f["sphere_negative_triangles"] == 0
    assert f["sphere_r_over_f_above_bound"] == 0
    assert f["sphere_max_r_over_f"] <= 1.0
    # Ocean area: the sphere's 510.07 M km^2 less land (148.7 M km^2) and what the coarse
    # generalisation closes or adds (a few percent at hmin 200 km).
    assert f["sphere_area_m2"] / 1e12 == pytest.approx(361.4, rel=0.03)


def test_gpkg_in_epsg_4326(run):
    db = sqlite3.connect(run["dir"] / "m.gpkg")
    srs = {r[0] for r in db.execute("select srs_id from gpkg_geometry_columns")}
    assert srs == {4326}
    n = db.execute("select count(*) from triangles").fetchone()[0]
    assert n == run["figures"]["sphere_triangles"]
    # Triangles across the antimeridian continue past +-180: none spans more than 180 degrees,
    # and some reach beyond 180 (the ocean crosses it in the Pacific and the Southern Ocean).
    ogr = pytest.importorskip("osgeo.ogr")
    ds = ogr.Open(str(run["dir"] / "m.gpkg"))  # kept: its layer dies with it
    lay = ds.GetLayerByName("triangles")
    beyond = 0
    for f in lay:
        r = f.GetGeometryRef().GetGeometryRef(0)
        xs = [r.GetX(i) for i in range(r.GetPointCount())]
        ys = [r.GetY(i) for i in range(r.GetPointCount())]
        if max(abs(y) for y in ys) < 80:  # a triangle around the north pole spans every longitude
            assert max(xs) - min(xs) < 180
        beyond += max(xs) > 180 or min(xs) < -180
    assert beyond > 0


@pytest.mark.parametrize("args", [
    ["--pole", "0,-90"],                                    # --pole needs --global
    ["--global", "--hmin", "1e4"],                          # --global needs --hmin and --hmax
    ["--global", "--hmin", "1e4", "--hmax", "1e5", "--extent", "0,0,1,1"],
    ["--global", "--hmin", "1e4", "--hmax", "1e5", "--pole", "0,-95"],
    ["--global", "--hmin", "1e4", "--hmax", "1e5", "--spacing", "1000"],
])
def test_usage_errors(args, tmp_path):
    if not FDRMESH:
        pytest.skip("set FDRMESH")
    r = subprocess.run([FDRMESH, "mesh", "--land", LAND] + args + ["-o", str(tmp_path / "m.14")],
                       capture_output=True, text=True)
    assert r.returncode == 2, r.stderr
    assert not (tmp_path / "m.14").exists()


def test_pole_outside_land_is_refused(tmp_path):
    if not FDRMESH or not os.path.exists(LAND):
        pytest.skip("set FDRMESH and the shared data")
    r = subprocess.run([FDRMESH, "mesh", "--land", LAND, "--global", "--pole", "-30,0", "--hmin", "2e5", "--hmax", "1e6",
                        "-o", str(tmp_path / "m.14")], capture_output=True, text=True)
    assert r.returncode != 0 and "no land polygon holds the pole" in r.stderr
