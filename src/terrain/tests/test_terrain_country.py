"""The terrain volume of the whole Luxembourg DEM (testdata/luxembourg: the country's 12 cantons) with a
base at -500 m and the two synthetic horizons of testdata/terrain, which cover the DEM's whole grid: the
targets measured on the VTU the CLI writes (long: minutes)."""
import json
import os
import subprocess

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
DATA = os.path.join(ROOT, "testdata")
FDRMESH = os.environ.get("FDRMESH", os.path.join(ROOT, "build", "bin", "fdrmesh"))
VERIFY = os.path.join(ROOT, "..", "shared", "tools", "verify_tets.py")


def tet_volumes(pts, tets):
    a, b, c, d = (pts[tets[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp("country")
    args = [FDRMESH, "mesh", os.path.join(DATA, "luxembourg", "lux.shp"),
            "--dem", os.path.join(DATA, "luxembourg", "elev.tif"), "--base", "-500",
            "--horizon", os.path.join(DATA, "terrain", "lux_h1.tif"),
            "--horizon", os.path.join(DATA, "terrain", "lux_h2.tif"),
            "--hmin", "1000", "--hmax", "4000", "--vertical-tol", "20", "--check", "-q",
            "-o", str(out / "m.vtu"), "--report", str(out / "r.json")]
    p = subprocess.run(args, capture_output=True, text=True, timeout=3600)
    assert p.returncode == 0, p.stderr
    return out


def test_targets(run):
    meshio = pytest.importorskip("meshio")
    m = meshio.read(run / "m.vtu")
    pts = np.asarray(m.points, dtype=float)
    tets = np.concatenate([c.data for c in m.cells if c.type == "tetra"])
    mat = np.concatenate([np.asarray(b) for b, c in zip(m.cell_data["material"], m.cells) if c.type == "tetra"])
    assert (tet_volumes(pts, tets) > 0).all()
    report = json.loads((run / "r.json").read_text())
    assert report["check_passed"] is True
    vol = tet_volumes(pts, tets)
    for l in report["layers"]:
        assert vol[mat == l["material"]].sum() == pytest.approx(l["expected_volume"], rel=1e-3), l["name"]
    assert np.concatenate(m.cell_data["r_over_f"]).max() <= 1.0 + 1e-9
    assert np.concatenate(m.cell_data["radius_edge"]).max() <= 2.0 + 1e-9
    assert np.concatenate(m.cell_data["min_dihedral_deg"]).min() >= 5.0


def test_independent_check(run):
    if not os.path.exists(VERIFY):
        pytest.skip("no ../shared/tools/verify_tets.py")
    p = subprocess.run(["/usr/bin/python3", VERIFY, str(run / "m.vtu"), "--json", str(run / "v.json")],
                       capture_output=True, text=True, timeout=1800)
    assert p.returncode == 0, p.stdout + p.stderr
    v = json.loads((run / "v.json").read_text())
    assert v["radius_edge_max"] <= 2.0 + 1e-9 and v["dihedral_min"] >= 5.0
