"""Tests of the 3D benchmark drivers' steps: .poly reading, the .off surface, the rows, the child; the terrain
benchmark's commands and count."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_tet  # noqa: E402

DATA = os.path.join(bench_tet.ROOT, "testdata", "3d")


def test_read_poly_one_based_cube():
    verts, polys = bench_tet.read_poly(os.path.join(DATA, "cube10.poly"))
    assert len(verts) == 8 and verts[0] == (0.0, 0.0, 0.0) and verts[6] == (10.0, 10.0, 10.0)
    assert len(polys) == 6 and polys[0] == [0, 1, 2, 3]


def test_read_poly_zero_based_cavity():
    verts, polys = bench_tet.read_poly(os.path.join(DATA, "box_cavity.poly"))
    assert len(verts) == 16 and verts[8] == (1.0, 1.0, 1.0)
    assert len(polys) == 12 and polys[6] == [8, 9, 10, 11]


def test_write_off_fans_each_quad(tmp_path):
    off = tmp_path / "c.off"
    bench_tet.write_off(os.path.join(DATA, "box_cavity.poly"), str(off))
    lines = off.read_text().split("\n")
    assert lines[0] == "OFF" and lines[1] == "16 24 0"
    assert lines[2 + 16] == "3 0 1 2" and lines[2 + 17] == "3 0 2 3"


def row(tets):
    return {"tool": "t", "param": "p", "tets": tets, "wall": 1.0, "cpu": 1.0, "rss": 1.0}


def test_format_row_marks_counts_off_by_more_than_ten_percent():
    assert "more than 10 %" not in bench_tet.format_row("x", row(1090), 1000)
    assert "more than 10 %" in bench_tet.format_row("x", row(1110), 1000)
    assert "1024 B/tet" in bench_tet.format_row("x", row(1024), 1000)


def test_run_child_measures_the_child(tmp_path):
    wall, cpu, rss, text = bench_tet.run_child([sys.executable, "-c", "print('hi')"], str(tmp_path))
    assert text.strip() == "hi" and wall > 0 and cpu >= 0 and rss > 1


def test_dihedral_compare_angles_of_known_tetrahedra():
    import numpy as np
    import dihedral_compare
    s = 1 / 2 ** 0.5
    pts = np.array([[1, 0, -s], [-1, 0, -s], [0, 1, s], [0, -1, s],  # regular
                    [0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.01]])  # a sliver
    ang = dihedral_compare.min_dihedral_deg(pts, np.array([[0, 1, 2, 3], [4, 5, 6, 7], [1, 0, 2, 3]]))
    assert abs(ang[0] - 70.528779) < 1e-5 and abs(ang[2] - ang[0]) < 1e-9
    assert ang[1] < 1
    s = dihedral_compare.summary(ang)
    assert s["tets"] == 3 and s["under5"] == 1 and s["under15"] == 1 and s["min"] == ang[1]


def test_terrain_bench_commands_and_count(tmp_path):
    import bench_terrain
    t = bench_terrain.terrain_command("fdrmesh", 140, 280)
    assert t[2].endswith("lux.shp") and t[t.index("--base") + 1] == "-500" and t[t.index("--hmin") + 1] == "140"
    assert os.path.exists(t[2]) and os.path.exists(t[t.index("--dem") + 1])
    c = bench_terrain.cube_command("fdrmesh", 0.165)
    assert c[2].endswith("cube10.poly") and c[c.index("--spacing") + 1] == "0.165"
    vtu = tmp_path / "m.vtu"
    vtu.write_text('<VTKFile><UnstructuredGrid><Piece NumberOfPoints="8" NumberOfCells="12">')
    assert bench_terrain.count_tets(str(vtu)) == 12
