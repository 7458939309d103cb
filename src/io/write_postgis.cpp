// PostGIS writer: the same tables and columns as the GeoPackage writer, written through GDAL's
// PostgreSQL driver (rows streamed with COPY), GiST indexes built after the rows, everything in
// one transaction so a failure anywhere leaves the database as it was.
#include "io/write_postgis.hpp"

#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "base/error.hpp"
#include "base/redact.hpp"
#include "gis/pg_source.hpp"
#include "io/detail.hpp"
#include "io/gdal_util.hpp"

namespace fdr::io::detail {

namespace {

// The five tables in the order they are written (and counted by fail_after_layer).
constexpr const char* kTables[] = {"nodes", "triangles", "boundaries", "repairs", "metadata"};

std::string quote_ident(const std::string& s) {
  std::string r = "\"";
  for (char c : s) {
    if (c == '"') r += '"';
    r += c;
  }
  return r + "\"";
}

std::string quote_literal(const std::string& s) {
  std::string r = "'";
  for (char c : s) {
    if (c == '\'') r += '\'';
    r += c;
  }
  return r + "'";
}

// The first schema of the connection string's `schemas=a,b` (GDAL's PG driver option), or "".
std::string schema_of_connection(const std::string& conn) {
  std::size_t at = 0;
  while ((at = conn.find("schemas=", at)) != std::string::npos) {
    if (at == 0 || conn[at - 1] == ' ' || conn[at - 1] == ':') {
      std::size_t end = at + 8;
      while (end < conn.size() && conn[end] != ',' && conn[end] != ' ') ++end;
      return conn.substr(at + 8, end - at - 8);
    }
    at += 8;
  }
  return "";
}

// The target and what goes wrong with it: every message names the connection without password.
class Target {
 public:
  explicit Target(const std::string& conn) : conn_(conn), label_(gis::source_label(conn)) {}
  const std::string& conn() const { return conn_; }
  const std::string& label() const { return label_; }
  [[noreturn]] void fail(const std::string& reason, const GdalErrors* errs = nullptr) const {
    std::string why = reason;
    if (errs && errs->any()) why += ": " + gis::pg_reason(errs->last());
    throw Error(ExitCode::kOutputError, label_ + ": " + why);
  }

 private:
  std::string conn_, label_;
};

// A transaction rolled back unless committed (the database is then as it was).
class Transaction {
 public:
  Transaction(GDALDataset& ds, const Target& t, GdalErrors& errs) : ds_(ds) {
    if (ds_.StartTransaction(FALSE) != OGRERR_NONE) t.fail("cannot start a transaction", &errs);
  }
  ~Transaction() {
    if (!done_) ds_.RollbackTransaction();
  }
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit(const Target& t, GdalErrors& errs) {
    done_ = true;
    if (ds_.CommitTransaction() != OGRERR_NONE) t.fail("commit failed (nothing written)", &errs);
  }

 private:
  GDALDataset& ds_;
  bool done_ = false;
};

// Runs a statement; a failure is an output error naming `what`.
void exec(GDALDataset& ds, const std::string& sql, const Target& t, GdalErrors& errs, const std::string& what) {
  errs.clear();
  OGRLayer* r = ds.ExecuteSQL(sql.c_str(), nullptr, nullptr);
  if (r) ds.ReleaseResultSet(r);
  if (errs.any()) t.fail(what, &errs);
}

// The schema the tables go to: the option, the connection's `schemas=`, else current_schema().
std::string resolve_schema(GDALDataset& ds, const PostgisOptions& p, const Target& t, GdalErrors& errs) {
  if (!p.schema.empty()) return p.schema;
  std::string s = schema_of_connection(t.conn());
  if (!s.empty()) return s;
  errs.clear();
  OGRLayer* r = ds.ExecuteSQL("SELECT current_schema() AS s", nullptr, nullptr);
  if (r) {
    std::unique_ptr<OGRFeature> f(r->GetNextFeature());
    if (f && f->IsFieldSetAndNotNull(0)) s = f->GetFieldAsString(0);
    ds.ReleaseResultSet(r);
  }
  if (s.empty()) t.fail("cannot tell the current schema (give --pg-schema)", &errs);
  return s;
}

// Tables of this mesh that already exist in `schema`.
std::vector<std::string> existing_tables(GDALDataset& ds, const std::string& schema, const std::string& prefix,
                                         const Target& t, GdalErrors& errs) {
  std::string names;
  for (const char* n : kTables) {
    if (!names.empty()) names += ',';
    names += quote_literal(prefix + n);
  }
  const std::string sql = "SELECT c.relname FROM pg_catalog.pg_class c JOIN pg_catalog.pg_namespace s ON "
                          "s.oid = c.relnamespace WHERE s.nspname = " + quote_literal(schema) +
                          " AND c.relname IN (" + names + ") ORDER BY c.relname";
  errs.clear();
  OGRLayer* r = ds.ExecuteSQL(sql.c_str(), nullptr, nullptr);
  if (!r) t.fail("cannot list the tables of schema '" + schema + "'", &errs);
  std::vector<std::string> out;
  for (auto& f : *r) out.push_back(f->GetFieldAsString(0));
  ds.ReleaseResultSet(r);
  return out;
}

// A column; real numbers travel as text written here (double precision in the table, see
// set_real) because the driver's own formatting (printf %.18g) is what the rows cost most.
struct Column {
  const char* name;
  OGRFieldType type;
  OGRFieldSubType sub = OFSTNone;
  bool real = false;  // double precision, filled by set_real
};
Column real_column(const char* name) { return {name, OFTString, OFSTNone, true}; }

OGRLayer* create_table(GDALDataset& ds, const std::string& schema, const std::string& name,
                       const OGRSpatialReference* srs, OGRwkbGeometryType geom, const std::vector<Column>& cols,
                       const Target& t, GdalErrors& errs) {
  const std::string schema_opt = "SCHEMA=" + schema;
  std::string types = "COLUMN_TYPES=";
  for (const Column& c : cols)
    if (c.real) types += std::string(types.back() == '=' ? "" : ",") + c.name + "=float8";
  // GiST indexes are built once the rows are in (faster than growing them row by row);
  // LAUNDER=NO keeps the GeoPackage's column names (R_over_f).
  const char* opts[] = {"GEOMETRY_NAME=geom", "FID=fid", "FID64=TRUE", "SPATIAL_INDEX=NONE", "LAUNDER=NO",
                        "PRECISION=NO", "DIM=2", schema_opt.c_str(), types.c_str(), nullptr};
  errs.clear();
  OGRLayer* l = ds.CreateLayer(name.c_str(), const_cast<OGRSpatialReference*>(srs), geom, const_cast<char**>(opts));
  if (!l) t.fail("cannot create table " + schema + "." + name, &errs);
  for (const Column& c : cols) {
    OGRFieldDefn d(c.name, c.type);
    d.SetSubType(c.sub);
    if (l->CreateField(&d) != OGRERR_NONE) t.fail("cannot add column " + std::string(c.name) + " to " + name, &errs);
  }
  // The primary key is built once the rows are in (finish_table): kept up row by row it costs a
  // B-tree insert per row. Running a statement also makes the driver create the table now.
  exec(ds, "ALTER TABLE " + quote_ident(schema) + "." + quote_ident(name) + " DROP CONSTRAINT IF EXISTS " +
               quote_ident(name + "_pkey"), t, errs, "cannot create table " + schema + "." + name);
  return l;
}

// Primary key, spatial index, the fid sequence past the rows, planner statistics (QGIS asks
// for extents).
void finish_table(GDALDataset& ds, const std::string& schema, const std::string& name, bool spatial, const Target& t,
                  GdalErrors& errs) {
  const std::string table = quote_ident(schema) + "." + quote_ident(name);
  const std::string what = schema + "." + name;
  // (Unless the driver named its key otherwise and it is still there.)
  exec(ds, "DO $$ BEGIN IF NOT EXISTS (SELECT 1 FROM pg_constraint WHERE contype = 'p' AND conrelid = " +
               quote_literal(table) + "::regclass) THEN ALTER TABLE " + table + " ADD CONSTRAINT " +
               quote_ident(name + "_pkey") + " PRIMARY KEY (fid); END IF; END $$",
       t, errs, "cannot build the primary key of " + what);
  if (spatial)
    exec(ds, "CREATE INDEX " + quote_ident(name + "_geom_idx") + " ON " + table + " USING GIST (geom)", t, errs,
         "cannot build the spatial index of " + what);
  exec(ds, "SELECT setval(pg_get_serial_sequence(" + quote_literal(table) + ", 'fid'), (SELECT COALESCE(max(fid), 0) + 1 FROM " +
               table + "), false)", t, errs, "cannot set the fid sequence of " + what);
  exec(ds, "ANALYZE " + table, t, errs, "cannot analyze " + what);
}

// Streams one feature per row (the PG driver sends them with COPY).
class Rows {
 public:
  Rows(OGRLayer& l, const Target& t, GdalErrors& errs, const std::string& table)
      : l_(l), t_(t), errs_(errs), table_(table), f_(new OGRFeature(l.GetLayerDefn())) {}
  OGRFeature& feature() { return *f_; }
  // Rows are numbered 1, 2, ... as the GeoPackage's (the fid sequence is set past them after).
  void put() {
    f_->SetFID(++fid_);
    if (l_.CreateFeature(f_.get()) != OGRERR_NONE) t_.fail("writing the rows of " + table_ + " failed", &errs_);
  }
  // Flushes the COPY stream, so a failure shows here and not in the next table.
  void finish() {
    errs_.clear();
    if (l_.SyncToDisk() != OGRERR_NONE || errs_.any()) t_.fail("writing the rows of " + table_ + " failed", &errs_);
  }

 private:
  OGRLayer& l_;
  const Target& t_;
  GdalErrors& errs_;
  std::string table_;
  std::unique_ptr<OGRFeature> f_;
  GIntBig fid_ = 0;
};

// The shortest text that reads back as the same double (std::to_chars), NULL when not finite.
void set_real(OGRFeature& f, int i, double v) {
  if (!std::isfinite(v)) {
    f.SetFieldNull(i);
    return;
  }
  char buf[32];
  *std::to_chars(buf, buf + sizeof buf - 1, v).ptr = '\0';
  f.SetField(i, buf);
}

// geom, id, z, f, conformity, marker: as the GeoPackage's nodes.
void write_nodes(OGRLayer& l, const mesh::MeshView& m, const WriteOptions& o, const Target& t, GdalErrors& errs) {
  const std::vector<double> nn = nearest_neighbour_distance(m);
  Rows rows(l, t, errs, "nodes");
  OGRFeature& f = rows.feature();
  f.SetGeometryDirectly(new OGRPoint(0, 0));
  auto* p = f.GetGeometryRef()->toPoint();
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const Point2 w = m.world(static_cast<Index>(v));
    p->setX(w.x);
    p->setY(w.y);
    double fv = std::nan("");
    if (!m.f.empty()) fv = m.f[v];
    else if (o.f) fv = (*o.f)(m.vertices[v]);
    double c = std::nan("");
    if (fv > 0 && std::isfinite(nn[v]) && nn[v] > 0) c = std::min(nn[v] / fv, fv / nn[v]);
    f.SetField(0, static_cast<GIntBig>(v + 1));
    set_real(f, 1, m.z.empty() ? std::nan("") : m.z[v]);
    set_real(f, 2, fv);
    set_real(f, 3, c);
    f.SetField(4, m.vertex_marker.empty() ? 0 : m.vertex_marker[v]);
    rows.put();
  }
  rows.finish();
}

// geom, id, n1, n2, n3, area, min_angle, R_over_f, quality: as the GeoPackage's triangles.
void write_triangles(OGRLayer& l, const mesh::MeshView& m, const WriteOptions& o, const Target& t, GdalErrors& errs) {
  Rows rows(l, t, errs, "triangles");
  OGRFeature& f = rows.feature();
  auto* poly = new OGRPolygon;
  auto* ring = new OGRLinearRing;
  ring->setNumPoints(4);
  poly->addRingDirectly(ring);
  f.SetGeometryDirectly(poly);
  for (std::size_t tr = 0; tr < m.triangles.size(); ++tr) {
    const auto& v = m.triangles[tr];
    for (int k = 0; k <= 3; ++k) {
      const Point2 w = m.world(v[k % 3]);
      ring->setPoint(k, w.x, w.y);
    }
    f.SetField(0, static_cast<GIntBig>(tr + 1));
    for (int k = 0; k < 3; ++k) f.SetField(1 + k, static_cast<GIntBig>(v[k]) + 1);
    set_real(f, 4, o.triangle_area ? (*o.triangle_area)[tr] : triangle_area(m, tr));
    set_real(f, 5, o.triangle_min_angle ? (*o.triangle_min_angle)[tr] : triangle_min_angle_deg(m, tr));
    if (o.f || o.triangle_r_over_f) {
      double r;
      if (o.triangle_r_over_f) {
        r = (*o.triangle_r_over_f)[tr];
      } else {
        Point2 c;
        r = circumradius(m, tr, c) / (*o.f)(c);
      }
      set_real(f, 6, r);
      set_real(f, 7, o.bound_B > 0 ? r / o.bound_B : std::nan(""));
    } else {
      f.SetFieldNull(6);
      f.SetFieldNull(7);
    }
    rows.put();
  }
  rows.finish();
}

// geom, id, kind, marker, part, closed, num_nodes: the boundary chains, as in the GeoPackage.
void write_boundaries(OGRLayer& l, const mesh::MeshView& m, const Target& t, GdalErrors& errs) {
  const std::vector<Chain> chains = build_chains(m);
  Rows rows(l, t, errs, "boundaries");
  OGRFeature& f = rows.feature();
  for (std::size_t i = 0; i < chains.size(); ++i) {
    const Chain& c = chains[i];
    auto* line = new OGRLineString;
    line->setNumPoints(static_cast<int>(c.nodes.size() + (c.closed ? 1 : 0)));
    for (std::size_t k = 0; k < c.nodes.size(); ++k) {
      const Point2 w = m.world(c.nodes[k]);
      line->setPoint(static_cast<int>(k), w.x, w.y);
    }
    if (c.closed) {
      const Point2 w = m.world(c.nodes[0]);
      line->setPoint(static_cast<int>(c.nodes.size()), w.x, w.y);
    }
    f.SetGeometryDirectly(line);
    f.SetField(0, static_cast<int>(i + 1));
    f.SetField(1, kind_name(c.marker).c_str());
    f.SetField(2, c.marker);
    f.SetField(3, c.part);
    f.SetField(4, c.closed ? 1 : 0);
    f.SetField(5, static_cast<int>(c.nodes.size()));
    rows.put();
  }
  rows.finish();
}

// geom, kind, size, reason, part: the fixes made to the input (no geometry where unknown).
void write_repairs(OGRLayer& l, const WriteOptions& o, const Target& t, GdalErrors& errs) {
  Rows rows(l, t, errs, "repairs");
  OGRFeature& f = rows.feature();
  for (const RepairRow& r : o.repairs) {
    if (std::isfinite(r.x) && std::isfinite(r.y)) f.SetGeometryDirectly(new OGRPoint(r.x, r.y));
    else f.SetGeometryDirectly(nullptr);
    f.SetField(0, r.kind.c_str());
    set_real(f, 1, r.size);
    f.SetField(2, r.reason.c_str());
    f.SetField(3, r.part);
    rows.put();
  }
  rows.finish();
}

// key, value: the run's metadata as in the GeoPackage (passwords removed from every value).
void write_metadata(OGRLayer& l, const WriteOptions& o, const Target& t, GdalErrors& errs) {
  Rows rows(l, t, errs, "metadata");
  OGRFeature& f = rows.feature();
  for (const auto& [k, v] : metadata_rows(o)) {
    f.SetField(0, k.c_str());
    f.SetField(1, redact_passwords(v).c_str());
    rows.put();
  }
  rows.finish();
}

void check_prefix(const std::string& prefix, const Target& t) {
  bool ok = !prefix.empty() && prefix.size() <= 40 && !std::isdigit(static_cast<unsigned char>(prefix[0]));
  for (char c : prefix) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  if (!ok)
    throw Error(ExitCode::kUsage, t.label() + ": table prefix '" + prefix +
                                      "' must be 1-40 letters, digits or '_' and not start with a digit");
}

// Opens the database for writing through the PostgreSQL driver only.
DatasetPtr open_for_writing(const Target& t, GdalErrors& errs) {
  gdal_register_once();
  const char* const drivers[] = {"PostgreSQL", nullptr};
  DatasetPtr ds(GDALDataset::Open(t.conn().c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE, drivers));
  if (!ds) t.fail("cannot connect", &errs);
  return ds;
}

// Makes room for the mesh: refuses an existing one, or drops it when it may be replaced.
void clear_target(GDALDataset& ds, const std::string& schema, const PostgisOptions& p, const Target& t,
                  GdalErrors& errs) {
  const std::vector<std::string> old = existing_tables(ds, schema, p.prefix, t, errs);
  if (old.empty()) return;
  std::string list;
  for (const auto& n : old) list += (list.empty() ? "" : ", ") + schema + "." + n;
  if (!p.overwrite)
    t.fail("a mesh with table prefix '" + p.prefix + "' exists (" + list +
           "); give --overwrite to replace it or --pg-prefix for another name");
  for (const auto& n : old) exec(ds, "DROP TABLE " + quote_ident(schema) + "." + quote_ident(n) + " CASCADE", t, errs,
                                 "cannot drop the old table " + schema + "." + n);
}

// PG_USE_COPY=YES on this thread while alive (the previous value restored after).
class UseCopy {
 public:
  UseCopy() {
    const char* v = CPLGetThreadLocalConfigOption("PG_USE_COPY", nullptr);
    had_ = v != nullptr;
    if (had_) old_ = v;
    CPLSetThreadLocalConfigOption("PG_USE_COPY", "YES");
  }
  ~UseCopy() { CPLSetThreadLocalConfigOption("PG_USE_COPY", had_ ? old_.c_str() : nullptr); }
  UseCopy(const UseCopy&) = delete;
  UseCopy& operator=(const UseCopy&) = delete;

 private:
  bool had_ = false;
  std::string old_;
};

void write_tables(const mesh::MeshView& m, const Target& t, const WriteOptions& o);

}  // namespace

void write_postgis(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  const Target t(gis::is_pg_connection(path) ? path : "PG:" + path);
  // Anything but an fdr::Error (out of memory, a sizing field that throws) is an output error
  // too, naming the connection without its password.
  try {
    write_tables(m, t, o);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    t.fail(redact_passwords(e.what()));
  }
}

namespace {
void write_tables(const mesh::MeshView& m, const Target& t, const WriteOptions& o) {
  const PostgisOptions& p = o.postgis;
  check_prefix(p.prefix, t);
  validate_for_output(m, t.label());
  GdalErrors errs;
  // COPY for the rows (the driver's default for new tables; said here so a setting elsewhere
  // cannot turn it into row-by-row inserts).
  const UseCopy copy;
  DatasetPtr ds = open_for_writing(t, errs);
  OGRSpatialReference srs;
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (!m.crs_wkt.empty() && srs.SetFromUserInput(m.crs_wkt.c_str()) != OGRERR_NONE)
    t.fail("the mesh CRS cannot be parsed", &errs);
  const OGRSpatialReference* crs = m.crs_wkt.empty() ? nullptr : &srs;
  int written = 0;
  auto done = [&](const char* table) {
    ++written;
    if (written == p.fail_after_layer)
      t.fail("test hook: failure injected after table " + p.prefix + table + " (" + std::to_string(written) + " of 5)");
  };
  {
    Transaction tx(*ds, t, errs);
    const std::string schema = resolve_schema(*ds, p, t, errs);
    clear_target(*ds, schema, p, t, errs);
    const std::string& pre = p.prefix;
    OGRLayer* nodes = create_table(*ds, schema, pre + "nodes", crs, wkbPoint,
                                   {{"id", OFTInteger64}, real_column("z"), real_column("f"), real_column("conformity"),
                                    {"marker", OFTInteger}}, t, errs);
    write_nodes(*nodes, m, o, t, errs);
    done("nodes");
    OGRLayer* tris = create_table(*ds, schema, pre + "triangles", crs, wkbPolygon,
                                  {{"id", OFTInteger64}, {"n1", OFTInteger64}, {"n2", OFTInteger64},
                                   {"n3", OFTInteger64}, real_column("area"), real_column("min_angle"),
                                   real_column("R_over_f"), real_column("quality")}, t, errs);
    write_triangles(*tris, m, o, t, errs);
    done("triangles");
    OGRLayer* bnd = create_table(*ds, schema, pre + "boundaries", crs, wkbLineString,
                                 {{"id", OFTInteger}, {"kind", OFTString}, {"marker", OFTInteger},
                                  {"part", OFTInteger}, {"closed", OFTInteger, OFSTBoolean}, {"num_nodes", OFTInteger}},
                                 t, errs);
    write_boundaries(*bnd, m, t, errs);
    done("boundaries");
    OGRLayer* rep = create_table(*ds, schema, pre + "repairs", crs, wkbPoint,
                                 {{"kind", OFTString}, real_column("size"), {"reason", OFTString}, {"part", OFTInteger}},
                                 t, errs);
    write_repairs(*rep, o, t, errs);
    done("repairs");
    OGRLayer* meta = create_table(*ds, schema, pre + "metadata", nullptr, wkbNone,
                                  {{"key", OFTString}, {"value", OFTString}}, t, errs);
    write_metadata(*meta, o, t, errs);
    done("metadata");
    // Keys and spatial indexes over the loaded rows (GiST sorts more in memory than the default).
    exec(*ds, "SET LOCAL maintenance_work_mem = '256MB'", t, errs, "cannot set maintenance_work_mem");
    for (const char* n : kTables) finish_table(*ds, schema, pre + n, std::string(n) != "metadata", t, errs);
    tx.commit(t, errs);
  }
}
}  // namespace

}  // namespace fdr::io::detail
