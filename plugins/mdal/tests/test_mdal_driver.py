# fort.14, hgrid.gr3 and hgrid.ll of fdrmesh runs opened by QGIS's MDAL provider through the
# libmdal_fdrmesh.so driver (MDAL_DRIVER_PATH set before QGIS starts, as MDAL reads it once, when
# QGIS registers its providers): counts equal the report, coordinates, faces and depths equal the
# file, extent and CRS; broken files give an invalid layer, not a crash. The Chesapeake example
# runs here; `-k global` runs the coarse global ocean (skipped without the shared data).
# CTest runs this only when PyQGIS is installed (else exit 77 = skipped), with FDRMESH and
# FDR_MDAL_DRIVER_DIR set.
import importlib.util
import json
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
sys.path.insert(0, os.path.join(REPO, "tools", "qgis"))
from pyqgis_app import pyqgis_app  # noqa: E402
CHES = os.path.join(REPO, "testdata", "chesapeake")
LAND = os.path.join(REPO, "..", "shared", "data", "global", "gshhg_land_l.gpkg")
FDRMESH = os.environ.get("FDRMESH")
DRIVER_DIR = os.environ.get("FDR_MDAL_DRIVER_DIR")

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("GDAL_PAM_ENABLED", "NO")

_spec = importlib.util.spec_from_file_location("model_formats", os.path.join(REPO, "src", "io", "tests",
                                                                            "test_model_formats.py"))
formats = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(formats)


@pytest.fixture(scope="module")
def qgs(tmp_path_factory):
    assert DRIVER_DIR and os.path.isfile(os.path.join(DRIVER_DIR, "libmdal_fdrmesh.so")), "set FDR_MDAL_DRIVER_DIR"
    # Why before QGIS starts: MDAL scans the folder once, when QGIS registers its providers.
    os.environ["MDAL_DRIVER_PATH"] = DRIVER_DIR
    with pyqgis_app(tmp_path_factory.mktemp("pyqgis_profile")) as app:
        from qgis.core import QgsProviderRegistry
        names = [d.name() for d in QgsProviderRegistry.instance().providerMetadata("mdal").meshDriversMetadata()]
        assert "FDRMESH_ADCIRC" in names
        # The Add Mesh Layer dialog offers the driver's extensions.
        filters = QgsProviderRegistry.instance().fileMeshFilters()
        assert all(ext in filters for ext in ("*.14", "*.grd", "*.gr3", "*.ll")), filters
        yield app


def mesh_run(d, args, outputs):
    assert FDRMESH, "set FDRMESH"
    cmd = [FDRMESH, "mesh"] + args + ["-q", "--report", str(d / "r.json")]
    for name in outputs:
        cmd += ["-o", str(d / name)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with open(d / "r.json") as f:
        return json.load(f)


@pytest.fixture(scope="module")
def chesapeake(tmp_path_factory):
    d = tmp_path_factory.mktemp("mdal_ches")
    rep = mesh_run(d, [os.path.join(CHES, "chesapeake_mouth_water.geojson"),
                       "--open-boundary", os.path.join(CHES, "chesapeake_mouth_open_boundary.geojson"),
                       "--raster", os.path.join(CHES, "chesapeake_mouth_etopo5.tif")], ["m.14", "m.gr3", "m.ll"])
    return {"dir": d, "report": rep}


@pytest.fixture(scope="module")
def global_run(tmp_path_factory):
    if not os.path.exists(LAND):
        pytest.skip("shared data not present: " + LAND)
    d = tmp_path_factory.mktemp("mdal_global")
    rep = mesh_run(d, ["--land", LAND, "--global", "--hmin", "200000", "--hmax", "1000000"], ["g.14", "g.ll"])
    return {"dir": d, "report": rep}


def load(path):
    from qgis.core import QgsMesh, QgsMeshDatasetIndex, QgsMeshLayer
    layer = QgsMeshLayer(str(path), "m", "mdal")
    assert layer.isValid(), layer.error().message()
    dp = layer.dataProvider()
    mesh = QgsMesh()
    dp.populateMesh(mesh)
    groups = {}
    for g in range(dp.datasetGroupCount()):
        name = dp.datasetGroupMetadata(g).name()
        vals = dp.datasetValues(QgsMeshDatasetIndex(g, 0), 0, dp.vertexCount())
        groups[name] = [vals.value(i).scalar() for i in range(dp.vertexCount())]
    ext = layer.extent()
    out = {"vertices": dp.vertexCount(), "faces": dp.faceCount(), "crs": layer.crs().authid(),
           "xyz": [(mesh.vertex(i).x(), mesh.vertex(i).y(), mesh.vertex(i).z()) for i in range(mesh.vertexCount())],
           "faces_list": [list(mesh.face(i)) for i in range(mesh.faceCount())],
           "extent": (ext.xMinimum(), ext.yMinimum(), ext.xMaximum(), ext.yMaximum()), "groups": groups}
    del dp, layer
    return out


def check_against_file(m, path, report, crs):
    """Counts as the report, every vertex (x, y, z = -depth), face and depth as the file, extent, CRS."""
    f = formats.parse_adcirc(path, schism=not str(path).endswith(".14"))
    assert m["vertices"] == report["vertices"] == len(f["nodes"])
    assert m["faces"] == report["triangles"] == len(f["elems"])
    nodes = [f["nodes"][i + 1] for i in range(len(f["nodes"]))]
    # The driver parses the same decimal text: coordinates and depths equal bit for bit.
    assert [(x, y) for x, y, _ in m["xyz"]] == [(x, y) for x, y, _ in nodes]
    assert [z for _, _, z in m["xyz"]] == [-dp if dp != 0 else 0.0 for _, _, dp in nodes]
    assert m["groups"]["depth"] == [dp for _, _, dp in nodes]
    assert m["faces_list"] == [[n - 1 for n in e] for e in f["elems"]]
    xs, ys = [p[0] for p in nodes], [p[1] for p in nodes]
    assert m["extent"] == (min(xs), min(ys), max(xs), max(ys))
    assert m["crs"] == crs


@pytest.mark.parametrize("name,crs", [("m.14", ""), ("m.gr3", ""), ("m.ll", "EPSG:4326")])
def test_chesapeake_through_mdal(qgs, chesapeake, name, crs):
    path = chesapeake["dir"] / name
    check_against_file(load(path), path, chesapeake["report"], crs)


@pytest.mark.parametrize("name", ["g.14", "g.ll"])
def test_global_through_mdal(qgs, global_run, name):
    path = global_run["dir"] / name
    m = load(path)
    check_against_file(m, path, global_run["report"], "EPSG:4326")
    x0, y0, x1, y1 = m["extent"]
    assert -180 <= x0 < -170 and 170 < x1 <= 180 and -90 <= y0 and y1 <= 90


def test_quads_through_mdal(qgs, tmp_path):
    """A SCHISM grid mixing triangles and quads keeps both as written."""
    path = tmp_path / "mixed.gr3"
    path.write_text("mixed\n2 5\n1 0 0 1\n2 10 0 2\n3 10 10 3\n4 0 10 4\n5 20 5 0\n"
                    "1 4 1 2 3 4\n2 3 2 5 3\n")
    m = load(path)
    assert m["vertices"] == 5 and m["faces"] == 2
    assert m["faces_list"] == [[0, 1, 2, 3], [1, 4, 2]]
    assert [z for _, _, z in m["xyz"]] == [-1, -2, -3, -4, 0]
    assert m["groups"]["depth"] == [1, 2, 3, 4, 0]
    assert m["crs"] == "EPSG:4326"  # every node within lon/lat bounds


def broken_copies(src, d):
    """The same grid cut in its node list, with one node too many in NP, and with one element
    too few in NE (the last element is then read as the boundary section)."""
    with open(src) as f:
        lines = f.read().splitlines(keepends=True)
    ne, np_ = (int(t) for t in lines[1].split()[:2])
    cases = {
        "cut.14": lines[:2 + np_ // 2],
        "np.14": [lines[0], "%d %d\n" % (ne, np_ + 1)] + lines[2:],
        "ne.14": [lines[0], "%d %d\n" % (ne - 1, np_)] + lines[2:],
        "empty.gr3": [],
    }
    for name, text in cases.items():
        with open(d / name, "w") as f:
            f.writelines(text)
    return [d / name for name in cases]


def test_broken_files_are_invalid_layers(qgs, chesapeake):
    from qgis.core import QgsMeshLayer
    for path in broken_copies(chesapeake["dir"] / "m.14", chesapeake["dir"]):
        layer = QgsMeshLayer(str(path), "broken", "mdal")
        assert not layer.isValid(), path
        del layer
    # The process is still alive and opens a good file after the broken ones.
    assert load(chesapeake["dir"] / "m.14")["vertices"] == chesapeake["report"]["vertices"]


def test_plugin_finds_the_loaded_driver(qgs):
    sys.path.insert(0, os.path.join(REPO, "plugins", "qgis"))
    from fdrmesh.mdal_driver import driver_dir, driver_loaded, setup_hint
    assert driver_loaded() and setup_hint(FDRMESH) is None
    # From the executable: build/bin/fdrmesh -> build/lib/fdrmesh/mdal, as <prefix>/bin and <libdir>/fdrmesh/mdal installed.
    assert os.path.realpath(driver_dir(FDRMESH)) == os.path.realpath(DRIVER_DIR)


PLUGIN_LATE = r"""
import os, sys
sys.path[:0] = [sys.argv[1], sys.argv[2]]
from pyqgis_app import pyqgis_app
with pyqgis_app(sys.argv[3]):
    os.environ["MDAL_DRIVER_PATH"] = sys.argv[4]  # as a plugin would: after QGIS has started
    from fdrmesh.mdal_driver import driver_loaded, setup_hint
    print("loaded=%s" % driver_loaded())
    print(setup_hint(sys.argv[5]))
"""


def test_plugin_is_too_late_to_set_the_path(tmp_path):
    """MDAL reads MDAL_DRIVER_PATH when QGIS starts: set later, the driver is not loaded, and the
    plugin's hint names the folder and the one-time QGIS setting."""
    env = dict(os.environ)
    env.pop("MDAL_DRIVER_PATH", None)
    r = subprocess.run([sys.executable, "-c", PLUGIN_LATE, os.path.join(REPO, "tools", "qgis"),
                        os.path.join(REPO, "plugins", "qgis"), str(tmp_path), DRIVER_DIR, FDRMESH],
                       capture_output=True, text=True, env=env, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "loaded=False" in r.stdout
    assert "MDAL_DRIVER_PATH=" + os.path.realpath(DRIVER_DIR) in r.stdout or "MDAL_DRIVER_PATH=" + DRIVER_DIR in r.stdout
    assert "Options > System > Environment" in r.stdout
