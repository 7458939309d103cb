# Selafin and Delft3D FM net file of one fdrmesh run read by QGIS's MDAL provider (the reader most
# users open them with): counts equal the quality report, BOTTOM / node z equal the depths, CRS.
# CTest runs this only when PyQGIS is installed (else exit 77 = skipped), with FDRMESH set.
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
CHES = os.path.join(REPO, "testdata", "chesapeake")
FDRMESH = os.environ.get("FDRMESH")

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("GDAL_PAM_ENABLED", "NO")


@pytest.fixture(scope="module")
def qgs(tmp_path_factory):
    with pyqgis_app(tmp_path_factory.mktemp("pyqgis_profile")) as app:
        yield app


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    assert FDRMESH, "set FDRMESH"
    d = tmp_path_factory.mktemp("mdal")
    base = [FDRMESH, "mesh", os.path.join(CHES, "chesapeake_mouth_water.geojson"),
            "--open-boundary", os.path.join(CHES, "chesapeake_mouth_open_boundary.geojson"),
            "--raster", os.path.join(CHES, "chesapeake_mouth_etopo5.tif"), "-q"]
    r = subprocess.run(base + ["--report", str(d / "r.json"), "-o", str(d / "m.slf"), "-o", str(d / "m_net.nc"),
                               "-o", str(d / "m.gr3")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    (d / "dbl").mkdir()
    r = subprocess.run(base + ["--slf-double", "-o", str(d / "dbl" / "m.slf")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with open(d / "r.json") as f:
        rep = json.load(f)
    depth = []
    with open(d / "m.gr3") as f:
        f.readline()
        ne, np_ = (int(t) for t in f.readline().split()[:2])
        xy = []
        for _ in range(np_):
            t = f.readline().split()
            xy.append((float(t[1]), float(t[2])))
            depth.append(float(t[3]))
    return {"dir": d, "report": rep, "depth": depth, "xy": xy}


def load(path):
    from qgis.core import QgsMesh, QgsMeshDatasetIndex, QgsMeshLayer
    layer = QgsMeshLayer(str(path), "m", "mdal")
    assert layer.isValid(), layer.error().message()
    dp = layer.dataProvider()
    mesh = QgsMesh()
    dp.populateMesh(mesh)
    groups = {}
    for g in range(dp.datasetGroupCount()):
        name = dp.datasetGroupMetadata(g).name().strip().lower()
        vals = dp.datasetValues(QgsMeshDatasetIndex(g, 0), 0, dp.vertexCount())
        groups[name] = [vals.value(i).scalar() for i in range(dp.vertexCount())]
    out = {"vertices": dp.vertexCount(), "faces": dp.faceCount(), "crs": layer.crs().authid(),
           "xy": [(mesh.vertex(i).x(), mesh.vertex(i).y()) for i in range(mesh.vertexCount())],
           "groups": groups}
    del dp, layer
    return out


def check_values(vals, depth, rel):
    for v, dp in zip(vals, depth):
        if math.isnan(v):  # some MDAL versions show a value of exactly 0 as "no data"
            assert dp == 0
        else:
            assert abs(v + dp) <= rel * max(1.0, abs(dp))


@pytest.mark.parametrize("name,tol", [("m.slf", 5e-3), ("dbl/m.slf", 1e-9)])
def test_selafin_through_mdal(qgs, run, name, tol):
    m = load(run["dir"] / name)
    assert m["vertices"] == run["report"]["vertices"] and m["faces"] == run["report"]["triangles"]
    bottom = next(v for k, v in m["groups"].items() if k.startswith("bottom"))
    check_values(bottom, run["depth"], 1e-5 if tol > 1e-6 else 1e-12)
    # MDAL adds the IPARAM(3)/(4) origin: world coordinates within float precision.
    for (x, y), (gx, gy) in zip(m["xy"], run["xy"]):
        assert abs(x - gx) <= tol and abs(y - gy) <= tol


def test_net_file_through_mdal(qgs, run):
    m = load(run["dir"] / "m_net.nc")
    assert m["vertices"] == run["report"]["vertices"] and m["faces"] == run["report"]["triangles"]
    assert m["crs"] == "EPSG:32618"
    z = next(v for k, v in m["groups"].items() if "elevation" in k or k.endswith("node_z"))
    check_values(z, run["depth"], 1e-12)
    assert m["xy"] == run["xy"]
