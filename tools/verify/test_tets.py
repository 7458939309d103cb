"""The 3D writers' files read by other programs, and tools/verify/tets.py against the lead's yardstick.

Needs the test tool tetio_convert (env TETIO_CONVERT, set by CTest `tetio_outputs`); gmsh, tetgen,
meshio and the yardstick ../shared/tools/verify_tets.py are each optional (their tests skip)."""
import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import tets  # noqa: E402

REPO = os.path.normpath(os.path.join(HERE, "..", ".."))
TESTDATA = os.environ.get("FDR_TESTDATA_DIR", os.path.join(REPO, "testdata"))
CONVERT = os.environ.get("TETIO_CONVERT", os.path.join(REPO, "build", "src", "tetio", "tetio_convert"))
YARDSTICK = os.path.normpath(os.path.join(REPO, "..", "shared", "tools", "verify_tets.py"))
PY = "/usr/bin/python3"

needs_convert = pytest.mark.skipif(not os.path.exists(CONVERT), reason="tetio_convert not built")


def convert(src, *outs):
    subprocess.run([CONVERT, src, *outs], check=True)


def write_tetgen(base, P, T, material=None):
    """A TetGen .node/.ele pair (0-based) from numpy arrays."""
    with open(base + ".node", "w") as f:
        f.write(f"{len(P)} 3 0 0\n")
        for i, p in enumerate(P):
            f.write(f"{i} {p[0]!r} {p[1]!r} {p[2]!r}\n")
    with open(base + ".ele", "w") as f:
        f.write(f"{len(T)} 4 {1 if material is not None else 0}\n")
        for i, t in enumerate(T):
            f.write(f"{i} {t[0]} {t[1]} {t[2]} {t[3]}" + (f" {material[i]}" if material is not None else "") + "\n")


def write_ascii_vtu(path, P, T):
    """A plain ASCII VTU, tetrahedra in the given order (so that bad orientations stay bad)."""
    conn = " ".join(str(int(v)) for v in np.asarray(T).ravel())
    offs = " ".join(str(4 * (i + 1)) for i in range(len(T)))
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">\n'
                f'<UnstructuredGrid><Piece NumberOfPoints="{len(P)}" NumberOfCells="{len(T)}">\n'
                '<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">'
                + " ".join(repr(float(c)) for c in np.asarray(P).ravel()) + "</DataArray></Points>\n"
                f'<Cells><DataArray type="Int64" Name="connectivity" format="ascii">{conn}</DataArray>\n'
                f'<DataArray type="Int64" Name="offsets" format="ascii">{offs}</DataArray>\n'
                '<DataArray type="UInt8" Name="types" format="ascii">' + " ".join(["10"] * len(T))
                + "</DataArray></Cells>\n</Piece></UnstructuredGrid></VTKFile>\n")


def random_delaunay(tmp_path, n=300, seed=48):
    from scipy.spatial import Delaunay
    rng = np.random.default_rng(seed)
    P = rng.random((n, 3)) * 10
    T = Delaunay(P).simplices.astype(np.int64)
    base = str(tmp_path / "rand")
    write_tetgen(base, P, T, material=[1 + (i % 3) for i in range(len(T))])
    return base, P, T


# ------------------------------------------------------------------ the writers' files elsewhere
@needs_convert
def test_vtu_and_msh_read_by_meshio(tmp_path):
    meshio = pytest.importorskip("meshio")
    out = [str(tmp_path / n) for n in ("c.vtu", "c.b64.vtu", "c.msh")]
    convert("--cube", *out)
    ref = None
    for f in out:
        m = meshio.read(f)
        T = np.vstack([c.data for c in m.cells if c.type == "tetra"])
        assert len(T) == 6 and m.points.shape == (8, 3)
        vol6 = np.einsum("ij,ij->i", m.points[T[:, 1]] - m.points[T[:, 0]],
                         np.cross(m.points[T[:, 2]] - m.points[T[:, 0]], m.points[T[:, 3]] - m.points[T[:, 0]]))
        assert (vol6 > 0).all()
        if f.endswith(".vtu"):
            assert m.cell_data["material"][0].tolist() == [1, 1, 2, 2, 2, 2]
            assert m.cell_data["r_over_f"][0][5] == 1e-300
            assert ref is None or np.array_equal(ref, T)
            ref = T
        else:
            assert m.field_data["upper"].tolist() == [1, 3] and m.field_data["west"].tolist() == [1, 2]
            assert sum(len(c.data) for c in m.cells if c.type == "triangle") == 12


@needs_convert
@pytest.mark.skipif(shutil.which("gmsh") is None, reason="gmsh not installed")
def test_msh_checked_by_gmsh(tmp_path):
    base, _, T = random_delaunay(tmp_path, n=80)
    for src, name in (("--cube", "c.msh"), (base + ".ele", "r.msh")):
        f = str(tmp_path / name)
        convert(src, f)
        r = subprocess.run(["gmsh", "-check", f], capture_output=True, text=True, timeout=60)
        log = r.stdout + r.stderr
        assert r.returncode == 0 and "Error" not in log and "Warning" not in log, log
        r = subprocess.run(["gmsh", f, "-0", "-o", str(tmp_path / "again.msh")], capture_output=True, text=True, timeout=60)
        assert r.returncode == 0, r.stdout + r.stderr


@needs_convert
@pytest.mark.skipif(shutil.which("tetgen") is None, reason="tetgen not installed")
def test_tetgen_files_read_by_tetgen(tmp_path):
    convert("--cube", str(tmp_path / "c.node"))
    r = subprocess.run(["tetgen", "-rNEFV", str(tmp_path / "c")], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "Mesh tetrahedra: 6" in r.stdout and "Smallest volume:          0.16667" in r.stdout, r.stdout


@needs_convert
@pytest.mark.skipif(shutil.which("tetgen") is None, reason="tetgen not installed")
def test_poly_written_from_any_input_meshed_by_tetgen(tmp_path):
    for name, switches, tets_min in (("octahedron_binary.stl", "-pQ", 4), ("layers.poly", "-pAaQ", 100),
                                      ("facet_hole.poly", "-pqQ", 20)):
        out = str(tmp_path / (name.split(".")[0] + "_copy.poly"))
        subprocess.run([CONVERT, "--plc", os.path.join(TESTDATA, "3d", name), out], check=True)
        r = subprocess.run(["tetgen", switches, out], capture_output=True, text=True, timeout=60)
        assert r.returncode == 0, r.stdout + r.stderr
        with open(out[:-5] + ".1.ele") as f:
            head = f.readline().split()
        assert int(head[0]) >= tets_min, (name, head)
        if "A" in switches:  # the two regions' attributes came through
            T = np.loadtxt(out[:-5] + ".1.ele", skiprows=1)
            assert sorted(set(T[:, 5].astype(int))) == [1, 2]


@needs_convert
def test_tetgen_round_trip_keeps_coordinates(tmp_path):
    base, P, T = random_delaunay(tmp_path, n=50)
    convert(base + ".ele", str(tmp_path / "out.node"), str(tmp_path / "out.b64.vtu"))
    Q, U, cd = tets.read_vtu(str(tmp_path / "out.b64.vtu"))
    assert np.array_equal(Q, P)
    assert sorted(map(sorted, U.tolist())) == sorted(map(sorted, T.tolist()))
    assert cd["material"].tolist() == [1 + (i % 3) for i in range(len(T))]
    node = np.loadtxt(str(tmp_path / "out.node"), skiprows=1)
    assert np.array_equal(node[:, 1:], P) and node[0, 0] == 1


# ------------------------------------------------------------------ the checker itself
def test_checker_finds_flipped_tet_shared_face_open_boundary_and_non_delaunay(tmp_path):
    P = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], float)
    good = np.array([[0, 1, 2, 3], [1, 2, 3, 4]])
    good[1] = good[1][[1, 0, 2, 3]] if tets.signed_volumes6(P, good[1:])[1][0] < 0 else good[1]
    r = tets.check(P, good)
    assert r["valid"] and r["not_delaunay"] == 0 and r["boundary_faces"] == 6
    flipped = good.copy()
    flipped[0] = flipped[0][[1, 0, 2, 3]]
    assert tets.check(P, flipped)["nonpositive_volume"] == 1
    # A point inside the first tetrahedron's circumsphere, meshed as a separate tetrahedron: the
    # boundary stays closed, the union is not Delaunay.
    Q = np.vstack([P, [[0.3, 0.3, -0.2], [10, 10, 10], [10, 11, 10], [11, 10, 10], [10, 10, 11]]])
    T = np.array([[0, 1, 2, 3], [6, 7, 8, 9]])  # vertex 4 (1, 1, 1) lies on the first sphere: not inside
    for i in range(2):
        if tets.signed_volumes6(Q, T[i:i + 1])[1][0] < 0:
            T[i] = T[i][[1, 0, 2, 3]]
    assert tets.check(Q, T)["not_delaunay"] == 1
    # A face in three tetrahedra; and a boundary left open by a missing face (one tetrahedron's
    # faces alone, one of them listed with the wrong side out, cannot close).
    R = np.vstack([P, [[0.2, 0.2, -1]]])
    three = np.array([[0, 1, 2, 3], [1, 0, 2, 5], [0, 1, 2, 5]])
    assert tets.check(R, three)["faces_shared_gt2"] == 1
    faces = np.array([[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 1, 2]])
    assert tets.boundary_open_edges(faces, np.ones(4, int)) == 6  # 0-1, 1-2, 2-0 twice each


def test_checker_exact_on_cospherical_points():
    # The cube's eight corners are cospherical: any tetrahedralization is Delaunay, and the
    # double-precision circumcentres must not make a corner look inside.
    P = np.array([[i & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)], float) * 0.1
    T = np.array([[0, 1, 3, 7], [0, 1, 5, 7], [0, 2, 3, 7], [0, 2, 6, 7], [0, 4, 5, 7], [0, 4, 6, 7]])
    T = np.array([t if tets.signed_volumes6(P, t[None])[1][0] > 0 else t[[1, 0, 2, 3]] for t in T])
    r = tets.check(P, T, spacing="0.05")
    assert r["valid"] and r["not_delaunay"] == 0
    assert abs(r["radius_edge_max"] - np.sqrt(3) / 2) < 1e-12 and abs(r["r_over_f_max"] - np.sqrt(3)) < 1e-12
    assert abs(r["dihedral_min"] - 45) < 1e-9 and abs(r["dihedral_max"] - 90) < 1e-9
    # 19 edges: 12 of length 0.1, 6 face diagonals, 1 space diagonal; f = 0.05.
    assert r["edge_over_f_min"] == pytest.approx(2) and r["edge_over_f_max"] == pytest.approx(2 * np.sqrt(3))
    assert r["edge_over_f_mean"] == pytest.approx((12 * 2 + 6 * 2 * np.sqrt(2) + 2 * np.sqrt(3)) / 19)


def test_reads_vtu_written_by_meshio(tmp_path):
    meshio = pytest.importorskip("meshio")
    rng = np.random.default_rng(7)
    from scipy.spatial import Delaunay
    P = rng.random((60, 3))
    T = Delaunay(P).simplices
    T = np.array([t if tets.signed_volumes6(P, t[None])[1][0] > 0 else t[[1, 0, 2, 3]] for t in T])
    ref = tets.check(P, T, "0.2")
    for kw in ({"binary": False}, {"binary": True, "compression": None}, {}):  # ascii, base64, zlib
        f = str(tmp_path / "m.vtu")
        meshio.write(f, meshio.Mesh(P, [("tetra", T)], cell_data={"material": [np.ones(len(T), np.int32)]}), **kw)
        Q, U, cd = tets.read_vtu(f)
        assert np.array_equal(U, T) and cd["material"].tolist() == [1] * len(T)
        if kw.get("binary", True):
            assert np.array_equal(Q, P) and tets.check(Q, U, "0.2") == ref
        else:  # meshio's ASCII rounds the coordinates
            assert np.allclose(Q, P, rtol=1e-9, atol=0) and tets.check(Q, U, "0.2")["valid"]


@needs_convert
def test_checker_compares_written_fields(tmp_path):
    # The cube's cell data: radius_edge 0.866 written (sqrt(3)/2 = 0.8660254 computed), r_over_f made up.
    convert("--cube", str(tmp_path / "c.vtu"))
    r = subprocess.run([PY, os.path.join(HERE, "tets.py"), str(tmp_path / "c.vtu"), "--spacing", "0.1",
                        "--fields-tol", "1e-3", "--json", str(tmp_path / "c.json")], capture_output=True, text=True)
    with open(tmp_path / "c.json") as f:
        d = json.load(f)["field_rel_diff"]
    assert d["radius_edge"] == pytest.approx(abs(0.866 / (np.sqrt(3) / 2) - 1), rel=1e-6)
    assert d["r_over_f"] > 0.5 and r.returncode == 1, r.stdout


def test_conformity_of_the_cube_mesh(tmp_path):
    import conformity
    P = np.array([[i & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)], float)
    T = np.array([[0, 1, 3, 7], [0, 1, 5, 7], [0, 2, 3, 7], [0, 2, 6, 7], [0, 4, 5, 7], [0, 4, 6, 7]])
    cube = os.path.join(TESTDATA, "3d", "cube.poly")
    r = conformity.conformity(P, T, cube)
    assert r["facets_not_conforming"] == 0 and r["boundary_faces_off_facets"] == 0
    assert [f["area"] for f in r["facets"]] == [1.0] * 6
    # One tetrahedron less: two sides lose a triangle, two faces inside become boundary.
    r = conformity.conformity(P, T[1:], cube)
    assert r["facets_not_conforming"] == 2 and r["boundary_faces_off_facets"] == 2
    # An internal facet at z = 1/2 that no mesh face follows.
    mid = tmp_path / "mid.poly"
    with open(cube) as f:
        text = f.read()
    text = text.replace("8 3 0 0", "12 3 0 0").replace("6 1\n", "7 1\n1 0 7\n4 9 10 11 12\n")
    text = text.replace("8 0 1 1\n", "8 0 1 1\n9 0 0 0.5\n10 1 0 0.5\n11 1 1 0.5\n12 0 1 0.5\n")
    mid.write_text(text)
    r = conformity.conformity(P, T, str(mid))
    assert r["facets_not_conforming"] == 1 and r["facets"][0]["mesh_area"] == 0


@pytest.mark.skipif(shutil.which("tetgen") is None, reason="tetgen not installed")
def test_tetgen_meshes_positive_and_conforming_to_the_test_plcs(tmp_path):
    for name in ("layers.poly", "facet_hole.poly", "box_cavity.poly", "dihedral10.poly"):
        src = str(tmp_path / name)
        shutil.copy(os.path.join(TESTDATA, "3d", name), src)
        subprocess.run(["tetgen", "-pq1.5a0.1Q", src], check=True, capture_output=True, timeout=120)
        base = src[:-5] + ".1"
        N = np.loadtxt(base + ".node", skiprows=1)
        P = N[:, 1:4]
        T = np.loadtxt(base + ".ele", skiprows=1, dtype=np.int64)[:, 1:5] - int(N[0, 0])
        # TetGen's own .ele order has positive volume (tetio's writer relies on it), and its
        # meshes are valid for this checker as they stand.
        r = tets.check(P, T, delaunay=False)
        assert r["valid"] and r["nonpositive_volume"] == 0, name
        import conformity
        c = conformity.conformity(P, T, os.path.join(TESTDATA, "3d", name))
        assert c["facets_not_conforming"] == 0 and c["boundary_faces_off_facets"] == 0, (name, c)


def _yardstick(path, spacing):
    out = path + ".ys.json"
    subprocess.run([PY, YARDSTICK, path, "--spacing", spacing, "--json", out], capture_output=True, timeout=300)
    with open(out) as f:
        return json.load(f)


def _mine(path, spacing):
    P, T, _ = tets.read_vtu(path)
    return tets.check(P, T, spacing)


def _agree(path, spacing="0.1*(abs(x-5)+abs(y-5)+abs(z-5))+0.1"):
    a, b = _mine(path, spacing), _yardstick(path, spacing)
    assert a["tetrahedra"] == b["tetrahedra"] and a["vertices"] == b["vertices"]
    assert a["nonpositive_volume"] == b["nonpositive_volume"]
    assert a["faces_shared_gt2"] == b["faces_shared_gt2"] and a["boundary_faces"] == b["boundary_faces"]
    assert (a["not_delaunay"] == 0) == (b["not_delaunay"] == 0)
    for k in ("volume", "radius_edge_max", "dihedral_min", "dihedral_max"):
        assert a[k] == pytest.approx(b[k], rel=1e-9, abs=1e-9), k
    assert a["r_over_f_max"] == pytest.approx(b["R_over_f_max"], rel=1e-9)
    assert a["dihedral_lt5"] == b["dihedral_lt5"] and a["dihedral_lt10"] == b["dihedral_lt10"]
    return a


@needs_convert
@pytest.mark.skipif(not os.path.exists(YARDSTICK), reason="the yardstick verify_tets.py is not here")
def test_agrees_with_yardstick(tmp_path):
    base, P, T = random_delaunay(tmp_path, n=400)
    convert(base + ".ele", str(tmp_path / "r.vtu"), str(tmp_path / "r.b64.vtu"))
    a = _agree(str(tmp_path / "r.vtu"))
    assert a["valid"] and a["not_delaunay"] == 0
    assert _mine(str(tmp_path / "r.b64.vtu"), "1") == _mine(str(tmp_path / "r.vtu"), "1")
    # Not Delaunay: the random mesh with one interior face flipped 2-3 would need geometry; a
    # simpler case is the lone point inside a circumsphere (two separate tetrahedra).
    Q = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.3, 0.3, -0.2], [10, 10, 10], [10, 11, 10], [11, 10, 10],
                  [10, 10, 11]], float)
    T2 = np.array([[0, 1, 2, 3], [5, 6, 7, 8]])  # vertex 4 in no tetrahedron, inside the first one's sphere
    write_tetgen(str(tmp_path / "nd"), Q, T2)
    convert(str(tmp_path / "nd.ele"), str(tmp_path / "nd.vtu"))
    a = _agree(str(tmp_path / "nd.vtu"))
    assert a["not_delaunay"] == 1


@needs_convert
@pytest.mark.skipif(shutil.which("tetgen") is None or not os.path.exists(YARDSTICK), reason="tetgen or yardstick missing")
def test_agrees_with_yardstick_on_tetgen_meshes(tmp_path):
    for name, switches in (("cube10.poly", "-pq1.5a1Q"), ("box_cavity.poly", "-pq1.4a0.05Q")):
        src = str(tmp_path / name)
        shutil.copy(os.path.join(TESTDATA, "3d", name), src)
        subprocess.run(["tetgen", switches, src], check=True, capture_output=True, timeout=120)
        base = src[:-5] + ".1"
        convert(base + ".ele", base + ".vtu")
        a = _agree(base + ".vtu")
        assert a["valid"], name
