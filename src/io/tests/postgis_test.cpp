// PostGIS writer against a real server (tools/postgis/cluster.sh, started by CTest's fixture):
// tables and columns, the one transaction (a failure injected after each table leaves no table),
// --overwrite, connection errors without passwords; and password redaction itself (no server).
#include <gtest/gtest.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "base/edge_kind.hpp"
#include "base/error.hpp"
#include "base/redact.hpp"
#include "io/pg_conn.hpp"
#include "io/pg_copy.hpp"
#include "io/writer.hpp"

using namespace fdr;
namespace pg = fdr::io::pg;

namespace {

// The test database's connection string, or "" with the reason the server is not there.
std::string test_database(std::string& why) {
  std::ifstream in(std::string(FDR_PG_STATE) + "/conninfo");
  std::string line;
  if (!in || !std::getline(in, line)) {
    why = "no " FDR_PG_STATE "/conninfo: run through ctest (fixture postgis_server_start)";
    return "";
  }
  if (line.rfind("SKIP:", 0) == 0) {
    why = "PostgreSQL test server not available: " + line.substr(5);
    return "";
  }
  return line;
}

#define NEED_SERVER(conn)                  \
  std::string why_;                        \
  const std::string conn = test_database(why_); \
  if (conn.empty()) GTEST_SKIP() << why_

std::int32_t mk(EdgeKind k) { return static_cast<std::int32_t>(k); }

// A 4x4 square of 8 triangles around a centre vertex, land below, open elsewhere, in UTM 18N.
mesh::MeshView square() {
  mesh::MeshView m;
  m.origin = {400000.0, 4100000.0};
  m.vertices = {{0, 0}, {2, 0}, {4, 0}, {4, 2}, {4, 4}, {2, 4}, {0, 4}, {0, 2}, {2, 2}};
  for (Index k = 0; k < 8; ++k) m.triangles.push_back({k, (k + 1) % 8, 8});
  for (Index k = 0; k < 8; ++k) m.edges.push_back({k, (k + 1) % 8, mk(k < 2 ? EdgeKind::kLand : EdgeKind::kOpen), 0});
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    m.z.push_back(-1.0 - static_cast<double>(v));
    m.f.push_back(2.0);
  }
  OGRSpatialReference srs;
  srs.importFromEPSG(32618);
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  m.crs_wkt = wkt;
  CPLFree(wkt);
  return m;
}

io::WriteOptions options(const std::string& prefix) {
  io::WriteOptions o;
  o.bound_B = 1.0;
  o.title = "postgis test";
  o.metadata = {{"software", "fdrmesh test"}, {"command_line", "fdrmesh mesh PG:dbname=x password=hunter2 -o y"}};
  o.repairs = {{"snap", 400001.0, 4100001.0, 0.01, "vertices closer than tolerance", 0}};
  o.postgis.prefix = prefix;
  return o;
}

struct Db {
  GDALDataset* ds = nullptr;
  explicit Db(const std::string& conn) {
    GDALAllRegister();
    ds = GDALDataset::Open(conn.c_str(), GDAL_OF_VECTOR);
  }
  ~Db() {
    if (ds) GDALClose(ds);
  }
  std::string value(const std::string& sql) const {
    OGRLayer* q = ds->ExecuteSQL(sql.c_str(), nullptr, nullptr);
    if (!q) return "<no result>";
    std::unique_ptr<OGRFeature> row(q->GetNextFeature());
    std::string r = row ? row->GetFieldAsString(0) : "<no row>";
    ds->ReleaseResultSet(q);
    return r;
  }
  // Tables whose name starts with `prefix`, in the public schema.
  int tables(const std::string& prefix) const {
    return std::stoi(value("SELECT count(*) FROM pg_tables WHERE schemaname = 'public' AND tablename LIKE '" + prefix +
                           "%'"));
  }
  // Staging schemas a write left behind.
  std::string staging() const {
    return value("SELECT count(*) FROM pg_namespace WHERE nspname LIKE 'fdr\\_staging\\_%'");
  }
  void drop(const std::string& prefix) const {
    for (const char* t : {"nodes", "triangles", "boundaries", "repairs", "metadata"}) {
      OGRLayer* r = ds->ExecuteSQL(("DROP TABLE IF EXISTS public." + prefix + t + " CASCADE").c_str(), nullptr, nullptr);
      if (r) ds->ReleaseResultSet(r);
    }
  }
};

Error write_error(const mesh::MeshView& m, const std::string& conn, const io::WriteOptions& o) {
  try {
    io::write_mesh(m, conn, io::Format::kPostgis, o);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error writing to " << conn;
  return Error(ExitCode::kOk, "");
}

}  // namespace

TEST(Redact, RemovesPasswordsOnly) {
  EXPECT_EQ(redact_passwords("PG:dbname=x password=secret host=h"), "PG:dbname=x host=h");
  EXPECT_EQ(redact_passwords("PG:dbname=x host=h password=secret"), "PG:dbname=x host=h");
  EXPECT_EQ(redact_passwords("PG:password = 'a b\\' c' dbname=x"), "PG:dbname=x");
  EXPECT_EQ(redact_passwords("PG:dbname=x PASSWORD=s\nnext line"), "PG:dbname=x\nnext line");
  EXPECT_EQ(redact_passwords("postgresql://me:secret@db.example/x?sslmode=require"),
            "postgresql://me@db.example/x?sslmode=require");
  EXPECT_EQ(redact_passwords("postgresql://h/x?user=me&password=secret&a=1"), "postgresql://h/x?user=me&a=1");
  EXPECT_EQ(redact_passwords("FATAL: password authentication failed for user \"fdr_pw\""),
            "FATAL: password authentication failed for user \"fdr_pw\"");
  EXPECT_EQ(redact_passwords("/data/coast.gpkg"), "/data/coast.gpkg");
}

TEST(Postgis, FormatFromConnectionString) {
  EXPECT_EQ(io::format_from_path("PG:dbname=x"), io::Format::kPostgis);
  EXPECT_EQ(io::format_from_path("pg:dbname=x"), io::Format::kPostgis);
  EXPECT_EQ(io::format_from_path("dbname=x", "PostgreSQL"), io::Format::kPostgis);
}

TEST(Postgis, WritesTheGeoPackageTables) {
  NEED_SERVER(conn);
  const mesh::MeshView m = square();
  Db db(conn);
  ASSERT_TRUE(db.ds) << conn;
  db.drop("t1_");
  io::write_mesh(m, conn, io::Format::kPostgis, options("t1_"));
  EXPECT_EQ(db.tables("t1_"), 5);
  EXPECT_EQ(db.value("SELECT count(*) FROM t1_nodes"), "9");
  EXPECT_EQ(db.value("SELECT count(*) FROM t1_triangles WHERE ST_IsValid(geom)"), "8");
  EXPECT_EQ(db.value("SELECT sum(ST_Area(geom)) FROM t1_triangles"), "16");
  EXPECT_EQ(db.value("SELECT Find_SRID('public', 't1_triangles', 'geom')"), "32618");
  EXPECT_EQ(db.value("SELECT z FROM t1_nodes WHERE id = 3"), "-3");
  EXPECT_EQ(db.value("SELECT string_agg(kind, ',' ORDER BY kind) FROM t1_boundaries"), "land,open");
  EXPECT_EQ(db.value("SELECT count(*) FROM t1_repairs"), "1");
  // Without f no R/f(c); the quality is the triangles' shape (right isosceles: sqrt(3)/2).
  EXPECT_EQ(db.value("SELECT count(*) FROM t1_triangles WHERE \"R_over_f\" IS NOT NULL"), "0");
  EXPECT_EQ(db.value("SELECT count(*) FROM t1_triangles WHERE abs(quality - sqrt(3) / 2) < 1e-12"), "8");
  // Passwords never reach the metadata.
  EXPECT_EQ(db.value("SELECT value FROM t1_metadata WHERE key = 'command_line'"), "fdrmesh mesh PG:dbname=x -o y");
  EXPECT_EQ(db.value("SELECT value FROM t1_metadata WHERE key = 'title'"), "postgis test");
  for (const char* t : {"nodes", "triangles", "boundaries", "repairs"})
    EXPECT_EQ(db.value(std::string("SELECT count(*) FROM pg_indexes WHERE tablename = 't1_") + t +
                       "' AND indexdef LIKE '%USING gist (geom)%'"),
              "1")
        << t;
  for (const char* t : {"nodes", "triangles", "boundaries", "repairs", "metadata"})
    EXPECT_EQ(db.value(std::string("SELECT string_agg(conname || ':' || pg_get_constraintdef(oid), ',') FROM "
                                   "pg_constraint WHERE contype = 'p' AND conrelid = 'public.t1_") + t + "'::regclass"),
              std::string("t1_") + t + "_pkey:PRIMARY KEY (fid)")
        << t;
  // The write runs no ANALYZE (autovacuum does); the index builds give the planner the row counts.
  EXPECT_EQ(db.value("SELECT reltuples::bigint FROM pg_class WHERE oid = 'public.t1_triangles'::regclass"), "8");
  EXPECT_EQ(db.value("SELECT reltuples::bigint FROM pg_class WHERE oid = 'public.t1_nodes'::regclass"), "9");
  // OGR reads the tables back as layers.
  OGRLayer* l = db.ds->GetLayerByName("t1_triangles");
  ASSERT_NE(l, nullptr);
  EXPECT_EQ(l->GetFeatureCount(), 8);
  EXPECT_EQ(wkbFlatten(l->GetGeomType()), wkbPolygon);
  db.drop("t1_");
}

TEST(Postgis, FailureAfterAnyTableLeavesNoTable) {
  NEED_SERVER(conn);
  const mesh::MeshView m = square();
  Db db(conn);
  ASSERT_TRUE(db.ds);
  db.drop("t2_");
  for (int k = 1; k <= 5; ++k) {
    io::WriteOptions o = options("t2_");
    o.postgis.fail_after_layer = k;
    const Error e = write_error(m, conn, o);
    EXPECT_EQ(e.code(), ExitCode::kOutputError) << e.what();
    EXPECT_NE(std::string(e.what()).find("test hook"), std::string::npos) << e.what();
    EXPECT_EQ(db.tables("t2_"), 0) << "after table " << k;
  }
}

TEST(Postgis, OverwriteReplacesElseRefuses) {
  NEED_SERVER(conn);
  mesh::MeshView m = square();
  Db db(conn);
  ASSERT_TRUE(db.ds);
  db.drop("t3_");
  io::write_mesh(m, conn, io::Format::kPostgis, options("t3_"));
  // A second write without overwrite is refused, the first mesh stays.
  m.triangles.pop_back();
  const Error e = write_error(m, conn, options("t3_"));
  EXPECT_EQ(e.code(), ExitCode::kOutputError);
  EXPECT_NE(std::string(e.what()).find("--overwrite"), std::string::npos) << e.what();
  EXPECT_EQ(db.value("SELECT count(*) FROM t3_triangles"), "8");
  // A failed replacement leaves the old mesh as it was.
  io::WriteOptions o = options("t3_");
  o.postgis.overwrite = true;
  o.postgis.fail_after_layer = 2;
  EXPECT_EQ(write_error(m, conn, o).code(), ExitCode::kOutputError);
  EXPECT_EQ(db.value("SELECT count(*) FROM t3_triangles"), "8");
  EXPECT_EQ(db.tables("t3_"), 5);
  // With overwrite it is replaced.
  o.postgis.fail_after_layer = -1;
  io::write_mesh(m, conn, io::Format::kPostgis, o);
  EXPECT_EQ(db.value("SELECT count(*) FROM t3_triangles"), "7");
  EXPECT_EQ(db.tables("t3_"), 5);
  db.drop("t3_");
}

TEST(Postgis, SchemaFromOptionOrConnection) {
  NEED_SERVER(conn);
  const mesh::MeshView m = square();
  Db db(conn);
  ASSERT_TRUE(db.ds);
  io::WriteOptions o = options("t4_");
  o.postgis.overwrite = true;
  io::write_mesh(m, conn + " schemas=coast", io::Format::kPostgis, o);
  EXPECT_EQ(db.value("SELECT count(*) FROM pg_tables WHERE schemaname = 'coast' AND tablename LIKE 't4_%'"), "5");
  o.postgis.schema = "public";
  io::write_mesh(m, conn + " schemas=coast", io::Format::kPostgis, o);
  EXPECT_EQ(db.tables("t4_"), 5);
  db.drop("t4_");
  for (const char* t : {"nodes", "triangles", "boundaries", "repairs", "metadata"}) {
    OGRLayer* r = db.ds->ExecuteSQL((std::string("DROP TABLE coast.t4_") + t).c_str(), nullptr, nullptr);
    if (r) db.ds->ReleaseResultSet(r);
  }
}

TEST(Postgis, ConnectionErrorsNameTheServerWithoutPassword) {
  NEED_SERVER(conn);
  const mesh::MeshView m = square();
  const std::string host = conn.substr(0, conn.find(" user="));
  const std::string wrong_pw = host + " user=fdr_pw password=not-the-secret";
  Error e = write_error(m, wrong_pw, options("t5_"));
  EXPECT_EQ(e.code(), ExitCode::kOutputError);
  std::string msg = e.what();
  EXPECT_EQ(msg.find("not-the-secret"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("password="), std::string::npos) << msg;
  EXPECT_NE(msg.find("user=fdr_pw"), std::string::npos) << msg;
  EXPECT_NE(msg.find("password authentication failed"), std::string::npos) << msg;
  e = write_error(m, conn + " dbname=no_such_db password=xyz", options("t5_"));
  msg = e.what();
  EXPECT_EQ(e.code(), ExitCode::kOutputError);
  EXPECT_NE(msg.find("no_such_db"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("xyz"), std::string::npos) << msg;
  // A missing schema is refused before any row is sent.
  io::WriteOptions missing = options("t5_");
  missing.postgis.schema = "no_such_schema";
  e = write_error(m, conn, missing);
  EXPECT_EQ(e.code(), ExitCode::kOutputError);
  EXPECT_NE(std::string(e.what()).find("schema 'no_such_schema' does not exist"), std::string::npos) << e.what();
  // A bad table prefix is a usage error.
  io::WriteOptions o = options("1bad;prefix");
  EXPECT_EQ(write_error(m, conn, o).code(), ExitCode::kUsage);
}

TEST(PgConnection, GdalKeywordsDroppedQuotesKept) {
  pg::ConnInfo c = pg::parse_connection("PG:host=/tmp/x dbname=coast schemas=meshes,public user=me", "t");
  EXPECT_EQ(c.libpq, "host='/tmp/x' dbname='coast' user='me'");
  EXPECT_EQ(c.first_schema, "meshes");
  c = pg::parse_connection("pg:dbname = 'a b' password='it\\'s' tables=coast.water active_schema=x", "t");
  EXPECT_EQ(c.libpq, "dbname='a b' password='it\\'s'");
  EXPECT_EQ(c.first_schema, "");
  c = pg::parse_connection("PG:postgresql://me@db.example/coast?sslmode=require", "t");
  EXPECT_EQ(c.libpq, "postgresql://me@db.example/coast?sslmode=require");
  try {
    pg::parse_connection("PG:dbname='open password=secret", "PG:dbname=...");
    ADD_FAILURE() << "an open quote was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    EXPECT_EQ(std::string(e.what()).find("secret"), std::string::npos) << e.what();
  }
  EXPECT_EQ(pg::quote_ident("a\"b"), "\"a\"\"b\"");
  EXPECT_EQ(pg::quote_literal("it's"), "'it''s'");
}

TEST(PgCopy, BinaryRowsAndEwkb) {
  std::string out;
  std::size_t pieces = 0;
  pg::CopyBuffer b([&](const char* d, std::size_t n) { out.append(d, n), ++pieces; }, 32);
  b.row(3);
  b.i32(-2);
  b.f8(std::nan(""));
  b.point(4326, 1.0, -2.0);
  b.row(2);
  b.text("é");
  b.boolean(true);
  b.finish();
  const std::string header("PGCOPY\n\377\r\n\0\0\0\0\0\0\0\0\0", 19);
  ASSERT_GE(out.size(), header.size());
  EXPECT_EQ(out.substr(0, 19), header);
  std::string row1("\0\3" "\0\0\0\4" "\xff\xff\xff\xfe" "\xff\xff\xff\xff" "\0\0\0\x19", 18);
  row1 += std::string("\1" "\1\0\0\x20" "\xe6\x10\0\0", 9);                  // little-endian, Point + SRID, 4326
  row1 += std::string("\0\0\0\0\0\0\xf0\x3f" "\0\0\0\0\0\0\0\xc0", 16);      // 1.0, -2.0
  EXPECT_EQ(out.substr(19, row1.size()), row1);
  const std::string row2("\0\2" "\0\0\0\2" "\xc3\xa9" "\0\0\0\1" "\1" "\xff\xff", 15);
  EXPECT_EQ(out.substr(19 + row1.size()), row2);
  EXPECT_EQ(pieces, 2u);  // the first row filled a piece of 32 bytes
}

// Every step of the write, made to fail, leaves no table and no staging schema.
TEST(Postgis, FailureAtEachStepLeavesNothing) {
  NEED_SERVER(conn);
  const mesh::MeshView m = square();
  Db db(conn);
  ASSERT_TRUE(db.ds);
  db.drop("t6_");
  std::vector<std::string> steps = {"staging", "commit"};
  for (const char* t : {"nodes", "triangles", "boundaries", "repairs", "metadata"}) {
    steps.push_back(std::string("rows:") + t);
    steps.push_back(std::string("indexes:") + t);
  }
  for (const std::string& step : steps) {
    io::WriteOptions o = options("t6_");
    o.postgis.fail_at = step;
    const Error e = write_error(m, conn, o);
    EXPECT_EQ(e.code(), ExitCode::kOutputError) << e.what();
    EXPECT_NE(std::string(e.what()).find("test hook: failure injected at " + step), std::string::npos) << e.what();
    EXPECT_EQ(db.tables("t6_"), 0) << step;
    EXPECT_EQ(db.staging(), "0") << step;
  }
  // A replacement that fails at the last step leaves the old mesh.
  io::write_mesh(m, conn, io::Format::kPostgis, options("t6_"));
  io::WriteOptions o = options("t6_");
  o.postgis.overwrite = true;
  o.postgis.fail_at = "commit";
  mesh::MeshView fewer = m;
  fewer.triangles.pop_back();
  EXPECT_EQ(write_error(fewer, conn, o).code(), ExitCode::kOutputError);
  EXPECT_EQ(db.value("SELECT count(*) FROM t6_triangles"), "8");
  EXPECT_EQ(db.tables("t6_"), 5);
  EXPECT_EQ(db.staging(), "0");
  db.drop("t6_");
}

// A role that may create tables but not schemas gets the same tables through one transaction.
TEST(Postgis, WithoutSchemaPrivilegeOneTransaction) {
  NEED_SERVER(conn);
  const mesh::MeshView m = square();
  Db db(conn);
  ASSERT_TRUE(db.ds);
  db.drop("t7_");
  const std::string role = conn.substr(0, conn.find(" user=")) + " user=fdr_pw password=fdr-secret";
  for (const char* step : {"rows:nodes", "indexes:triangles", "rows:metadata", "commit"}) {
    io::WriteOptions o = options("t7_");
    o.postgis.fail_at = step;
    const Error e = write_error(m, role, o);
    EXPECT_NE(std::string(e.what()).find("test hook"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("fdr-secret"), std::string::npos) << e.what();
    EXPECT_EQ(db.tables("t7_"), 0) << step;
  }
  io::write_mesh(m, role, io::Format::kPostgis, options("t7_"));
  EXPECT_EQ(db.tables("t7_"), 5);
  EXPECT_EQ(db.value("SELECT count(*) FROM t7_triangles WHERE ST_IsValid(geom)"), "8");
  EXPECT_EQ(db.value("SELECT count(*) FROM pg_indexes WHERE tablename LIKE 't7\\_%' AND indexdef LIKE '%gist%'"), "4");
  EXPECT_EQ(db.value("SELECT count(*) FROM pg_constraint WHERE contype = 'p' AND conrelid::regclass::text LIKE 't7\\_%'"), "5");
  EXPECT_EQ(db.staging(), "0");
  db.drop("t7_");
}

// Reals read back bit for bit; the fid sequence continues after the rows; a CRS missing from
// spatial_ref_sys is added with the tables (and not when the write fails).
TEST(Postgis, ExactRealsSequenceAndNewCrs) {
  NEED_SERVER(conn);
  mesh::MeshView m = square();
  m.z[2] = 0.1 + 0.2;
  OGRSpatialReference srs;
  srs.SetProjCS("fdr test local");
  srs.SetWellKnownGeogCS("WGS84");
  srs.SetTM(37.123456, -76.654321, 0.9996, 500000, 0);
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  m.crs_wkt = wkt;
  CPLFree(wkt);
  Db db(conn);
  ASSERT_TRUE(db.ds);
  db.drop("t8_");
  const std::string before = db.value("SELECT count(*) FROM spatial_ref_sys");
  io::WriteOptions o = options("t8_");
  o.postgis.fail_at = "commit";
  EXPECT_EQ(write_error(m, conn, o).code(), ExitCode::kOutputError);
  EXPECT_EQ(db.value("SELECT count(*) FROM spatial_ref_sys"), before);
  io::write_mesh(m, conn, io::Format::kPostgis, options("t8_"));
  EXPECT_EQ(db.value("SELECT (z = 0.1::float8 + 0.2::float8 AND z <> 0.3::float8)::text FROM t8_nodes WHERE id = 3"),
            "true");
  EXPECT_EQ(db.value("SELECT count(*) FROM spatial_ref_sys"), std::to_string(std::stoi(before) + 1));
  const std::string srid = db.value("SELECT Find_SRID('public', 't8_nodes', 'geom')");
  EXPECT_NE(db.value("SELECT srtext FROM spatial_ref_sys WHERE srid = " + srid).find("fdr test local"), std::string::npos);
  EXPECT_EQ(db.value("SELECT nextval(pg_get_serial_sequence('public.t8_triangles', 'fid'))"), "9");
  db.drop("t8_");
  OGRLayer* r = db.ds->ExecuteSQL(("DELETE FROM spatial_ref_sys WHERE srid = " + srid).c_str(), nullptr, nullptr);
  if (r) db.ds->ReleaseResultSet(r);
}
