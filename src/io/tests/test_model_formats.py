# Coastal-model outputs of one fdrmesh run (fort.14, hgrid.gr3/.ll, 2DM, Selafin + .cli, Delft3D FM
# net file) read back by small parsers written from the published formats (not from the writers'
# code), checked against each other and against the quality report. Run by CTest with FDRMESH set.
import json
import math
import os
import shutil
import struct
import subprocess

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
CHES = os.path.join(REPO, "testdata", "chesapeake")
FDRMESH = os.environ.get("FDRMESH") or shutil.which("fdrmesh")


# ---------------------------------------------------------------- parsers (published formats)
def parse_adcirc(path, schism):
    """ADCIRC fort.14 / SCHISM hgrid.gr3: nodes, elements, open and land boundary lists."""
    with open(path) as f:
        lines = f.read().splitlines()
    it = iter(lines)
    title = next(it)
    ne, np_ = (int(t) for t in next(it).split()[:2])
    nodes = {}
    for _ in range(np_):
        t = next(it).split()
        nodes[int(t[0])] = (float(t[1]), float(t[2]), float(t[3]))
    elems = []
    for _ in range(ne):
        t = next(it).split()
        assert t[1] == "3"
        elems.append(tuple(int(x) for x in t[2:5]))
    nope = int(next(it).split()[0])
    neta = int(next(it).split()[0])
    opens = []
    for _ in range(nope):
        head = next(it).split()
        n = int(head[0])
        if not schism:
            assert head[1] == "0", "fort.14 IBTYPEE of an elevation boundary is 0"
        opens.append([int(next(it).split()[0]) for _ in range(n)])
    assert sum(len(o) for o in opens) == neta
    nbou = int(next(it).split()[0])
    nvel = int(next(it).split()[0])
    lands = []
    for _ in range(nbou):
        head = next(it).split()
        n, ibtype = int(head[0]), int(head[1])
        lands.append((ibtype, [int(next(it).split()[0]) for _ in range(n)]))
    assert sum(len(l) for _, l in lands) == nvel
    return {"title": title, "nodes": nodes, "elems": elems, "open": opens, "land": lands}


def parse_2dm(path):
    nodes, elems, strings, cur = {}, [], [], []
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "ND":
                nodes[int(t[1])] = (float(t[2]), float(t[3]), float(t[4]))
            elif t[0] == "E3T":
                elems.append(tuple(int(x) for x in t[2:5]))
            elif t[0] == "NS":
                for x in t[1:]:
                    v = int(x)
                    cur.append(abs(v))
                    if v < 0:
                        strings.append(cur)
                        cur = []
                        break
    assert not cur
    return nodes, elems, strings


def parse_cli(path):
    rows = []
    with open(path) as f:
        for line in f:
            t = line.split()
            assert len(t) == 13, line
            rows.append((tuple(int(x) for x in t[0:3]), int(t[7]), int(t[11]), int(t[12])))
    return rows


def read_selafin(path):
    """Selafin: big-endian Fortran records (title, NBV, names, IPARAM, [date], sizes, IKLE, IPOBO, X, Y, steps)."""
    with open(path, "rb") as f:
        data = f.read()
    pos = 0

    def record():
        nonlocal pos
        (n,) = struct.unpack(">i", data[pos:pos + 4])
        body = data[pos + 4:pos + 4 + n]
        (m,) = struct.unpack(">i", data[pos + 4 + n:pos + 8 + n])
        assert m == n
        pos += 8 + n
        return body

    title = record()
    kind = title[72:80].decode()
    real = ">d" if kind == "SERAFIND" else ">f"
    size = 8 if kind == "SERAFIND" else 4
    nbv1, nbv2 = struct.unpack(">2i", record())
    names = [record().decode() for _ in range(nbv1 + nbv2)]
    iparam = struct.unpack(">10i", record())
    if iparam[9] == 1:
        record()
    nelem, npoin, ndp, one = struct.unpack(">4i", record())
    ikle = struct.unpack(">%di" % (nelem * ndp), record())
    ipobo = struct.unpack(">%di" % npoin, record())
    x = struct.unpack(">%d%s" % (npoin, real[1]), record())
    y = struct.unpack(">%d%s" % (npoin, real[1]), record())
    steps = []
    while pos < len(data):
        (t,) = struct.unpack(real, record())
        steps.append((t, [struct.unpack(">%d%s" % (npoin, real[1]), record()) for _ in names]))
    assert size * npoin == len(steps[0][1][0]) * size
    return {"kind": kind, "names": names, "iparam": iparam, "nelem": nelem, "npoin": npoin, "ndp": ndp,
            "ikle": ikle, "ipobo": ipobo, "x": [v + iparam[2] for v in x], "y": [v + iparam[3] for v in y],
            "steps": steps}


# ---------------------------------------------------------------- helpers
def directed_boundary_edges(elems):
    """Edges used by one triangle, directed as in that (counter-clockwise) triangle."""
    count = {}
    for a, b, c in elems:
        for u, v in ((a, b), (b, c), (c, a)):
            count[(u, v)] = count.get((u, v), 0) + 1
    return {e for e in count if (e[1], e[0]) not in count}


def list_edges(nodes):
    return list(zip(nodes, nodes[1:]))


def signed_area(nodes, xy):
    s = 0.0
    for a, b in zip(nodes, nodes[1:] + nodes[:1]):
        s += xy[a][0] * xy[b][1] - xy[b][0] * xy[a][1]
    return s / 2


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    if not FDRMESH:
        pytest.skip("set FDRMESH")
    d = tmp_path_factory.mktemp("models")
    names = ["m.gpkg", "m.slf", "m.gr3", "m.ll", "m_net.nc", "m.14", "m.2dm"]
    cmd = [FDRMESH, "mesh", os.path.join(CHES, "chesapeake_mouth_water.geojson"),
           "--open-boundary", os.path.join(CHES, "chesapeake_mouth_open_boundary.geojson"),
           "--raster", os.path.join(CHES, "chesapeake_mouth_etopo5.tif"), "-q", "--report", str(d / "r.json")]
    for n in names:
        cmd += ["-o", str(d / n)]
    r = subprocess.run(cmd, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    dd = d / "double"
    dd.mkdir()
    r = subprocess.run(cmd[:cmd.index("-q")] + ["-q", "--slf-double", "--telemac-open", "4,5,5",
                                                 "-o", str(dd / "m.slf")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with open(d / "r.json") as f:
        report = json.load(f)
    return {"dir": d, "report": report}


def test_counts_and_depths(run):
    d, rep = run["dir"], run["report"]
    f14 = parse_adcirc(d / "m.14", schism=False)
    gr3 = parse_adcirc(d / "m.gr3", schism=True)
    ll = parse_adcirc(d / "m.ll", schism=True)
    nodes2dm, elems2dm, _ = parse_2dm(d / "m.2dm")
    slf = read_selafin(d / "m.slf")
    for n, e in ((f14["nodes"], f14["elems"]), (gr3["nodes"], gr3["elems"]), (ll["nodes"], ll["elems"]),
                 (nodes2dm, elems2dm)):
        assert len(n) == rep["vertices"] and len(e) == rep["triangles"]
    assert slf["npoin"] == rep["vertices"] and slf["nelem"] == rep["triangles"] and slf["ndp"] == 3
    assert gr3["elems"] == f14["elems"] == ll["elems"] == elems2dm
    assert [tuple(slf["ikle"][3 * i:3 * i + 3]) for i in range(slf["nelem"])] == gr3["elems"]
    # Depth positive down in fort.14/gr3/ll, z positive up in 2DM and Selafin BOTTOM.
    assert slf["kind"] == "SERAFIN " and slf["names"] == ["BOTTOM          M               "]
    assert slf["iparam"][0] == 1 and slf["iparam"][6] == 0
    bottom = slf["steps"][0][1][0]
    assert len(slf["steps"]) == 1 and slf["steps"][0][0] == 0.0
    for i in range(1, rep["vertices"] + 1):
        dp = gr3["nodes"][i][2]
        assert f14["nodes"][i][2] == dp and ll["nodes"][i][2] == dp
        assert nodes2dm[i][2] == -dp or (dp == 0 and nodes2dm[i][2] == 0)
        assert abs(bottom[i - 1] + dp) <= 1e-5 * max(1.0, abs(dp))
        # Single precision with the I_ORIG/J_ORIG offset keeps about a millimetre.
        assert abs(slf["x"][i - 1] - gr3["nodes"][i][0]) < 5e-3
        assert abs(slf["y"][i - 1] - gr3["nodes"][i][1]) < 5e-3
        assert gr3["nodes"][i][:2] == f14["nodes"][i][:2] == nodes2dm[i][:2]
        lon, lat = ll["nodes"][i][:2]
        assert -76.61 <= lon <= -75.59 and 36.74 <= lat <= 37.76
    assert slf["iparam"][2] != 0 and slf["iparam"][3] != 0  # UTM metres: an origin offset is used
    dbl = read_selafin(d / "double" / "m.slf")
    assert dbl["kind"] == "SERAFIND" and dbl["iparam"][2] == 0 and dbl["iparam"][3] == 0
    for i in range(1, rep["vertices"] + 1):
        assert (dbl["x"][i - 1], dbl["y"][i - 1]) == gr3["nodes"][i][:2]
        assert dbl["steps"][0][1][0][i - 1] == -gr3["nodes"][i][2] or gr3["nodes"][i][2] == 0


def test_boundaries_identical_across_formats(run):
    d = run["dir"]
    f14 = parse_adcirc(d / "m.14", schism=False)
    gr3 = parse_adcirc(d / "m.gr3", schism=True)
    ll = parse_adcirc(d / "m.ll", schism=True)
    _, _, strings = parse_2dm(d / "m.2dm")
    cli = parse_cli(d / "m.cli")
    slf = read_selafin(d / "m.slf")
    xy = {i: v[:2] for i, v in gr3["nodes"].items()}
    bnd = directed_boundary_edges(gr3["elems"])
    assert len(f14["open"]) > 1 and any(t == 1 for t, _ in f14["land"]), "extract must have open boundaries and islands"

    # Every list runs with the mesh on its left: each step is a boundary edge of the counter-clockwise
    # triangles, in that direction; together the lists of a format cover every boundary edge once.
    def edge_kinds(opens, lands, close_islands):
        kinds = {}
        for o in opens:
            for e in list_edges(o):
                assert e not in kinds
                kinds[e] = "open"
        for t, l in lands:
            seq = l + [l[0]] if (close_islands and t == 1 and l[0] != l[-1]) else l
            for e in list_edges(seq):
                assert e not in kinds
                kinds[e] = "island" if t == 1 else "land"
        return kinds

    k14 = edge_kinds(f14["open"], f14["land"], False)
    kgr3 = edge_kinds(gr3["open"], gr3["land"], True)
    assert set(k14) == bnd and k14 == kgr3
    assert ll["open"] == gr3["open"] and ll["land"] == gr3["land"]
    # Same order: open boundaries identical lists; land lists equal up to the closure convention
    # (fort.14 repeats the first node of a closed loop, gr3 splits an outer loop of one kind in two
    # and leaves islands open-ended).
    assert f14["open"] == gr3["open"]
    g = iter(gr3["land"])
    for t, l in f14["land"]:
        a = next(g)
        assert a[0] == t
        if l[0] != l[-1]:
            assert a[1] == l
        elif t == 1:
            assert a[1] + [a[1][0]] == l
        else:
            b = next(g)
            assert b[0] == t and a[1] + b[1][1:] == l
    assert next(g, None) is None
    # Orientation: closed outer loops counter-clockwise, islands clockwise.
    for t, l in f14["land"]:
        if l[0] == l[-1]:
            area = signed_area(l[:-1], xy)
            assert (area < 0) if t == 1 else (area > 0)
    # 2DM: the fort.14 lists in the same order, closed ones split in two nodestrings.
    s = iter(strings)
    for l in f14["open"] + [l for _, l in f14["land"]]:
        a = next(s)
        if l[0] != l[-1]:
            assert a == l
        else:
            b = next(s)
            assert a + b[1:] == l
    assert next(s, None) is None
    # Telemac: .cli in IPOBO order; N K columns; consecutive nodes of a loop are boundary edges in
    # loop direction; open nodes (5 4 4) are exactly the nodes of the open boundaries.
    assert [r[3] for r in cli] == list(range(1, len(cli) + 1))
    ipobo = slf["ipobo"]
    assert sum(1 for v in ipobo if v) == len(cli)
    for codes, litbor, n, k in cli:
        assert ipobo[n - 1] == k
    open_nodes = {v for o in f14["open"] for v in o}
    for codes, litbor, n, k in cli:
        assert (codes, litbor) == (((5, 4, 4), 4) if n in open_nodes else ((2, 2, 2), 2))
    order = [r[2] for r in cli]
    assert len(set(order)) == len(order)
    steps = sum(1 for a, b in zip(order, order[1:]) if (a, b) in bnd)
    loops = len(order) - steps
    assert steps + loops == len(bnd)  # each loop closes with one edge not listed consecutively
    # The .cli starts with the first open boundary of fort.14.
    assert order[:len(f14["open"][0])] == f14["open"][0]
    dcli = parse_cli(d / "double" / "m.cli")
    assert [r[2] for r in dcli] == order
    assert {r[0] for r in dcli} == {(4, 5, 5), (2, 2, 2)}


def test_net_file_every_edge(run):
    netCDF4 = pytest.importorskip("netCDF4")
    d, rep = run["dir"], run["report"]
    gr3 = parse_adcirc(d / "m.gr3", schism=True)
    with netCDF4.Dataset(d / "m_net.nc") as nc:
        assert nc.Conventions == "CF-1.8 UGRID-1.0 Deltares-0.10"
        m = nc["mesh2d"]
        assert m.cf_role == "mesh_topology" and m.topology_dimension == 2
        assert m.edge_node_connectivity == "mesh2d_edge_nodes"
        nv, nf = len(nc.dimensions["mesh2d_nNodes"]), len(nc.dimensions["mesh2d_nFaces"])
        assert nv == rep["vertices"] and nf == rep["triangles"]
        faces = nc["mesh2d_face_nodes"][:].tolist()
        edges = nc["mesh2d_edge_nodes"][:].tolist()
        etype = nc["mesh2d_edge_type"][:].tolist()
        assert nc["mesh2d_face_nodes"].start_index == 1 and nc["mesh2d_edge_nodes"].start_index == 1
        z = nc["mesh2d_node_z"][:].tolist()
        x = nc["mesh2d_node_x"][:].tolist()
        assert nc["projected_coordinate_system"].epsg == 32618
        fx = nc["mesh2d_face_x"][:].tolist()
        fy = nc["mesh2d_face_y"][:].tolist()
    assert [tuple(f) for f in faces] == gr3["elems"]
    for i in range(nv):
        assert z[i] == -gr3["nodes"][i + 1][2] or gr3["nodes"][i + 1][2] == 0
        assert x[i] == gr3["nodes"][i + 1][0]
    from_faces = {frozenset(e) for a, b, c in faces for e in ((a, b), (b, c), (c, a))}
    listed = [frozenset(e) for e in edges]
    assert len(set(listed)) == len(listed) and set(listed) == from_faces
    bnd = directed_boundary_edges(gr3["elems"])
    # 3F = 2 E_interior + E_boundary, and Euler: E = V + F - (outer loops) + (islands).
    assert 3 * nf == 2 * (len(edges) - len(bnd)) + len(bnd)
    f14 = parse_adcirc(d / "m.14", schism=False)
    xy = {i: v[:2] for i, v in gr3["nodes"].items()}
    # Loops from the directed boundary edges.
    nxt = {a: b for a, b in bnd}
    seen, outer, holes = set(), 0, 0
    for a in nxt:
        if a in seen:
            continue
        loop = [a]
        seen.add(a)
        while nxt[loop[-1]] != a:
            loop.append(nxt[loop[-1]])
            seen.add(loop[-1])
        if signed_area(loop, xy) > 0:
            outer += 1
        else:
            holes += 1
    assert len(edges) == nv + nf - outer + holes
    # Edge types: 2 open, 3 closed boundary, 1 interior.
    open_edges = {frozenset(e) for o in f14["open"] for e in list_edges(o)}
    for e, t in zip(edges, etype):
        fe = frozenset(e)
        if tuple(e) in bnd or (e[1], e[0]) in bnd:
            assert t == (2 if fe in open_edges else 3)
        else:
            assert t == 1
    # Face coordinates are circumcentres: equidistant from the three corners.
    for k in range(0, nf, 97):
        dists = [math.hypot(fx[k] - xy[v][0], fy[k] - xy[v][1]) for v in faces[k]]
        assert max(dists) - min(dists) <= 1e-6 * max(dists)


def test_quality_round_trip(run):
    d, rep = run["dir"], run["report"]
    assert 0 <= rep["orthogonality"]["p99"] <= rep["orthogonality"]["max"] <= 1
    assert 1 <= rep["smoothness"]["p99"] <= rep["smoothness"]["max"]
    for name, tol in (("m.gr3", 1e-9), ("m.14", 1e-9), ("m.2dm", 1e-9), ("m.slf", 1e-3),
                      ("double/m.slf", 1e-9)):
        out = d / (name.replace("/", "_") + ".json")
        r = subprocess.run([FDRMESH, "quality", str(d / name), "-q", "--report", str(out)],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        with open(out) as f:
            q = json.load(f)
        assert q["vertices"] == rep["vertices"] and q["triangles"] == rep["triangles"], name
        assert abs(q["min_angle_deg"] - rep["min_angle_deg"]) <= tol * max(1, rep["min_angle_deg"]), name
        assert abs(q["orthogonality"]["p99"] - rep["orthogonality"]["p99"]) <= 1e-3, name
        assert abs(q["smoothness"]["max"] - rep["smoothness"]["max"]) <= 1e-3 * rep["smoothness"]["max"], name


def test_usage_publishes_formats():
    if not FDRMESH:
        pytest.skip("set FDRMESH")
    j = json.loads(subprocess.run([FDRMESH, "--json-usage"], capture_output=True, text=True).stdout)
    fm = {f["name"]: f for f in j["output_formats"]}
    for name, ext in (("SELAFIN", ".slf"), ("GR3", ".gr3"), ("LL", ".ll"), ("DFLOWFM", "_net.nc"),
                      ("FORT14", ".14"), ("2DM", ".2dm"), ("GPKG", ".gpkg"), ("UGRID", ".nc")):
        assert ext in fm[name]["extensions"] and fm[name]["carries"]
    mesh = next(c for c in j["commands"] if c["name"] == "mesh")
    of = next(o for o in mesh["options"] if o["key"] == "of")
    assert of["choices"] == [f["name"] for f in j["output_formats"]]
    keys = {o["key"] for o in mesh["options"]}
    assert {"slf-double", "telemac-open"} <= keys
    h = subprocess.run([FDRMESH, "mesh", "--help"], capture_output=True, text=True).stdout
    for s in (".slf", ".gr3", ".ll", "_net.nc", "--slf-double", "--telemac-open"):
        assert s in h, s


def test_bad_telemac_codes_and_ll_without_crs(tmp_path):
    if not FDRMESH:
        pytest.skip("set FDRMESH")
    poly = os.path.join(REPO, "testdata", "poly", "square10.poly")
    r = subprocess.run([FDRMESH, "mesh", poly, "--telemac-open", "5,4", "-o", str(tmp_path / "a.slf")],
                       capture_output=True, text=True)
    assert r.returncode == 2 and "ERROR 2: --telemac-open" in r.stderr
    r = subprocess.run([FDRMESH, "mesh", poly, "-o", str(tmp_path / "a.ll")], capture_output=True, text=True)
    assert r.returncode == 2 and "hgrid.ll needs lon/lat" in r.stderr
    assert os.listdir(tmp_path) == []
    # A .poly square: one outer loop of one kind; gr3 splits it in two land segments.
    r = subprocess.run([FDRMESH, "mesh", poly, "-q", "-o", str(tmp_path / "a.gr3"), "-o", str(tmp_path / "a.slf")],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    g = parse_adcirc(tmp_path / "a.gr3", schism=True)
    assert g["open"] == [] and len(g["land"]) == 2 and all(t == 0 for t, _ in g["land"])
    assert g["land"][0][1][-1] == g["land"][1][1][0] and g["land"][1][1][-1] == g["land"][0][1][0]
    assert sorted(os.listdir(tmp_path)) == ["a.cli", "a.gr3", "a.slf"]


def test_gpkg_boundary_kinds_agree(run):
    """The GeoPackage 'boundaries' layer (lines by kind) tags every boundary edge as the model formats do."""
    ogr = pytest.importorskip("osgeo.ogr")
    d = run["dir"]
    f14 = parse_adcirc(d / "m.14", schism=False)
    node_of = {v[:2]: i for i, v in f14["nodes"].items()}  # shortest round-trip text: exact doubles
    want = {}
    for o in f14["open"]:
        for a, b in list_edges(o):
            want[frozenset((a, b))] = "open"
    for t, l in f14["land"]:
        for a, b in list_edges(l):
            want[frozenset((a, b))] = "island" if t == 1 else "land"
    ds = ogr.Open(str(d / "m.gpkg"))
    got = {}
    for f in ds.GetLayerByName("boundaries"):
        kind = f.GetField("kind")
        if kind not in ("open", "land", "island"):
            continue
        g = f.GetGeometryRef()
        pts = [node_of[(g.GetX(i), g.GetY(i))] for i in range(g.GetPointCount())]
        for a, b in zip(pts, pts[1:]):
            got[frozenset((a, b))] = kind
    ds = None
    assert got == want
