"""pytest for plot_tets_cut.py: the outer faces of a cut and a PNG from a small VTU."""
import os
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
PY = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
sys.path.insert(0, HERE)
import plot_tets_cut  # noqa: E402


def two_tets():
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], dtype=float)
    tets = np.array([[0, 1, 2, 3], [1, 2, 3, 4]])
    return pts, tets


def test_outer_faces_drop_the_shared_face():
    _, tets = two_tets()
    faces, owner = plot_tets_cut.outer_faces(tets, np.array([True, True]))
    assert len(faces) == 6
    assert sorted(set(owner)) == [0, 1]
    faces, owner = plot_tets_cut.outer_faces(tets, np.array([True, False]))
    assert len(faces) == 4 and set(owner) == {0}


def test_png_from_a_vtu(tmp_path):
    meshio = pytest.importorskip("meshio")
    pts, tets = two_tets()
    vtu = tmp_path / "t.vtu"
    meshio.write(vtu, meshio.Mesh(pts, [("tetra", tets)], cell_data={"material": [np.array([1, 2])]}))
    png = tmp_path / "t.png"
    p = subprocess.run([PY, os.path.join(HERE, "plot_tets_cut.py"), str(vtu), "-o", str(png), "--cut", "1"],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    with open(png, "rb") as fh:
        assert fh.read(8) == b"\x89PNG\r\n\x1a\n"
