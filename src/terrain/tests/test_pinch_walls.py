"""Pinch-outs ended at vertical walls, through the CLI: a horizon pinching out against the DEM
(testdata/terrain/synthetic_pinch.tif) and the Remich canton of Luxembourg with its two synthetic
horizons. The written VTU, checked by the project's checker (tools/verify/tets.py) and by the
yardstick ../shared/tools/verify_tets.py when present: no tetrahedron under 5 degrees, radius-edge
at most 2 on the synthetic pinch-out, layer volumes those of the repaired surfaces."""
import json
import os
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
DATA = os.path.join(ROOT, "testdata")
FDRMESH = os.environ.get("FDRMESH", os.path.join(ROOT, "build", "bin", "fdrmesh"))
YARDSTICK = os.path.normpath(os.path.join(ROOT, "..", "shared", "tools", "verify_tets.py"))
sys.path.insert(0, os.path.join(ROOT, "tools", "verify"))
import tets  # noqa: E402


def mesh(tmp_path, args):
    out = tmp_path / "m.vtu"
    p = subprocess.run([FDRMESH, "mesh", *args, "--check", "-o", str(out), "--report", str(tmp_path / "r.json")],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    assert "pinch-outs end at vertical walls" in p.stderr, p.stderr
    report = json.loads((tmp_path / "r.json").read_text())
    P, T, _ = tets.read_vtu(str(out))
    figures = tets.check(P, T, delaunay=False)
    assert figures["valid"]
    for layer in report["layers"]:
        assert abs(layer["relative_difference"]) < 1e-3, layer
    assert report["layers"][0]["pinch_out_triangles"] > 0 and report["layers"][0]["pinch_out_volume_moved"] > 0
    yard = None
    if os.path.exists(YARDSTICK):
        j = tmp_path / "v.json"
        subprocess.run(["/usr/bin/python3", YARDSTICK, str(out), "--json", str(j)], check=True, capture_output=True)
        yard = json.loads(j.read_text())
    return figures, yard


def test_synthetic_pinch_out(tmp_path):
    t = os.path.join(DATA, "terrain")
    figures, yard = mesh(tmp_path, [os.path.join(t, "synthetic_domain.geojson"), "--dem", os.path.join(t, "synthetic_dem.tif"),
                                    "--base", "-200", "--horizon", os.path.join(t, "synthetic_pinch.tif"),
                                    "--hmin", "150", "--hmax", "400"])
    for f in filter(None, [figures, yard]):
        assert f["dihedral_lt5"] == 0 and f["dihedral_min"] >= 5, f
        assert f["radius_edge_max"] <= 2, f


def test_remich_canton(tmp_path):
    figures, yard = mesh(tmp_path, [os.path.join(DATA, "luxembourg", "lux.shp"), "--where", "NAME_2 = 'Remich'",
                                    "--dem", os.path.join(DATA, "luxembourg", "elev.tif"), "--base", "-500",
                                    "--horizon", os.path.join(DATA, "terrain", "lux_h1.tif"),
                                    "--horizon", os.path.join(DATA, "terrain", "lux_h2.tif"),
                                    "--hmin", "1000", "--hmax", "4000", "--vertical-tol", "20"])
    for f in filter(None, [figures, yard]):
        assert f["dihedral_lt5"] == 0 and f["dihedral_min"] >= 5, f
