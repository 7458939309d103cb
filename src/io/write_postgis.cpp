// PostGIS writer: the same tables and columns as the GeoPackage writer, loaded with binary COPY
// (EWKB geometries built here) over libpq. The tables are filled and indexed in a private staging
// schema, two at a time over separate connections, then moved into place in one short
// transaction; a failure anywhere drops the staging schema and leaves the database as it was.
#include "io/write_postgis.hpp"

#include <ogr_spatialref.h>

#include <cctype>
#include <cstdio>
#include <future>
#include <memory>
#include <random>
#include <vector>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/redact.hpp"
#include "gis/pg_source.hpp"
#include "io/detail.hpp"
#include "io/gdal_util.hpp"
#include "io/pg_conn.hpp"
#include "io/pg_mesh_rows.hpp"

namespace fdr::io::detail {

namespace {

using pg::quote_ident;
using pg::quote_literal;

// What every step of one write needs.
struct Job {
  const mesh::MeshView& m;
  const WriteOptions& o;
  const PostgisOptions& p;
  std::string label;    // the connection string without its password
  pg::ConnInfo conn;
  std::string schema;   // where the tables end up
  std::int32_t srid = 0;
  std::string srs_insert;  // adds the mesh CRS to spatial_ref_sys when it is not there, or ""
  std::vector<PgTable> tables;

  [[noreturn]] void fail(const std::string& why) const { throw Error(ExitCode::kOutputError, label + ": " + why); }
  // Test hook: fails at the named step (PostgisOptions::fail_at) as a broken connection would.
  void step(const std::string& name) const {
    const bool after_rows = p.fail_after_layer >= 1 && p.fail_after_layer <= 5 &&
                            name == std::string("rows:") + tables[static_cast<std::size_t>(p.fail_after_layer - 1)].name;
    if (name == p.fail_at || after_rows) fail("test hook: failure injected at " + name);
  }
  std::string table(const std::string& in_schema, std::size_t i) const {
    return quote_ident(in_schema) + "." + quote_ident(p.prefix + tables[i].name);
  }
};

void check_prefix(const std::string& prefix, const std::string& label) {
  bool ok = !prefix.empty() && prefix.size() <= 40 && !std::isdigit(static_cast<unsigned char>(prefix[0]));
  for (char c : prefix) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  if (!ok)
    throw Error(ExitCode::kUsage, label + ": table prefix '" + prefix +
                                      "' must be 1-40 letters, digits or '_' and not start with a digit");
}

// The schema the tables go to: the option, the connection's `schemas=`, else current_schema().
std::string resolve_schema(pg::Connection& c, const Job& j) {
  if (!j.p.schema.empty()) return j.p.schema;
  if (!j.conn.first_schema.empty()) return j.conn.first_schema;
  const std::vector<std::string> s = c.column("SELECT current_schema()", "cannot tell the current schema");
  if (s.empty() || s[0].empty()) j.fail("cannot tell the current schema (give --pg-schema)");
  return s[0];
}

// Refuses a schema that is missing or closed to this role before any row is sent.
void check_schema(pg::Connection& c, const Job& j) {
  const std::vector<std::string> r = c.column(
      "SELECT has_schema_privilege(oid, 'CREATE') FROM pg_catalog.pg_namespace WHERE nspname = " +
          quote_literal(j.schema), "cannot look schema '" + j.schema + "' up");
  if (r.empty()) j.fail("schema '" + j.schema + "' does not exist (create it, or give another with --pg-schema)");
  if (r[0] != "t") j.fail("no right to create tables in schema '" + j.schema + "'");
}

// The SRID of the mesh CRS in spatial_ref_sys: by EPSG code, else by its WKT, else a new row
// (inserted with the tables, so a failed write adds none).
void resolve_srid(pg::Connection& c, Job& j) {
  if (j.m.crs_wkt.empty()) return;
  OGRSpatialReference srs;
  if (srs.SetFromUserInput(j.m.crs_wkt.c_str()) != OGRERR_NONE) j.fail("the mesh CRS cannot be parsed");
  if (!srs.GetAuthorityName(nullptr)) srs.AutoIdentifyEPSG();
  const char* auth = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  const bool epsg = auth && code && std::string(auth) == "EPSG";
  const std::string what = "cannot look the mesh CRS up in spatial_ref_sys";
  if (epsg) {
    const auto r = c.column("SELECT srid FROM spatial_ref_sys WHERE upper(auth_name) = 'EPSG' AND auth_srid = " +
                                std::string(code) + " ORDER BY srid LIMIT 1", what);
    if (!r.empty()) {
      j.srid = std::stoi(r[0]);
      return;
    }
  }
  char* wkt = nullptr;
  char* proj4 = nullptr;
  srs.exportToWkt(&wkt);
  srs.exportToProj4(&proj4);
  const std::string srtext = wkt ? wkt : "", proj4text = proj4 ? proj4 : "";
  CPLFree(wkt);
  CPLFree(proj4);
  const auto r = c.column("SELECT srid FROM spatial_ref_sys WHERE srtext = " + quote_literal(srtext) +
                              " ORDER BY srid LIMIT 1", what);
  if (!r.empty()) {
    j.srid = std::stoi(r[0]);
    return;
  }
  const std::string free_code =
      epsg ? "(SELECT " + std::string(code) + " WHERE NOT EXISTS (SELECT 1 FROM spatial_ref_sys WHERE srid = " + code + "))"
           : "NULL";
  const auto n = c.column("SELECT COALESCE(" + free_code + ", (SELECT COALESCE(max(srid), 0) + 1 FROM spatial_ref_sys "
                              "WHERE srid < 900913))", what);
  j.srid = std::stoi(n.at(0));
  j.srs_insert = "INSERT INTO spatial_ref_sys (srid, auth_name, auth_srid, srtext, proj4text) VALUES (" +
                 std::to_string(j.srid) + ", " + (epsg ? "'EPSG', " + std::string(code) : "NULL, NULL") + ", " +
                 quote_literal(srtext) + ", " + quote_literal(proj4text) + ")";
}

// Tables of this mesh that already exist in the target schema, "schema.name" each.
std::vector<std::string> existing_tables(pg::Connection& c, const Job& j) {
  std::string names;
  for (const PgTable& t : j.tables) {
    if (!names.empty()) names += ',';
    names += quote_literal(j.p.prefix + t.name);
  }
  return c.column("SELECT s.nspname || '.' || c.relname FROM pg_catalog.pg_class c JOIN pg_catalog.pg_namespace s "
                  "ON s.oid = c.relnamespace WHERE s.nspname = " + quote_literal(j.schema) +
                  " AND c.relname IN (" + names + ") ORDER BY c.relname",
                  "cannot list the tables of schema '" + j.schema + "'");
}

// Refuses an existing mesh of the same prefix unless it may be replaced; `drop` drops it.
void clear_target(pg::Connection& c, const Job& j, bool drop) {
  const std::vector<std::string> old = existing_tables(c, j);
  if (old.empty()) return;
  std::string list;
  for (const auto& n : old) {
    if (!list.empty()) list += ", ";
    list += n;
  }
  if (!j.p.overwrite)
    j.fail("a mesh with table prefix '" + j.p.prefix + "' exists (" + list +
           "); give --overwrite to replace it or --pg-prefix for another name");
  if (!drop) return;
  std::string sql;
  for (const auto& n : old) {
    const std::size_t dot = n.find('.');
    sql += "DROP TABLE " + quote_ident(n.substr(0, dot)) + "." + quote_ident(n.substr(dot + 1)) + " CASCADE;";
  }
  c.exec(sql, "cannot drop the old tables (" + list + ")");
}

// Creates table i in `schema` and streams its rows with binary COPY; returns how many. The
// caller's transaction created the table, so COPY may FREEZE the rows (no later vacuum has to
// rewrite them).
std::int64_t copy_rows(pg::Connection& c, const Job& j, const std::string& schema, std::size_t i) {
  const PgTable& t = j.tables[i];
  const std::string q = j.table(schema, i);
  const std::string shown = j.schema + "." + j.p.prefix + t.name;
  c.exec("CREATE TABLE " + q + " (fid bigserial, " + t.columns + ")", "cannot create table " + shown);
  c.copy_begin("COPY " + q + " (" + t.copy_columns + ") FROM STDIN (FORMAT binary, FREEZE)",
               "writing the rows of " + shown + " failed");
  pg::CopyBuffer b([&c](const char* d, std::size_t n) { c.copy_put(d, n); });
  const std::int64_t rows = pg_rows(i, b, j.m, j.o, j.srid);
  b.finish();
  c.copy_end();
  j.step(std::string("rows:") + t.name);
  return rows;
}

// The index that becomes table i's primary key (unique on fid, named as the key).
std::string fid_index(const Job& j, const std::string& schema, std::size_t i) {
  const std::string name = j.p.prefix + j.tables[i].name;
  return "CREATE UNIQUE INDEX " + quote_ident(name + "_pkey") + " ON " + j.table(schema, i) + " (fid);";
}

// Over the loaded rows of table i: its fid index (unless built elsewhere), spatial index and fid
// sequence past the rows. Built once the rows are in: kept up row by row they cost a B-tree and a
// GiST insert per row. No ANALYZE: autovacuum analyses the new tables anyway once they are in
// place (their rows count as changes), so running it here would double the work on the write's
// own critical path; the index builds already set the tables' row counts for the planner.
void build_indexes(pg::Connection& c, const Job& j, const std::string& schema, std::size_t i, std::int64_t rows,
                   bool with_fid_index) {
  const PgTable& t = j.tables[i];
  const std::string name = j.p.prefix + t.name;
  const std::string q = j.table(schema, i);
  const std::string what = "cannot build the indexes of " + j.schema + "." + name;
  if (with_fid_index) c.exec(fid_index(j, schema, i), what);
  if (t.spatial) c.exec("CREATE INDEX " + quote_ident(name + "_geom_idx") + " ON " + q + " USING GIST (geom)", what);
  c.exec("SELECT setval(pg_get_serial_sequence(" + quote_literal(q) + ", 'fid'), " + std::to_string(rows + 1) +
             ", false)", what);
  j.step(std::string("indexes:") + t.name);
}

// "ALTER TABLE ... ADD PRIMARY KEY USING INDEX" for every table (fid is NOT NULL: no scan).
std::string primary_keys(const Job& j, const std::string& schema) {
  std::string sql;
  for (std::size_t i = 0; i < j.tables.size(); ++i) {
    const std::string key = quote_ident(j.p.prefix + j.tables[i].name + "_pkey");
    sql += "ALTER TABLE " + j.table(schema, i) + " ADD CONSTRAINT " + key + " PRIMARY KEY USING INDEX " + key + ";";
  }
  return sql;
}

// The index builds sort in memory up to this (the server's default of a few tens of MB is less
// than a million triangles' bounding boxes take, and a sort that spills to disk is slower). No
// parallel workers: the writer already keeps two sessions busy, and each worker of a parallel
// B-tree build writes its sorted share to a temporary file for the leader to merge (set through
// pg_settings: a server older than PostgreSQL 11 has neither the setting nor parallel builds).
constexpr const char* kIndexMemory =
    "SET maintenance_work_mem = '256MB'; SELECT set_config(name, '0', false) FROM pg_settings "
    "WHERE name = 'max_parallel_maintenance_workers'";

// A connection for one side of the staged load, each table in a transaction of its own. Those
// commits need not reach the disk before the swap's own commit, which flushes the log up to
// itself.
std::unique_ptr<pg::Connection> staging_session(const Job& j) {
  auto c = std::make_unique<pg::Connection>(j.conn.libpq, j.label);
  c->exec(std::string(kIndexMemory) + "; SET synchronous_commit = off", "cannot configure the session");
  return c;
}

template <class Fn>
void in_transaction(pg::Connection& c, Fn&& fn) {
  c.exec("BEGIN", "cannot start a transaction");
  fn();
  c.exec("COMMIT", "commit failed");
}

constexpr std::size_t kTriangles = 1;  // the index in pg_tables

// Loads every table into the staging schema on two connections (one when the sizing field may
// not be called from two threads). The triangles, the largest table, take one: rows, then
// spatial index. The other takes the rest, then the triangles' fid index, built beside their
// spatial index (two index builds do not lock each other out).
void load_staged(const Job& j, const std::string& staging) {
  std::promise<void> rows_in;
  std::shared_future<void> triangles_in = rows_in.get_future().share();
  // Opens its connection when given none; whatever fails before the rows are in also stops the
  // other side's wait.
  auto triangles = [&](std::unique_ptr<pg::Connection>& c) {
    std::int64_t rows = 0;
    try {
      if (!c) c = staging_session(j);
      in_transaction(*c, [&] { rows = copy_rows(*c, j, staging, kTriangles); });
    } catch (...) {
      rows_in.set_exception(std::current_exception());
      throw;
    }
    rows_in.set_value();
    in_transaction(*c, [&] { build_indexes(*c, j, staging, kTriangles, rows, false); });
  };
  auto rest = [&](pg::Connection& c) {
    for (std::size_t i = 0; i < j.tables.size(); ++i) {
      if (i == kTriangles) continue;
      in_transaction(c, [&] { build_indexes(c, j, staging, i, copy_rows(c, j, staging, i), false); });
    }
    triangles_in.get();
    in_transaction(c, [&] {
      for (std::size_t i = 0; i < j.tables.size(); ++i) c.exec(fid_index(j, staging, i), "cannot build the fid indexes");
    });
  };
  if ((j.o.f && !j.o.f->thread_safe()) || max_threads() < 2) {
    auto c = staging_session(j);
    triangles(c);
    rest(*c);
    return;
  }
  run_beside(
      [&] {
        std::unique_ptr<pg::Connection> c;
        triangles(c);
      },
      [&] { rest(*staging_session(j)); });
}

// The one transaction that puts the staged tables in place: the old mesh dropped (with
// --overwrite), the CRS row added when missing, the tables moved, the staging schema dropped.
void swap_in(pg::Connection& c, const Job& j, const std::string& staging) {
  c.exec("BEGIN", "cannot start a transaction");
  clear_target(c, j, true);
  if (!j.srs_insert.empty()) c.exec(j.srs_insert, "cannot add the mesh CRS to spatial_ref_sys");
  std::string sql;
  for (std::size_t i = 0; i < j.tables.size(); ++i)
    sql += "ALTER TABLE " + j.table(staging, i) + " SET SCHEMA " + quote_ident(j.schema) + ";";
  c.exec(sql + primary_keys(j, j.schema), "cannot move the tables into schema " + j.schema);
  c.exec("DROP SCHEMA " + quote_ident(staging), "cannot drop the staging schema " + staging);
  j.step("commit");
  c.exec("COMMIT", "commit failed (nothing written)");
}

// Without the right to create a schema: every table loaded on this connection in one transaction.
void write_in_one_transaction(pg::Connection& c, const Job& j) {
  c.exec(std::string("BEGIN; ") + kIndexMemory, "cannot start a transaction");
  clear_target(c, j, true);
  if (!j.srs_insert.empty()) c.exec(j.srs_insert, "cannot add the mesh CRS to spatial_ref_sys");
  for (std::size_t i = 0; i < j.tables.size(); ++i) build_indexes(c, j, j.schema, i, copy_rows(c, j, j.schema, i), true);
  c.exec(primary_keys(j, j.schema), "cannot add the primary keys");
  j.step("commit");
  c.exec("COMMIT", "commit failed (nothing written)");
}

// A schema name no other write picks.
std::string staging_name() {
  std::random_device rd;
  const unsigned long long r = (static_cast<unsigned long long>(rd()) << 32) ^ rd();
  char buf[40];
  std::snprintf(buf, sizeof buf, "fdr_staging_%016llx", r);
  return buf;
}

// Drops what a failed staged write left; says in the error when even that fails.
Error without_staging(pg::Connection& c, const Job& j, const std::string& staging, const Error& e) {
  std::string state;
  const std::string drop = "DROP SCHEMA IF EXISTS " + quote_ident(staging) + " CASCADE";
  bool dropped = false;
  if (c.alive()) dropped = c.try_exec("ROLLBACK", state) && c.try_exec(drop, state);
  if (!dropped) {
    try {
      pg::Connection again(j.conn.libpq, j.label);
      dropped = again.try_exec(drop, state);
    } catch (const Error&) {
    }
  }
  if (dropped) return e;
  return Error(e.code(), std::string(e.what()) + " (the staging schema " + staging +
                             " is left behind; drop it with DROP SCHEMA " + staging + " CASCADE)");
}

void write_tables(const mesh::MeshView& m, const std::string& conn, const WriteOptions& o) {
  Job j{m, o, o.postgis, gis::source_label(conn), {}, {}, 0, {}, pg_tables(0)};
  check_prefix(j.p.prefix, j.label);
  validate_for_output(m, j.label);
  j.conn = pg::parse_connection(conn, j.label);
  gdal_register_once();  // the CRS lookup uses GDAL's OGRSpatialReference (PROJ)
  pg::Connection c(j.conn.libpq, j.label);
  j.schema = resolve_schema(c, j);
  check_schema(c, j);
  clear_target(c, j, false);  // refuses an existing mesh before any work
  resolve_srid(c, j);
  j.tables = pg_tables(j.srid);
  const std::string staging = staging_name();
  std::string state;
  if (!c.try_exec("CREATE SCHEMA " + quote_ident(staging), state)) {
    if (state != pg::kInsufficientPrivilege) c.fail("cannot create the staging schema " + staging);
    write_in_one_transaction(c, j);
    return;
  }
  try {
    j.step("staging");
    load_staged(j, staging);
    swap_in(c, j, staging);
  } catch (const Error& e) {
    throw without_staging(c, j, staging, e);
  } catch (const std::exception& e) {
    throw without_staging(c, j, staging, Error(ExitCode::kOutputError, j.label + ": " + redact_passwords(e.what())));
  }
}

}  // namespace

void write_postgis(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  const std::string conn = gis::is_pg_connection(path) ? path : "PG:" + path;
  // Anything but an fdr::Error (out of memory, a sizing field that throws) is an output error
  // too, naming the connection without its password.
  try {
    write_tables(m, conn, o);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(ExitCode::kOutputError, gis::source_label(conn) + ": " + redact_passwords(e.what()));
  }
}

}  // namespace fdr::io::detail
