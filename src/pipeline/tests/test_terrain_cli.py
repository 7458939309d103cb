"""The terrain-volume command on the Luxembourg DEM (testdata/luxembourg, one canton) with a base at
-500 m and two synthetic horizons (testdata/terrain): what the CLI writes, read back with meshio."""
import json
import os
import subprocess

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
DATA = os.path.join(ROOT, "testdata")
FDRMESH = os.environ.get("FDRMESH", os.path.join(ROOT, "build", "bin", "fdrmesh"))


def tet_volumes(pts, tets):
    a, b, c, d = (pts[tets[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("terrain")
    args = [FDRMESH, "mesh", os.path.join(DATA, "luxembourg", "lux.shp"), "--where", "NAME_2 = 'Remich'",
            "--dem", os.path.join(DATA, "luxembourg", "elev.tif"), "--base", "-500",
            "--horizon", os.path.join(DATA, "terrain", "lux_h1.tif"),
            "--horizon", os.path.join(DATA, "terrain", "lux_h2.tif"),
            "--hmin", "1000", "--hmax", "4000", "--vertical-tol", "20", "--check", "-q",
            "-o", str(out / "m.vtu"), "-o", str(out / "m.msh"), "-o", str(out / "top.gpkg"), "--report", str(out / "r.json")]
    p = subprocess.run(args, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    return out


def test_layers_and_volumes(run):
    meshio = pytest.importorskip("meshio")
    m = meshio.read(run / "m.vtu")
    pts = np.asarray(m.points, dtype=float)
    tets = np.concatenate([c.data for c in m.cells if c.type == "tetra"])
    mat = np.concatenate([np.asarray(b) for b, c in zip(m.cell_data["material"], m.cells) if c.type == "tetra"])
    vol = tet_volumes(pts, tets)
    assert (vol > 0).all()
    assert set(np.unique(mat)) == {1, 2, 3}
    report = json.loads((run / "r.json").read_text())
    layers = report["layers"]
    assert [l["name"] for l in layers] == ["top-lux_h1", "lux_h1-lux_h2", "lux_h2-base"]
    for l in layers:
        measured = vol[mat == l["material"]].sum()
        assert measured == pytest.approx(l["expected_volume"], rel=1e-3), l["name"]
    assert report["check_passed"] is True
    # UTM 32N world coordinates; the base at -500 m.
    assert pts[:, 0].min() > 2e5 and pts[:, 1].min() > 5e6
    assert pts[:, 2].min() == pytest.approx(-500.0)


def test_quality_fields(run):
    meshio = pytest.importorskip("meshio")
    m = meshio.read(run / "m.vtu")
    rf = np.concatenate(m.cell_data["r_over_f"])
    assert rf.max() <= 1.0 + 1e-9


def test_msh_groups(run):
    text = (run / "m.msh").read_text(errors="replace")
    names = text[text.index("$PhysicalNames"):text.index("$EndPhysicalNames")]
    for g in ["top", "base", "side", "lux_h1", "lux_h2", "top-lux_h1", "lux_h1-lux_h2", "lux_h2-base"]:
        assert f'"{g}"' in names, g


def test_top_surface_gpkg(run):
    """The GIS user's GeoPackage: the top TIN with the DEM's elevations, the walls' outline, the names."""
    ogr = pytest.importorskip("osgeo.ogr")
    meshio = pytest.importorskip("meshio")
    ds = ogr.Open(str(run / "top.gpkg"))
    assert ds is not None
    nodes, tris, bnd = ds.GetLayerByName("nodes"), ds.GetLayerByName("triangles"), ds.GetLayerByName("boundaries")
    assert nodes.GetFeatureCount() > 100 and tris.GetFeatureCount() > 100 and bnd.GetFeatureCount() >= 1
    assert "UTM" in nodes.GetSpatialRef().ExportToWkt()
    # Every node is a vertex of the volume's top, at the elevation the volume has there.
    m = meshio.read(run / "m.vtu")
    pts = np.asarray(m.points, dtype=float)
    top = {(round(p[0], 3), round(p[1], 3)): p[2] for p in pts}
    xyz = []
    for f in nodes:
        g = f.GetGeometryRef()
        xyz.append((g.GetX(), g.GetY(), f.GetField("z")))
    xyz = np.array(xyz)
    for x, y, z in xyz:
        assert (round(x, 3), round(y, 3)) in top
    assert xyz[:, 2].min() > 100 and xyz[:, 2].max() < 600  # the DEM of Remich, not a horizon or the base
    highest = {}
    for p in pts:
        k = (round(p[0], 3), round(p[1], 3))
        highest[k] = max(highest.get(k, -1e9), p[2])
    for x, y, z in xyz:
        assert highest[(round(x, 3), round(y, 3))] == pytest.approx(z, abs=1e-6)
    # The side walls stand on the closed outline of the domain.
    closed = [f.GetField("closed") for f in bnd]
    assert all(closed)
    meta = {f.GetField("key"): f.GetField("value") for f in ds.GetLayerByName("metadata")}
    assert meta["terrain_surfaces"] == "top,lux_h1,lux_h2,base"
    assert [meta[f"terrain_marker_{k}"] for k in (1, 2, 3, 4, 5)] == ["top", "base", "side", "lux_h1", "lux_h2"]
    assert [meta[f"terrain_layer_{k}"] for k in (1, 2, 3)] == ["top-lux_h1", "lux_h1-lux_h2", "lux_h2-base"]
    layers = json.loads(meta["terrain_layers"])
    assert layers == json.loads((run / "r.json").read_text())["layers"]
