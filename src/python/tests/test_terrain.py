"""fdrmesh.mesh(domain, dem=..., base=..., horizons=[...]): the terrain volume as numpy arrays, the
same tetrahedra as the command line's for the same options (synthetic rasters of testdata/terrain)."""
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import fdrmesh

FDRMESH = os.environ.get("FDRMESH", "build/bin/fdrmesh")
TESTDATA = Path(os.environ.get("FDR_TESTDATA", Path(__file__).resolve().parents[3] / "testdata"))
TERRAIN = TESTDATA / "terrain"
OPTIONS = dict(dem=TERRAIN / "synthetic_dem.tif", base=-200, horizons=[TERRAIN / "synthetic_h1.tif"],
               hmin=150, hmax=400)


def read_tetgen(base):
    """TetGen .node/.ele/.face as written by the CLI (1-based), as 0-based arrays."""
    def rows(path):
        lines = [l.split("#")[0].split() for l in Path(path).read_text().splitlines()]
        return [l for l in lines if l]
    node = rows(str(base) + ".node")
    pts = np.array([[float(x) for x in r[1:4]] for r in node[1:]])
    ele = rows(str(base) + ".ele")
    tets = np.array([[int(x) - 1 for x in r[1:5]] for r in ele[1:]], dtype=np.int64).reshape(-1, 4)
    mats = np.array([int(float(r[5])) if len(r) > 5 else 0 for r in ele[1:]])
    face = rows(str(base) + ".face")
    faces = np.array([[int(x) - 1 for x in r[1:4]] for r in face[1:]], dtype=np.int64).reshape(-1, 3)
    marks = np.array([int(r[4]) if len(r) > 4 else 0 for r in face[1:]])
    return pts, tets, mats, faces, marks


@pytest.fixture(scope="module")
def volume(tmp_path_factory):
    out = tmp_path_factory.mktemp("terrain_py")
    r = fdrmesh.mesh(TERRAIN / "synthetic_domain.geojson", output=[out / "m.vtu"], report=out / "r.json", **OPTIONS)
    return r, out


def test_arrays_layers_and_names(volume):
    r, out = volume
    p, t = r["points"], r["tets"]
    assert p.shape[1] == 3 and t.shape[1] == 4 and len(r["materials"]) == len(t)
    a, b, c, d = (p[t[:, k]] for k in range(4))
    vol = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6
    assert (vol > 0).all()
    assert set(np.unique(r["materials"])) == {1, 2}
    assert r["material_names"][1:3] == ["top-synthetic_h1", "synthetic_h1-base"]
    assert [r["marker_names"][m] for m in (1, 2, 3, 4)] == ["top", "base", "side", "synthetic_h1"]
    assert set(np.unique(r["face_markers"])) == {1, 2, 3, 4}
    assert p[:, 2].min() == pytest.approx(-200.0)
    layers = r["report"]["layers"]
    assert [l["name"] for l in layers] == ["top-synthetic_h1", "synthetic_h1-base"]
    for l in layers:
        assert vol[r["materials"] == l["material"]].sum() == pytest.approx(l["expected_volume"], rel=1e-3)
        assert l["tets"] == int((r["materials"] == l["material"]).sum())
    assert r["cell_fields"]["r_over_f"].shape == (len(t),)
    assert r["written"] == [str(out / "m.vtu"), str(out / "r.json")]
    assert json.loads((out / "r.json").read_text())["layers"] == layers


def test_same_tets_as_cli(volume, tmp_path):
    r, _ = volume
    cli = subprocess.run([FDRMESH, "mesh", str(TERRAIN / "synthetic_domain.geojson"), "--dem", str(OPTIONS["dem"]),
                          "--base", "-200", "--horizon", str(OPTIONS["horizons"][0]), "--hmin", "150", "--hmax", "400",
                          "-o", str(tmp_path / "c.node"), "-q"], capture_output=True, text=True, timeout=300)
    assert cli.returncode == 0, cli.stderr
    pts, tets, mats, faces, marks = read_tetgen(tmp_path / "c")
    assert np.array_equal(r["points"], pts)
    assert np.array_equal(r["tets"], tets)
    assert np.array_equal(r["materials"], mats)
    assert np.array_equal(r["faces"], faces)
    assert np.array_equal(r["face_markers"], marks)


def test_errors_are_the_cli_codes(tmp_path):
    with pytest.raises(fdrmesh.UsageError, match="--base"):
        fdrmesh.mesh(TERRAIN / "synthetic_domain.geojson", dem=OPTIONS["dem"])
    with pytest.raises(fdrmesh.UsageError):
        fdrmesh.mesh(TERRAIN / "synthetic_domain.geojson", dem=OPTIONS["dem"], base=-200, output=[tmp_path / "m.2dm"])
    with pytest.raises(fdrmesh.GeometryError):  # a horizon above the DEM everywhere: its layer would be empty
        fdrmesh.mesh(TERRAIN / "synthetic_domain.geojson", dem=OPTIONS["dem"], base=-200,
                     horizons=[TERRAIN / "synthetic_high.tif"], hmin=150, hmax=400)
    with pytest.raises(fdrmesh.UsageError, match="needs --dem"):
        fdrmesh.mesh(TERRAIN / "synthetic_domain.geojson", base=-200)


def test_wells_and_the_domain_from_the_dem():
    """No domain: the DEM's valid-data box; wells=... gives one edge group per well, on one vertical each."""
    r = fdrmesh.mesh(dem=OPTIONS["dem"], base=-200, hmin=300, hmax=600,
                     wells=TERRAIN / "synthetic_wells.geojson", well_spacing=60)
    p = r["points"]
    assert p[:, 0].min() == 500050 and p[:, 0].max() == 502350
    names = r["marker_names"]
    wells = [m for m, n in enumerate(names) if n.startswith("well_")]
    assert [names[m] for m in wells] == ["well_BH1", "well_BH2"]
    for m in wells:
        e = r["edges"][r["edge_markers"] == m]
        assert len(e) >= 4
        xy = p[e.ravel(), :2]
        assert (xy == xy[0]).all()
    with pytest.raises(fdrmesh.GeometryError, match="far"):
        fdrmesh.mesh(TERRAIN / "synthetic_domain.geojson", dem=OPTIONS["dem"], base=-200, hmin=300, hmax=600,
                     wells=TERRAIN / "synthetic_wells_outside.geojson")
