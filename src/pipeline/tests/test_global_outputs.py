# The outputs of a coarse global ocean mesh (GSHHG l land of the shared data, hmin 200 km, hmax
# 1000 km) read back as users read them: the VTU and msh on the sphere through meshio (every node
# at the radius R, every triangle's normal pointing away from the centre, the mesh closed with the
# coast as its only boundary), and the UGRID, D-Flow FM net, 2DM and Selafin files through QGIS's
# MDAL (vertex and face counts, lon/lat extent). Skipped without the shared data; the meshio and
# MDAL parts skip with a message when python3-meshio or PyQGIS is missing.
import importlib.util
import json
import math
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
sys.path.insert(0, os.path.join(REPO, "tools", "qgis"))
from pyqgis_app import pyqgis_app  # noqa: E402
LAND = os.path.join(REPO, "..", "shared", "data", "global", "gshhg_land_l.gpkg")
FDRMESH = os.environ.get("FDRMESH")
R = 6371008.8  # the sphere of --global runs (gis/global_sphere.hpp kEarthRadius)

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("GDAL_PAM_ENABLED", "NO")

_spec = importlib.util.spec_from_file_location("model_formats", os.path.join(REPO, "src", "io", "tests",
                                                                            "test_model_formats.py"))
formats = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(formats)

OUTPUTS = ["m.14", "m.vtu", "m.msh", "m.nc", "m_net.nc", "m.2dm", "m.slf"]


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    if not FDRMESH:
        pytest.skip("set FDRMESH")
    if not os.path.exists(LAND):
        pytest.skip("shared data not present: " + LAND)
    d = tmp_path_factory.mktemp("global_out")
    cmd = [FDRMESH, "mesh", "--land", LAND, "--global", "--hmin", "200000", "--hmax", "1000000", "-q",
           "--report", str(d / "r.json")]
    for name in OUTPUTS:
        cmd += ["-o", str(d / name)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with open(d / "r.json") as f:
        report = json.load(f)
    f14 = formats.parse_adcirc(d / "m.14", schism=False)
    # fort.14 numbers nodes 1..n in the order of every other output (0-based there).
    lonlat = [f14["nodes"][i + 1][:2] for i in range(len(f14["nodes"]))]
    coast = set()
    for _, nodes in f14["land"]:
        for u, v in zip(nodes, nodes[1:]):
            coast.add((min(u, v) - 1, max(u, v) - 1))
    return {"dir": d, "report": report, "lonlat": lonlat, "coast": coast, "triangles": len(f14["elems"])}


def sphere_point(lon, lat):
    lo, la = math.radians(lon), math.radians(lat)
    return (R * math.cos(la) * math.cos(lo), R * math.cos(la) * math.sin(lo), R * math.sin(la))


def edge_uses(triangles):
    count = {}
    for t in triangles:
        for k in range(3):
            u, v = int(t[k]), int(t[(k + 1) % 3])
            e = (min(u, v), max(u, v))
            count[e] = count.get(e, 0) + 1
    return count


def check_on_sphere(run, points, triangles):
    """Every node at radius R and where fort.14's lon/lat put it, every triangle outward, the mesh
    closed with fort.14's coast as its only boundary."""
    np = pytest.importorskip("numpy")
    assert len(points) == len(run["lonlat"]) and len(triangles) == run["triangles"]
    r = np.linalg.norm(points, axis=1)
    assert np.max(np.abs(r - R)) < 1e-6  # metres: rounding of 15-17 significant digits
    expect = np.array([sphere_point(lon, lat) for lon, lat in run["lonlat"]])
    assert np.max(np.linalg.norm(points - expect, axis=1)) < 1e-3
    a, b, c = (points[triangles[:, k]] for k in range(3))
    outward = np.einsum("ij,ij->i", np.cross(b - a, c - a), a + b + c)
    assert (outward > 0).all(), f"{int((outward <= 0).sum())} triangles face the centre"
    count = edge_uses(triangles)
    assert max(count.values()) == 2
    once = {e for e, n in count.items() if n == 1}
    assert once == run["coast"]
    return once


def test_vtu_on_the_sphere(run):
    meshio = pytest.importorskip("meshio", reason="python3-meshio is not installed: the VTU is not read back")
    m = meshio.read(run["dir"] / "m.vtu")
    tri = m.get_cells_type("triangle")
    check_on_sphere(run, m.points, tri)
    assert float(m.field_data["sphere_radius_m"][0]) == R
    # Its lon/lat point data are fort.14's node coordinates.
    for i, (lon, lat) in enumerate(run["lonlat"]):
        assert abs(m.point_data["lat"][i] - lat) < 1e-9
        if abs(lat) < 89.9:
            assert abs((m.point_data["lon"][i] - lon + 180) % 360 - 180) < 1e-9


def test_msh_on_the_sphere_with_coast_groups(run):
    meshio = pytest.importorskip("meshio", reason="python3-meshio is not installed: the msh is not read back")
    m = meshio.read(run["dir"] / "m.msh")
    once = check_on_sphere(run, m.points, m.get_cells_type("triangle"))
    # The coast rings are its line elements, in the physical groups "land" and "island".
    lines = {(min(int(u), int(v)), max(int(u), int(v))) for u, v in m.get_cells_type("line")}
    assert lines == once
    names = {}
    for name, blocks in m.cell_sets.items():
        for k, ids in enumerate(blocks):
            if m.cells[k].type == "line" and len(ids):
                names[name] = names.get(name, 0) + len(ids)
    assert set(names) == {"land", "island"}
    assert sum(names.values()) == len(lines)


@pytest.fixture(scope="module")
def qgs(tmp_path_factory):
    try:
        import qgis.core  # noqa: F401
    except ImportError:
        pytest.skip("PyQGIS (python3-qgis) is not installed: the MDAL read-back is not tested")
    with pyqgis_app(tmp_path_factory.mktemp("pyqgis_profile")) as app:
        yield app


def mdal_load(path):
    from qgis.core import QgsMeshLayer
    layer = QgsMeshLayer(str(path), "m", "mdal")
    assert layer.isValid(), f"MDAL cannot read {path}: {layer.error().message()}"
    e = layer.extent()
    out = {"vertices": layer.dataProvider().vertexCount(), "faces": layer.dataProvider().faceCount(),
           "crs": layer.crs().authid(), "extent": (e.xMinimum(), e.yMinimum(), e.xMaximum(), e.yMaximum())}
    del layer
    return out


# The global outputs MDAL reads (QGIS 3.22 has no ADCIRC, SCHISM, Gmsh or VTK mesh driver), the CRS
# it finds in them and how close the coordinates are (Selafin stores 32-bit reals by default).
@pytest.mark.parametrize("name,crs,tol", [("m.nc", "EPSG:4326", 1e-9), ("m_net.nc", "EPSG:4326", 1e-9),
                                          ("m.2dm", "", 1e-9), ("m.slf", "", 1e-4)])
def test_mdal_reads_the_global_mesh(qgs, run, name, crs, tol):
    m = mdal_load(run["dir"] / name)
    assert m["vertices"] == run["report"]["vertices"] == len(run["lonlat"])
    assert m["faces"] == run["report"]["triangles"] == run["triangles"]
    assert m["crs"] == crs
    lons = [p[0] for p in run["lonlat"]]
    lats = [p[1] for p in run["lonlat"]]
    expect = (min(lons), min(lats), max(lons), max(lats))
    assert all(abs(g - w) <= tol for g, w in zip(m["extent"], expect)), (m["extent"], expect)
    # The whole ocean in lon/lat: every longitude, the Southern Ocean and the Arctic.
    assert expect[0] < -179.9 and expect[2] > 179.9 and expect[1] < -70 and expect[3] > 85


def test_coast_deviation_on_the_sphere(run):
    figs = {}

    def walk(o):
        if isinstance(o, dict):
            for k, v in o.items():
                if k.startswith("sphere_coast_"):
                    figs[k] = v
                walk(v)
        elif isinstance(o, list):
            for x in o:
                walk(x)
    walk(run["report"])
    hmin = 200000
    for way in ("input_to_mesh", "input_to_mesh_kept", "mesh_to_input"):
        mx, p99 = figs[f"sphere_coast_{way}_max_m"], figs[f"sphere_coast_{way}_p99_m"]
        assert 0 < p99 <= mx
        if way == "input_to_mesh":
            continue  # every input ring, the islands the generalisation removed among them
        # Great-circle metres, not the stereographic plane's (up to 100 times longer near
        # Antarctica): at this coarse spacing the coast stays within a few hmin of the input
        # (input to mesh over the rings with a counterpart, as the regional yardstick measures).
        assert p99 <= 3 * hmin and mx <= 4 * hmin, (way, p99, mx)
    for way in ("input_to_mesh", "mesh_to_input"):
        assert -180 <= figs[f"sphere_coast_{way}_max_lon"] <= 180 and -90 <= figs[f"sphere_coast_{way}_max_lat"] <= 90
    # The rings left out are islands the coarse generalisation removed: they only add to the figure
    # over every ring.
    assert figs["sphere_coast_input_rings_without_counterpart"] > 0
    assert figs["sphere_coast_input_to_mesh_max_m"] >= figs["sphere_coast_input_to_mesh_kept_max_m"]
    assert figs["sphere_coast_input_to_mesh_p99_m"] >= figs["sphere_coast_input_to_mesh_kept_p99_m"]
    # The farthest mesh coast point lies on the mesh coast: within half a coast edge of a coast node.
    p = sphere_point(figs["sphere_coast_mesh_to_input_max_lon"], figs["sphere_coast_mesh_to_input_max_lat"])
    xyz = {u: sphere_point(*run["lonlat"][u]) for e in run["coast"] for u in e}
    longest = max(math.dist(xyz[u], xyz[v]) for u, v in run["coast"])
    assert min(math.dist(p, q) for q in xyz.values()) <= 0.51 * longest


def test_project_reader_reads_the_sphere_msh_as_its_fort14(run):
    # fdrmesh's own msh reader turns the sphere back into lon/lat: `fdrmesh quality` counts the same
    # in the msh as in the fort.14 (the figures of triangles across the antimeridian, 360 degrees
    # wide in lon/lat, move with the last bits of a longitude near +-180, so they are not compared).
    def quality(name):
        r = subprocess.run([FDRMESH, "quality", str(run["dir"] / name)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        rows = dict(line.split(":", 1) for line in r.stdout.splitlines() if ":" in line)
        return {k.strip(): rows[k].strip() for k in rows if k.strip() in ("vertices / triangles", "degenerate / inverted")}
    msh = quality("m.msh")
    assert len(msh) == 2 and msh == quality("m.14")
    assert msh["vertices / triangles"] == f"{len(run['lonlat'])} / {run['triangles']}"
