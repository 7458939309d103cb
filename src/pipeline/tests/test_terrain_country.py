"""The whole of Luxembourg (testdata/luxembourg, every canton) with a base at -500 m and two synthetic
horizons (testdata/terrain), the terrain issue's target case: the run finishes and what it writes holds
R/f <= B, radius-edge <= 2 with no shortfall listed, the layer volumes and, with the pinch-outs
ended at walls, no dihedral angle under 5 degrees. Long (about a minute)."""
import json
import os
import subprocess

import sys

import numpy as np
import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
DATA = os.path.join(ROOT, "testdata")
FDRMESH = os.environ.get("FDRMESH", os.path.join(ROOT, "build", "bin", "fdrmesh"))
sys.path.insert(0, os.path.join(ROOT, "tools", "verify"))
import tets as verify  # noqa: E402


def test_whole_country_with_two_horizons(tmp_path):
    meshio = pytest.importorskip("meshio")
    args = [FDRMESH, "mesh", os.path.join(DATA, "luxembourg", "lux.shp"),
            "--dem", os.path.join(DATA, "luxembourg", "elev.tif"), "--base", "-500",
            "--horizon", os.path.join(DATA, "terrain", "lux_h1.tif"),
            "--horizon", os.path.join(DATA, "terrain", "lux_h2.tif"),
            "--hmin", "1000", "--hmax", "4000", "--vertical-tol", "20", "-q",
            "-o", str(tmp_path / "m.vtu"), "--report", str(tmp_path / "r.json")]
    p = subprocess.run(args, capture_output=True, text=True, timeout=1200)
    assert p.returncode == 0, p.stderr
    report = json.loads((tmp_path / "r.json").read_text())
    assert report["bad_tetrahedra"] == 0 and report["max_R_over_f"] <= report["bound_B"]
    m = meshio.read(tmp_path / "m.vtu")
    pts = np.asarray(m.points, dtype=float)
    tets = np.concatenate([c.data for c in m.cells if c.type == "tetra"])
    mat = np.concatenate([np.asarray(b) for b, c in zip(m.cell_data["material"], m.cells) if c.type == "tetra"])
    a, b, c, d = (pts[tets[:, k]] for k in range(4))
    vol = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0
    assert (vol > 0).all()
    rf = np.concatenate(m.cell_data["r_over_f"])
    assert rf.max() <= report["bound_B"] + 1e-9
    assert report["max_radius_edge"] <= 2 and not report["refinement"]["shortfalls"]
    assert np.concatenate(m.cell_data["radius_edge"]).max() <= 2 * (1 + 1e-9)
    layers = report["layers"]
    assert [l["name"] for l in layers] == ["top-lux_h1", "lux_h1-lux_h2", "lux_h2-base"]
    for l in layers:
        assert vol[mat == l["material"]].sum() == pytest.approx(l["expected_volume"], rel=1e-3), l["name"]
    assert verify.dihedral_angles(pts, tets).min() >= 5.0
