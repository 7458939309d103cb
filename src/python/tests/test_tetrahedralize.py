"""fdrmesh.tetrahedralize: numpy arrays out, the same mesh as `fdrmesh mesh` for the same input."""
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import fdrmesh

FDRMESH = os.environ.get("FDRMESH", "build/bin/fdrmesh")
TESTDATA = Path(os.environ.get("FDR_TESTDATA", Path(__file__).resolve().parents[3] / "testdata"))

CUBE_V = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]
CUBE_F = [[0, 1, 2, 3], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]


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


def test_arrays_and_shapes():
    r = fdrmesh.tetrahedralize(CUBE_V, CUBE_F, spacing=0.5, facet_markers=[1, 2, 3, 4, 5, 6])
    assert r["points"].shape[1] == 3 and r["points"].dtype == np.float64
    assert r["tets"].shape[1] == 4 and len(r["materials"]) == len(r["tets"])
    assert r["faces"].shape[1] == 3 and len(r["face_markers"]) == len(r["faces"])
    p = r["points"]
    a, b, c, d = (p[r["tets"][:, k]] for k in range(4))
    vol = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6
    assert (vol > 0).all()
    assert vol.sum() == pytest.approx(1.0, rel=1e-12)
    assert set(r["face_markers"]) <= {1, 2, 3, 4, 5, 6}
    assert {"segment_splits", "facet_splits", "tet_splits", "bound", "shortfalls", "sliver_splits", "slivers_left"} <= set(r["stats"])
    assert r["stats"]["sliver_angle_deg"] == 15 and r["stats"]["slivers_before"] >= r["stats"]["slivers_left"]


@pytest.mark.parametrize("spacing", [0.5, "0.4 + 0.1*x", "0.2*paper-f1"])
def test_same_mesh_as_cli(tmp_path, spacing):
    cli = subprocess.run([FDRMESH, "mesh", str(TESTDATA / "3d" / "cube.poly"), "--spacing", str(spacing),
                          "-o", str(tmp_path / "c.node"), "-q"], capture_output=True, text=True, timeout=120)
    assert cli.returncode == 0, cli.stderr
    pts, tets, mats, faces, marks = read_tetgen(tmp_path / "c")
    r = fdrmesh.tetrahedralize(CUBE_V, CUBE_F, spacing=spacing, facet_markers=[1, 2, 3, 4, 5, 6])
    assert np.array_equal(r["points"], pts)
    assert np.array_equal(r["tets"], tets)
    assert np.array_equal(r["materials"], mats)
    assert np.array_equal(r["faces"], faces)
    assert np.array_equal(r["face_markers"], marks)


def test_callable_spacing():
    r = fdrmesh.tetrahedralize(CUBE_V, CUBE_F, spacing=lambda x, y, z: 0.3 + 0.1 * x)
    assert len(r["tets"]) > 0


def test_holes_and_regions_arguments():
    r = fdrmesh.tetrahedralize(CUBE_V, CUBE_F, regions=[[0.5, 0.5, 0.5, 7]], spacing=0.5)
    assert len(r["tets"]) > 0
    with pytest.raises(fdrmesh.UsageError):
        fdrmesh.tetrahedralize(CUBE_V, CUBE_F, regions=[[0.5, 0.5, 0.5]])


def test_bad_input_raises_with_exit_code():
    with pytest.raises(fdrmesh.InputMalformedError) as e:
        fdrmesh.tetrahedralize(CUBE_V, [[0, 1, 2, 99]])
    assert e.value.exit_code == 4 and "99" in str(e.value)
    bent = [list(v) for v in CUBE_V]
    bent[6] = [1, 1, 1.25]
    with pytest.raises(fdrmesh.GeometryError):
        fdrmesh.tetrahedralize(bent, CUBE_F)
    with pytest.raises(fdrmesh.SpacingError):
        fdrmesh.tetrahedralize(CUBE_V, CUBE_F, spacing=-1)
