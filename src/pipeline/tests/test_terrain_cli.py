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
            "-o", str(out / "m.vtu"), "-o", str(out / "m.msh"), "--report", str(out / "r.json")]
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
