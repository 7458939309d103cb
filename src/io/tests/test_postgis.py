"""fdrmesh in and out of a real PostgreSQL + PostGIS server (CTest fixture postgis_server,
tools/postgis/cluster.sh): what the command line reads from and writes to the database.

Skipped, saying why, only when the fixture could not start the server (FDR_PG_STATE/conninfo
then reads "SKIP: <why>")."""
import os
import re
import shutil
import subprocess

import pytest

FDRMESH = os.environ.get("FDRMESH", "fdrmesh")
STATE = os.environ.get("FDR_PG_STATE", "")
TESTDATA = os.environ.get("FDR_TESTDATA", os.path.join(os.path.dirname(__file__), "..", "..", "..", "testdata"))
GPKG = os.path.join(TESTDATA, "chesapeake", "chesapeake_mouth.gpkg")
PASSWORD = "fdr-secret"  # the role fdr_pw of cluster.sh


def _conninfo():
    try:
        with open(os.path.join(STATE, "conninfo"), encoding="utf-8") as f:
            line = f.readline().strip()
    except OSError:
        return None, "no %s/conninfo (run through ctest: fixture postgis_server_start)" % STATE
    if line.startswith("SKIP:"):
        return None, "PostgreSQL test server not available:" + line[5:]
    return line, ""


CONN, WHY = _conninfo()
pytestmark = pytest.mark.skipif(CONN is None, reason=WHY)


def host():
    return re.search(r"host=(\S+)", CONN).group(1)


def sql(query):
    """One value (or rows joined by newlines) from psql as the superuser."""
    psql = shutil.which("psql") or "/usr/bin/psql"
    r = subprocess.run([psql, "-X", "-At", "-h", host(), "-p", "5432", "-U", "postgres", "-d", "fdrtest",
                        "-v", "ON_ERROR_STOP=1", "-c", query], capture_output=True, text=True, check=True)
    return r.stdout.strip()


def run(*args):
    return subprocess.run([FDRMESH, "mesh", *args], capture_output=True, text=True)


@pytest.fixture(scope="module", autouse=True)
def coast_tables():
    """The GeoPackage's layers as coast.water and coast.open_boundary, a view, a table without geometry."""
    if CONN is None:
        yield
        return
    r = subprocess.run(["ogr2ogr", "-f", "PostgreSQL", CONN, GPKG, "-overwrite", "-lco", "SCHEMA=coast",
                        "-lco", "GEOMETRY_NAME=geom", "-lco", "FID=fid"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    sql("CREATE OR REPLACE VIEW coast.water_view AS SELECT * FROM coast.water;"
        "DROP TABLE IF EXISTS coast.no_geometry; CREATE TABLE coast.no_geometry (id int, name text);"
        "INSERT INTO coast.no_geometry VALUES (1, 'a');"
        "GRANT SELECT ON ALL TABLES IN SCHEMA coast TO fdr_pw")
    yield


def drop_mesh(prefix, schema="public"):
    sql(";".join("DROP TABLE IF EXISTS %s.%s%s CASCADE" % (schema, prefix, t)
                 for t in ("nodes", "triangles", "boundaries", "repairs", "metadata")))


def gpkg_args():
    return [GPKG, "--layer", "water", "--open-boundary", GPKG, "--open-boundary-layer", "open_boundary"]


def pg_args(layer="coast.water"):
    return [CONN, "--layer", layer, "--open-boundary", CONN, "--open-boundary-layer", "coast.open_boundary"]


def body(path):
    """A 2DM without its MESHNAME line (the title names the source)."""
    with open(path, encoding="utf-8") as f:
        return [ln for ln in f if not ln.startswith("MESHNAME")]


def test_mesh_from_table_equals_mesh_from_geopackage(tmp_path):
    a, b, c = tmp_path / "pg.2dm", tmp_path / "gpkg.2dm", tmp_path / "view.2dm"
    r = run(*pg_args(), "-q", "-o", str(a))
    assert r.returncode == 0, r.stderr
    r = run(*gpkg_args(), "-q", "-o", str(b))
    assert r.returncode == 0, r.stderr
    r = run(*pg_args("coast.water_view"), "-q", "-o", str(c))
    assert r.returncode == 0, r.stderr
    assert body(a) == body(b)  # byte for byte but the title
    assert body(c) == body(b)
    assert len(body(a)) > 1000


def test_where_and_breaklines_points_from_the_database(tmp_path):
    a, b = tmp_path / "pg.2dm", tmp_path / "gpkg.2dm"
    sql("DROP TABLE IF EXISTS coast.pts; CREATE TABLE coast.pts AS SELECT 1 AS id, "
        "ST_SetSRID(ST_PointOnSurface(geom), 4326)::geometry(Point, 4326) AS geom FROM coast.water LIMIT 1")
    r = subprocess.run(["ogr2ogr", "-f", "GPKG", str(tmp_path / "pts.gpkg"), CONN, "coast.pts"], capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr
    r = run(*pg_args(), "--where", "fid >= 1", "--points", CONN, "--points-layer", "coast.pts", "-q", "-o", str(a))
    assert r.returncode == 0, r.stderr
    r = run(*gpkg_args(), "--where", "fid >= 1", "--points", str(tmp_path / "pts.gpkg"), "-q", "-o", str(b))
    assert r.returncode == 0, r.stderr
    assert body(a) == body(b)
    # A where clause that selects nothing is the same error as for a file.
    r = run(*pg_args(), "--where", "fid < 0", "-q", "-o", str(a))
    assert r.returncode == 5 and "where clause" in r.stderr, r.stderr


def test_write_and_read_back_with_ogr_and_sql(tmp_path):
    drop_mesh("mesh_")
    rep = tmp_path / "r.json"
    pw_conn = "PG:host=%s dbname=fdrtest user=fdr_pw password=%s" % (host(), PASSWORD)
    r = run(GPKG, "--layer", "water", "--keep-coast", "-o", pw_conn, "--report", str(rep))
    assert r.returncode == 0, r.stderr
    assert PASSWORD not in r.stdout + r.stderr
    assert "wrote PG:host=%s dbname=fdrtest user=fdr_pw\n" % host() in r.stdout, r.stdout
    import json
    with open(rep, encoding="utf-8") as f:
        report = json.load(f)
    # ogr: the layers and their counts.
    info = subprocess.run(["ogrinfo", "-ro", "-so", CONN, "mesh_triangles", "mesh_nodes"], capture_output=True,
                          text=True)
    assert info.returncode == 0, info.stderr
    counts = [int(n) for n in re.findall(r"Feature Count: (\d+)", info.stdout)]
    assert counts == [report["triangles"], report["vertices"]], info.stdout
    # SQL: counts, validity, the triangles cover the water polygons' area (UTM 18N) within 0.1 %.
    assert int(sql("SELECT count(*) FROM mesh_triangles")) == report["triangles"]
    assert sql("SELECT bool_and(ST_IsValid(geom)) FROM mesh_triangles") == "t"
    srid = sql("SELECT Find_SRID('public', 'mesh_triangles', 'geom')")
    assert srid == "32618"
    mesh_area = float(sql("SELECT sum(ST_Area(geom)) FROM mesh_triangles"))
    water_area = float(sql("SELECT sum(ST_Area(ST_Transform(geom, 32618))) FROM coast.water"))
    assert abs(mesh_area - water_area) <= 1e-3 * water_area, (mesh_area, water_area)
    assert sql("SELECT count(*) FROM mesh_nodes WHERE f IS NULL") == "0"  # no raster: z is NULL, as in the GeoPackage
    assert sql("SELECT count(*) FROM mesh_triangles WHERE quality IS NULL") == "0"
    assert set(sql("SELECT DISTINCT kind FROM mesh_boundaries").split()) <= {"land", "island", "open"}
    meta = sql("SELECT string_agg(key || '=' || left(value, 200), E'\\n') FROM mesh_metadata")
    assert "crs=WGS 84 / UTM zone 18N" in meta and "command_line=" in meta and PASSWORD not in meta
    assert int(sql("SELECT count(*) FROM pg_indexes WHERE tablename LIKE 'mesh\\_%' AND indexdef LIKE '%gist%'")) == 4


def test_overwrite_replaces_else_refuses(tmp_path):
    drop_mesh("ow_")
    base = [GPKG, "--layer", "water", "-q", "--pg-prefix", "ow_"]
    r = run(*base, "--spacing", "4000", "--of", "PostgreSQL", "-o", CONN)
    assert r.returncode == 0, r.stderr
    n = sql("SELECT count(*) FROM ow_triangles")
    r = run(*base, "--spacing", "3000", "-o", CONN)
    assert r.returncode == 8 and "--overwrite" in r.stderr and "ow_triangles" in r.stderr, r.stderr
    assert sql("SELECT count(*) FROM ow_triangles") == n
    r = run(GPKG, "--layer", "water", "--spacing", "3000", "-q", "--pg-prefix", "ow_", "--overwrite", "-o", CONN)
    assert r.returncode == 0, r.stderr
    assert sql("SELECT count(*) FROM ow_triangles") != n  # the second mesh replaced the first
    drop_mesh("ow_")


def test_schema_option(tmp_path):
    drop_mesh("sc_", "coast")
    r = run(GPKG, "--layer", "water", "--spacing", "4000", "-q", "--pg-prefix", "sc_", "--pg-schema", "coast",
            "-o", CONN)
    assert r.returncode == 0, r.stderr
    assert int(sql("SELECT count(*) FROM coast.sc_triangles")) > 0
    drop_mesh("sc_", "coast")


def error_of(*args):
    r = run(*args)
    assert PASSWORD not in r.stdout + r.stderr and "password=" not in r.stderr, r.stderr
    lines = [ln[ln.index("ERROR"):] for ln in r.stderr.splitlines() if "ERROR" in ln]
    assert len(lines) == 1, r.stderr
    return r.returncode, lines[0]


def test_errors_give_exit_codes_and_no_password(tmp_path):
    out = str(tmp_path / "x.2dm")
    h = host()
    wrong = "PG:host=%s dbname=fdrtest user=fdr_pw password=wrong-%s" % (h, PASSWORD)
    code, msg = error_of(wrong, "--layer", "coast.water", "-o", out)
    assert code == 3 and "user=fdr_pw" in msg and "password authentication failed" in msg, msg
    code, msg = error_of("PG:host=%s dbname=no_such_db user=fdr_pw password=%s" % (h, PASSWORD), "-o", out)
    assert code == 3 and "no_such_db" in msg and "does not exist" in msg, msg
    code, msg = error_of(CONN, "--layer", "coast.no_such_table", "-o", out)
    assert code == 3 and "no layer 'coast.no_such_table'" in msg, msg
    code, msg = error_of(CONN, "--layer", "coast.no_geometry", "-o", out)
    assert code == 3 and "no geometry column" in msg, msg
    # Output side: the same failures are output errors (8), nothing written.
    code, msg = error_of(GPKG, "--layer", "water", "--spacing", "4000", "-o", wrong)
    assert code == 8 and "user=fdr_pw" in msg and "password authentication failed" in msg, msg
    code, msg = error_of(GPKG, "--layer", "water", "--spacing", "4000", "--pg-schema", "no_such_schema", "-o", CONN)
    assert code == 8 and "no_such_schema" in msg, msg
    assert sql("SELECT count(*) FROM pg_tables WHERE schemaname = 'public' AND tablename LIKE 'mesh\\_%'") in ("0", "5")


def test_qgis_plugin_passes_a_postgis_layer_through(tmp_path):
    """A PostGIS layer chosen in QGIS reaches fdrmesh as PG: + --layer schema.table (+ --where
    for a layer filter), not as an exported copy; the logged command shows no password."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    qgis_core = pytest.importorskip("qgis.core")
    import sys
    plugins = os.path.join(os.path.dirname(__file__), "..", "..", "..", "plugins", "qgis")
    saved = {k: v for k, v in sys.modules.items() if k == "fdrmesh" or k.startswith("fdrmesh.")}
    for k in saved:
        del sys.modules[k]
    sys.path.insert(0, plugins)
    try:
        from fdrmesh import fdrmesh_algorithm as fa  # the plugin's package, named as the Python module
    finally:
        sys.path.remove(plugins)
        for k in [k for k in sys.modules if k == "fdrmesh" or k.startswith("fdrmesh.")]:
            del sys.modules[k]
        sys.modules.update(saved)
    app = qgis_core.QgsApplication([], False)
    app.initQgis()
    uri = ("dbname='fdrtest' host=%s port=5432 user='fdr_pw' password='%s' key='fid' srid=4326 type=Polygon "
           "checkPrimaryKeyUnicity='0' table=\"coast\".\"water\" (geom) sql=fid >= 1" % (host(), PASSWORD))
    layer = qgis_core.QgsVectorLayer(uri, "water", "postgres")
    assert layer.isValid()
    os.environ["FDRMESH"] = FDRMESH
    alg = fa.FdrmeshMeshCoastalAlgorithm().create()
    out = tmp_path / "q.gpkg"
    context = qgis_core.QgsProcessingContext()
    args, _ = alg.build_command({"INPUT": layer, "OUTPUT": str(out)}, context, qgis_core.QgsProcessingFeedback())
    assert args[2].startswith("PG:") and "dbname=fdrtest" in args[2] and "user=fdr_pw" in args[2], args
    assert args[args.index("--layer") + 1] == "coast.water" and args[args.index("--where") + 1] == "fid >= 1", args
    logged = fa.redact_passwords(" ".join(fa._quote(a) for a in args))
    assert PASSWORD not in logged and "user=fdr_pw" in logged, logged
    # The CLI reads what the plugin passes: the same mesh as from the GeoPackage.
    a, b = tmp_path / "q.2dm", tmp_path / "g.2dm"
    r = subprocess.run([FDRMESH, "mesh", *args[2:3], "--layer", "coast.water", "--where", "fid >= 1", "-q", "-o",
                        str(a)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    r = run(GPKG, "--layer", "water", "-q", "-o", str(b))
    assert r.returncode == 0, r.stderr
    assert body(a) == body(b)
    del layer


def test_python_reads_and_writes_the_database(tmp_path):
    """fdrmesh.mesh takes the same options: a table in, tables out; errors without password."""
    fdrmesh = pytest.importorskip("fdrmesh")
    if not hasattr(fdrmesh, "mesh"):
        pytest.skip("the fdrmesh Python module is not built")
    drop_mesh("py_")
    pw_conn = "PG:host=%s dbname=fdrtest user=fdr_pw password=%s" % (host(), PASSWORD)
    m = fdrmesh.mesh(pw_conn, layer="coast.water", spacing="4000", output=[pw_conn], pg_prefix="py_")
    assert int(sql("SELECT count(*) FROM py_triangles")) == len(m.triangles)
    with pytest.raises(fdrmesh.OutputError) as e:
        fdrmesh.mesh(CONN, layer="coast.water", spacing="4000", output=[pw_conn], pg_prefix="py_")
    assert "--overwrite" in str(e.value) and PASSWORD not in str(e.value)
    with pytest.raises(fdrmesh.InputUnreadableError) as e:
        fdrmesh.mesh(pw_conn.replace(PASSWORD, "wrong-" + PASSWORD), layer="coast.water", spacing="4000")
    assert "user=fdr_pw" in str(e.value) and PASSWORD not in str(e.value), str(e.value)
    drop_mesh("py_")
