// GeoPackage writer straight through SQLite: nodes, triangles, boundaries, repairs and metadata
// tables in one transaction, geometry blobs (GeoPackage header + WKB) built by hand, batched
// prepared inserts in fid order, R-trees bulk-loaded (gpkg_rtree.cpp). OGR is used only to turn
// the mesh CRS into the WKT1 definition and authority code of gpkg_spatial_ref_sys.
#include <ogr_spatialref.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

#include "base/step_laps.hpp"
#include "base/parallel.hpp"
#include "io/detail.hpp"
#include "io/gdal_util.hpp"
#include "io/gpkg_rtree.hpp"
#include "io/sqlite_bulk.hpp"
#include "io/sqlite_db.hpp"

namespace fdr::io::detail {

void gdal_register_once() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

namespace {

constexpr std::int64_t kGpkgApplicationId = 0x47504B47;  // "GPKG"
constexpr int kGpkgUserVersion = 10200;                  // GeoPackage 1.2
constexpr std::int64_t kCustomSrsId = 100000;            // first id GDAL uses for a CRS without authority code
constexpr std::size_t kLargePagesFrom = 32768;           // triangles from which the file has 64 KiB pages

std::string sql_quote(std::string_view s) {
  std::string r = "'";
  for (char c : s) {
    if (c == '\'') r += '\'';
    r += c;
  }
  return r + "'";
}

std::string real_or_null(double v) {
  if (!std::isfinite(v)) return "NULL";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// The CRS row of gpkg_spatial_ref_sys (srs_id -1: undefined Cartesian, already present).
struct SrsRow {
  std::int64_t id = -1;
  std::string name, organization, definition;
  std::int64_t org_id = -1;
};

SrsRow srs_row(const std::string& wkt, const std::string& path) {
  SrsRow r;
  if (wkt.empty()) return r;
  gdal_register_once();
  GdalErrors errs;
  OGRSpatialReference srs;
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (srs.SetFromUserInput(wkt.c_str()) != OGRERR_NONE) fail_output(path, errs.reason("the mesh CRS cannot be parsed"));
  const char* name = srs.GetName();
  r.name = name ? name : "Unnamed";
  const char* auth = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (auth && code && EQUAL(auth, "EPSG") && std::atoll(code) > 0) {
    r.organization = "EPSG";
    r.org_id = r.id = std::atoll(code);
  } else {
    r.organization = "NONE";
    r.org_id = r.id = kCustomSrsId;
  }
  // GeoPackage 1.2 definitions are WKT1 (as GDAL writes them); WKT2-only CRSs keep their WKT2.
  char* out = nullptr;
  const char* opts[] = {"FORMAT=WKT1", "ALLOW_ELLIPSOIDAL_HEIGHT_AS_VERTICAL_CRS=YES", nullptr};
  if (srs.exportToWkt(&out, opts) == OGRERR_NONE && out) r.definition = out;
  else r.definition = wkt;
  CPLFree(out);
  return r;
}

// GeoPackage geometry blob: "GP", version 0, flags (little endian; envelope [minx,maxx,miny,maxy]
// except for points; empty bit), srs_id, envelope, then little-endian WKB.
class GeomBlob {
 public:
  explicit GeomBlob(std::int32_t srs) : srs_(srs) {}
  void set_srs(std::int32_t srs) { srs_ = srs; }
  const std::string& point(double x, double y) {
    const bool empty = !(std::isfinite(x) && std::isfinite(y));
    header(empty ? 0x11 : 0x01);
    wkb_head(1);
    if (empty) x = y = std::numeric_limits<double>::quiet_NaN();
    put(x);
    put(y);
    return b_;
  }
  // Polygon with one ring or linestring; `closed` repeats the first point (the ring always is).
  // The polygon's bytes are written in place into a buffer sized once (one per triangle row).
  template <class Pt>
  const std::string& polygon(const Pt* p, std::uint32_t n) {
    header(0x03);
    envelope(p, n);
    const std::size_t at = b_.size();
    b_.resize(at + 1 + 4 + 4 + 4 + 16 * (static_cast<std::size_t>(n) + 1));
    char* o = b_.data() + at;
    *o++ = 1;  // little endian
    const std::uint32_t head[3] = {3, 1, n + 1};  // polygon, one ring, its points
    std::memcpy(o, head, 12);
    o += 12;
    for (std::uint32_t i = 0; i <= n; ++i, o += 16) {
      const double xy[2] = {p[i % n].x, p[i % n].y};
      std::memcpy(o, xy, 16);
    }
    return b_;
  }
  template <class Pt>
  const std::string& linestring(const Pt* p, std::uint32_t n, bool closed) {
    header(0x03);
    envelope(p, n);
    wkb_head(2);
    put32(n + (closed ? 1 : 0));
    for (std::uint32_t i = 0; i < n; ++i) put(p[i].x), put(p[i].y);
    if (closed) put(p[0].x), put(p[0].y);
    return b_;
  }
  double minx = 0, maxx = 0, miny = 0, maxy = 0;  // envelope of the last polygon/linestring

 private:
  void header(std::uint8_t flags) {
    b_.resize(8);
    b_[0] = 'G';
    b_[1] = 'P';
    b_[2] = 0;
    b_[3] = static_cast<char>(flags);
    const auto srs = static_cast<std::uint32_t>(srs_);
    std::memcpy(&b_[4], &srs, 4);
  }
  template <class Pt>
  void envelope(const Pt* p, std::uint32_t n) {
    minx = maxx = p[0].x;
    miny = maxy = p[0].y;
    for (std::uint32_t i = 1; i < n; ++i) {
      minx = std::min(minx, p[i].x), maxx = std::max(maxx, p[i].x);
      miny = std::min(miny, p[i].y), maxy = std::max(maxy, p[i].y);
    }
    const double e[4] = {minx, maxx, miny, maxy};
    b_.append(reinterpret_cast<const char*>(e), 32);
  }
  void wkb_head(std::uint32_t type) {
    b_.push_back(1);
    put32(type);
  }
  void put32(std::uint32_t v) {
    char c[4];
    std::memcpy(c, &v, 4);  // little-endian host (checked below)
    b_.append(c, 4);
  }
  void put(double v) {
    char c[8];
    std::memcpy(c, &v, 8);
    b_.append(c, 8);
  }
  std::int32_t srs_;
  std::string b_;
};
static_assert(std::endian::native == std::endian::little, "GeomBlob writes the host byte order as little endian");

struct Extent {
  double minx = std::numeric_limits<double>::infinity(), maxx = -minx, miny = minx, maxy = -minx;
  void add(double x0, double x1, double y0, double y1) {
    minx = std::min(minx, x0), maxx = std::max(maxx, x1), miny = std::min(miny, y0), maxy = std::max(maxy, y1);
  }
  bool empty() const { return !(minx <= maxx); }
};

// The mandatory GeoPackage tables and the srs rows (GeoPackage 1.2, tables as GDAL creates them).
void create_core_tables(SqliteDb& db, const SrsRow& srs) {
  db.exec(
      "CREATE TABLE gpkg_spatial_ref_sys (srs_name TEXT NOT NULL,srs_id INTEGER NOT NULL PRIMARY KEY,organization TEXT "
      "NOT NULL,organization_coordsys_id INTEGER NOT NULL,definition  TEXT NOT NULL,description TEXT);"
      "INSERT INTO gpkg_spatial_ref_sys VALUES ('Undefined Cartesian SRS',-1,'NONE',-1,'undefined','undefined Cartesian "
      "coordinate reference system');"
      "INSERT INTO gpkg_spatial_ref_sys VALUES ('Undefined geographic SRS',0,'NONE',0,'undefined','undefined geographic "
      "coordinate reference system');"
      "CREATE TABLE gpkg_contents (table_name TEXT NOT NULL PRIMARY KEY,data_type TEXT NOT NULL,identifier TEXT "
      "UNIQUE,description TEXT DEFAULT '',last_change DATETIME NOT NULL DEFAULT "
      "(strftime('%Y-%m-%dT%H:%M:%fZ','now')),min_x DOUBLE, min_y DOUBLE,max_x DOUBLE, max_y DOUBLE,srs_id "
      "INTEGER,CONSTRAINT fk_gc_r_srs_id FOREIGN KEY (srs_id) REFERENCES gpkg_spatial_ref_sys(srs_id));"
      "CREATE TABLE gpkg_geometry_columns (table_name TEXT NOT NULL,column_name TEXT NOT NULL,geometry_type_name TEXT "
      "NOT NULL,srs_id INTEGER NOT NULL,z TINYINT NOT NULL,m TINYINT NOT NULL,CONSTRAINT pk_geom_cols PRIMARY KEY "
      "(table_name, column_name),CONSTRAINT uk_gc_table_name UNIQUE (table_name),CONSTRAINT fk_gc_tn FOREIGN KEY "
      "(table_name) REFERENCES gpkg_contents(table_name),CONSTRAINT fk_gc_srs FOREIGN KEY (srs_id) REFERENCES "
      "gpkg_spatial_ref_sys (srs_id));"
      "CREATE TABLE gpkg_extensions (table_name TEXT, column_name TEXT, extension_name TEXT NOT NULL, definition TEXT "
      "NOT NULL, scope TEXT NOT NULL, CONSTRAINT ge_tce UNIQUE (table_name, column_name, extension_name));");
  if (srs.id != 4326)
    db.exec(
        "INSERT INTO gpkg_spatial_ref_sys VALUES ('WGS 84 geodetic',4326,'EPSG',4326,'GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\","
        "SPHEROID[\"WGS 84\",6378137,298.257223563,AUTHORITY[\"EPSG\",\"7030\"]],AUTHORITY[\"EPSG\",\"6326\"]],PRIMEM["
        "\"Greenwich\",0,AUTHORITY[\"EPSG\",\"8901\"]],UNIT[\"degree\",0.0174532925199433,AUTHORITY[\"EPSG\",\"9122\"]],"
        "AXIS[\"Latitude\",NORTH],AXIS[\"Longitude\",EAST],AUTHORITY[\"EPSG\",\"4326\"]]','longitude/latitude "
        "coordinates in decimal degrees on the WGS 84 spheroid')");
  if (srs.id != -1)
    db.exec("INSERT INTO gpkg_spatial_ref_sys VALUES (" + sql_quote(srs.name) + "," + std::to_string(srs.id) + "," +
            sql_quote(srs.organization) + "," + std::to_string(srs.org_id) + "," + sql_quote(srs.definition) +
            (srs.organization == "EPSG" ? ",NULL)" : ",'')"));
}

void register_table(SqliteDb& db, const std::string& table, const char* geom_type, std::int64_t srs_id, const Extent& e) {
  const bool features = geom_type != nullptr;
  std::string sql = "INSERT INTO gpkg_contents (table_name, data_type, identifier, description, min_x, min_y, max_x, "
                    "max_y, srs_id) VALUES (" + sql_quote(table) + (features ? ",'features'," : ",'attributes',") +
                    sql_quote(table) + ",''";
  if (features && !e.empty())
    for (double v : {e.minx, e.miny, e.maxx, e.maxy}) sql.append(",").append(real_or_null(v));
  else
    sql += ",NULL,NULL,NULL,NULL";
  sql += ',';
  sql += std::to_string(features ? srs_id : 0);
  sql += ')';
  db.exec(sql);
  if (features)
    db.exec("INSERT INTO gpkg_geometry_columns VALUES (" + sql_quote(table) + ",'geom','" + geom_type + "'," +
            std::to_string(srs_id) + ",0,0)");
}

// The rows of the nodes and triangles tables, for BatchInsert (SQL inserts) and Record (pages
// written by sqlite_bulk.cpp) alike: the same values in the same column order.
struct RowValues {
  const mesh::MeshView& m;
  const WriteOptions& o;
  const std::vector<double>& nn;  // nearest-neighbour distance per vertex

  // geom, id, z, f, conformity, marker
  template <class Sink>
  void node(Sink& s, GeomBlob& gb, std::size_t v) const {
    const Point2 p = m.world(static_cast<Index>(v));
    double f = std::nan("");
    if (!m.f.empty()) f = m.f[v];
    else if (o.f) f = (*o.f)(m.vertices[v]);
    double c = std::nan("");
    if (f > 0 && std::isfinite(nn[v]) && nn[v] > 0) c = std::min(nn[v] / f, f / nn[v]);
    const std::string& g = gb.point(p.x, p.y);
    s.add_blob(g.data(), g.size()).add_int(static_cast<std::int64_t>(v + 1));
    if (m.z.empty()) s.add_null();
    else s.add_real_or_null(m.z[v]);
    s.add_real_or_null(f).add_real_or_null(c).add_int(m.vertex_marker.empty() ? 0 : m.vertex_marker[v]);
    s.end_row();
  }
  // geom, id, n1, n2, n3, area, min_angle, R_over_f, quality
  template <class Sink>
  void triangle(Sink& s, GeomBlob& gb, std::size_t t) const {
    const auto& tr = m.triangles[t];
    Point2 w[3];
    for (int k = 0; k < 3; ++k) w[k] = m.world(tr[k]);
    const std::string& g = gb.polygon(w, 3);
    s.add_blob(g.data(), g.size()).add_int(static_cast<std::int64_t>(t + 1));
    for (int k = 0; k < 3; ++k) s.add_int(static_cast<std::int64_t>(tr[k]) + 1);
    s.add_real_or_null(o.triangle_area ? (*o.triangle_area)[t] : triangle_area(m, t));
    s.add_real_or_null(o.triangle_min_angle ? (*o.triangle_min_angle)[t] : triangle_min_angle_deg(m, t));
    if (o.f || o.triangle_r_over_f) {
      double r;
      if (o.triangle_r_over_f) {
        r = (*o.triangle_r_over_f)[t];
      } else {
        Point2 c;
        r = circumradius(m, t, c) / (*o.f)(c);
      }
      s.add_real_or_null(r);
      if (o.bound_B > 0) s.add_real_or_null(r / o.bound_B);
      else s.add_null();
    } else {
      s.add_null().add_null();
    }
    s.end_row();
  }
};

}  // namespace

void write_gpkg(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  StepLaps lap(debug::Aid::kGpkg, "gpkg");  // developer aid (base/step_laps.hpp)
  const SrsRow srs = srs_row(m.crs_wkt, path);
  const auto srs_id = static_cast<std::int32_t>(srs.id);

  // Per-vertex f (from the mesh, else from the sizing field) and conformity.
  const std::size_t nv = m.vertices.size(), nt = m.triangles.size();
  std::vector<double> nn = nearest_neighbour_distance(m);
  lap("srs, nearest neighbours");

  TempFile tf(path);  // declared before the database: the database closes first on failure
  tf.release_for_library();
  SqliteDb db(tf.path(), path);
  // Pages of 64 KiB (SQLite's largest) for large meshes: the rows are appended, and per page
  // SQLite balances the B-tree and the file takes one write, so 16x fewer of both (GPKG writes of
  // a 1 M-triangle square: 1.54-1.82 s with 4 KiB pages, 1.29-1.52 s with 64 KiB, interleaved).
  // R-tree nodes stay 51 cells (SQLite's cap, reached from 4 KiB pages on). Small meshes keep
  // 4 KiB pages: every table takes at least one page.
  if (nt >= kLargePagesFrom) db.exec("PRAGMA page_size = 65536");
  // No auto-vacuum (the B-tree pages written by sqlite_bulk.cpp assume none; SQLite's default,
  // unless a build changed it).
  db.exec("PRAGMA auto_vacuum = NONE");
  db.exec("PRAGMA application_id = " + std::to_string(kGpkgApplicationId) + "; PRAGMA user_version = " +
          std::to_string(kGpkgUserVersion) + ";");
  // The file is a private temp file renamed into place on success, so no journal and no syncs:
  // a crash leaves only the temp file, which is never renamed.
  db.exec("PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF; PRAGMA locking_mode = EXCLUSIVE; "
          "PRAGMA cache_size = -8192; PRAGMA temp_store = MEMORY;");
  db.exec("BEGIN");
  create_core_tables(db, srs);
  db.exec(
      "CREATE TABLE \"nodes\" ( \"fid\" INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, \"geom\" POINT, \"id\" INTEGER, "
      "\"z\" REAL, \"f\" REAL, \"conformity\" REAL, \"marker\" MEDIUMINT);"
      "CREATE TABLE \"triangles\" ( \"fid\" INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, \"geom\" POLYGON, \"id\" "
      "INTEGER, \"n1\" INTEGER, \"n2\" INTEGER, \"n3\" INTEGER, \"area\" REAL, \"min_angle\" REAL, \"R_over_f\" REAL, "
      "\"quality\" REAL);"
      "CREATE TABLE \"boundaries\" ( \"fid\" INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, \"geom\" LINESTRING, \"id\" "
      "MEDIUMINT, \"kind\" TEXT, \"marker\" MEDIUMINT, \"part\" MEDIUMINT, \"closed\" BOOLEAN, \"num_nodes\" INTEGER);"
      "CREATE TABLE \"repairs\" ( \"fid\" INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, \"geom\" POINT, \"kind\" TEXT, "
      "\"size\" REAL, \"reason\" TEXT, \"part\" MEDIUMINT);"
      "CREATE TABLE \"metadata\" ( \"fid\" INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, \"key\" TEXT, \"value\" TEXT);");

  const bool index = o.gpkg_spatial_index;
  std::vector<RtreeEntry> chain_boxes, repair_boxes;
  // The R-trees of nodes and triangles (their boxes and STR packing) are planned from the mesh
  // alone, while the rows go in when threads allow (same trees either way).
  RtreePlan node_plan, tri_plan;
  std::exception_ptr plan_error;
  auto plan_trees = [&, cap = index ? gpkg_rtree_cap(db.query_int("PRAGMA page_size")) : 0] {
    try {
      std::vector<RtreeEntry> boxes;
      boxes.reserve(nv);
      for (std::size_t v = 0; v < nv; ++v) {
        const Point2 p = m.world(static_cast<Index>(v));
        boxes.push_back(RtreeEntry::of(static_cast<std::int64_t>(v + 1), p.x, p.x, p.y, p.y));
      }
      node_plan = plan_gpkg_rtree(std::move(boxes), cap);
      boxes = {};
      boxes.reserve(nt);
      Point2 w[3];
      for (std::size_t t = 0; t < nt; ++t) {
        for (int k = 0; k < 3; ++k) w[k] = m.world(m.triangles[t][k]);
        // The envelope as GeomBlob::envelope computes it (the same comparisons in the same order).
        double minx = w[0].x, maxx = w[0].x, miny = w[0].y, maxy = w[0].y;
        for (int k = 1; k < 3; ++k) {
          minx = std::min(minx, w[k].x), maxx = std::max(maxx, w[k].x);
          miny = std::min(miny, w[k].y), maxy = std::max(maxy, w[k].y);
        }
        boxes.push_back(RtreeEntry::of(static_cast<std::int64_t>(t + 1), minx, maxx, miny, maxy));
      }
      tri_plan = plan_gpkg_rtree(std::move(boxes), cap);
    } catch (...) {
      plan_error = std::current_exception();
    }
  };
  GeomBlob gb(srs_id);
  Extent mesh_ext, repair_ext;

  // The rows of nodes and triangles, and the shadow tables of their R-trees, are written as
  // B-tree pages after SQLite has made everything else (sqlite_bulk.cpp: SQLite inserts about
  // 1 M rows/s on one thread). FDR_GPKG_SQL_ROWS: SQLite inserts them (the tests' reference);
  // then they are built on one thread and bound and stepped by another (BatchInsert async)
  // when threads allow.
  const bool bulk = std::getenv("FDR_GPKG_SQL_ROWS") == nullptr;
  const bool async = max_threads() > 1;
  const RowValues values{m, o, nn};
  auto write_rows = [&] {
    // Rows are written in fid order without naming the fid: SQLite then appends each row (fid =
    // previous + 1, as the ids below assume) instead of searching the B-tree for it.
    if (bulk) {
      // The rows are written as pages once SQLite is done (below); the extent now, and the
      // AUTOINCREMENT counters SQLite would have set (in the same order).
      for (std::size_t v = 0; v < nv; ++v) {
        const Point2 p = m.world(static_cast<Index>(v));
        mesh_ext.add(p.x, p.x, p.y, p.y);
      }
      if (nv > 0) db.exec("INSERT INTO sqlite_sequence (name, seq) VALUES ('nodes', " + std::to_string(nv) + ")");
      if (nt > 0) db.exec("INSERT INTO sqlite_sequence (name, seq) VALUES ('triangles', " + std::to_string(nt) + ")");
    } else {
      {
        BatchInsert ins(db, "nodes", {"geom", "id", "z", "f", "conformity", "marker"}, 256, async);
        for (std::size_t v = 0; v < nv; ++v) {
          values.node(ins, gb, v);
          const Point2 p = m.world(static_cast<Index>(v));
          mesh_ext.add(p.x, p.x, p.y, p.y);
        }
        ins.finish();
      }
      std::vector<double>().swap(nn);
      {
        BatchInsert ins(db, "triangles", {"geom", "id", "n1", "n2", "n3", "area", "min_angle", "R_over_f", "quality"},
                        128, async);
        for (std::size_t t = 0; t < nt; ++t) values.triangle(ins, gb, t);
        ins.finish();
      }
    }
    {
      const std::vector<Chain> chains = build_chains(m);
      BatchInsert ins(db, "boundaries", {"geom", "id", "kind", "marker", "part", "closed", "num_nodes"}, 32);
      std::vector<Point2> pts;
      for (std::size_t i = 0; i < chains.size(); ++i) {
        const Chain& c = chains[i];
        pts.clear();
        for (Index v : c.nodes) pts.push_back(m.world(v));
        const std::string& g = gb.linestring(pts.data(), static_cast<std::uint32_t>(pts.size()), c.closed);
        const auto fid = static_cast<std::int64_t>(i + 1);
        ins.add_blob(g.data(), g.size()).add_int(fid).add_text(kind_name(c.marker)).add_int(c.marker);
        ins.add_int(c.part).add_int(c.closed ? 1 : 0).add_int(static_cast<std::int64_t>(c.nodes.size()));
        ins.end_row();
        mesh_ext.add(gb.minx, gb.maxx, gb.miny, gb.maxy);
        chain_boxes.push_back(RtreeEntry::of(fid, gb.minx, gb.maxx, gb.miny, gb.maxy));
      }
      ins.finish();
    }
    {
      BatchInsert ins(db, "repairs", {"geom", "kind", "size", "reason", "part"}, 64);
      for (std::size_t i = 0; i < o.repairs.size(); ++i) {
        const RepairRow& r = o.repairs[i];
        const std::string& g = gb.point(r.x, r.y);
        const auto fid = static_cast<std::int64_t>(i + 1);
        ins.add_blob(g.data(), g.size()).add_text(r.kind).add_real_or_null(r.size).add_text(r.reason);
        ins.add_int(r.part);
        ins.end_row();
        if (std::isfinite(r.x) && std::isfinite(r.y)) {
          repair_boxes.push_back(RtreeEntry::of(fid, r.x, r.x, r.y, r.y));
          repair_ext.add(r.x, r.x, r.y, r.y);
        }
      }
      ins.finish();
    }
    {
      BatchInsert ins(db, "metadata", {"key", "value"}, 16);
      auto row = [&](const std::string& k, const std::string& v) {
        ins.add_text(k).add_text(v);
        ins.end_row();
      };
      bool has_title = false, has_b = false;
      for (const auto& [k, v] : o.metadata) {
        has_title |= k == "title";
        has_b |= k == "bound_B";
        row(k, v);
      }
      if (!has_title && !o.title.empty()) row("title", o.title);
      if (!has_b && o.bound_B > 0) row("bound_B", real_or_null(o.bound_B));
      ins.finish();
    }
    // Table order as OGR lists layers: the order of gpkg_contents rows.
    register_table(db, "nodes", "POINT", srs.id, mesh_ext);
    register_table(db, "triangles", "POLYGON", srs.id, mesh_ext);
    register_table(db, "boundaries", "LINESTRING", srs.id, mesh_ext);
    register_table(db, "repairs", "POINT", srs.id, repair_ext);
    register_table(db, "metadata", nullptr, 0, {});
  };
  // Two threads when allowed: `rows` on a helper thread while this one plans the R-trees (the
  // plans' large arrays then reuse the pages this thread's heap freed in the stages before, as
  // without threads: 15-20 MiB less at the process's peak than on a fresh thread).
  auto beside_plans = [&](auto&& rows) {
    if (index && max_threads() > 1) {
      run_beside(rows, [&] { plan_trees(); });
    } else {
      if (index) plan_trees();
      rows();
    }
  };
  if (!bulk) {
    beside_plans(write_rows);
    lap("rows and R-tree plans");
    if (index) {
      if (plan_error) std::rethrow_exception(plan_error);
      build_gpkg_rtree(db, "nodes", "geom", "fid", std::move(node_plan));
      lap("node rtree");
      build_gpkg_rtree(db, "triangles", "geom", "fid", std::move(tri_plan));
      lap("triangle rtree");
      build_gpkg_rtree(db, "boundaries", "geom", "fid", std::move(chain_boxes));
      build_gpkg_rtree(db, "repairs", "geom", "fid", std::move(repair_boxes));
    }
    db.exec("COMMIT");
    db.close();
    lap("commit, close");
    tf.commit();
    return;
  }
  // SQLite makes the small tables and the frames of the R-trees of nodes and triangles (empty
  // shadow tables), then the nodes and triangles go in as pages, while a helper thread plans the
  // R-trees; their shadow tables go in last, as pages too.
  RtreeRows node_tree, tri_tree;
  auto tables_and_rows = [&] {
    write_rows();
    if (index) {
      node_tree = create_gpkg_rtree(db, "nodes", "geom", "fid", nv > 0);
      tri_tree = create_gpkg_rtree(db, "triangles", "geom", "fid", nt > 0);
      build_gpkg_rtree(db, "boundaries", "geom", "fid", std::move(chain_boxes));
      build_gpkg_rtree(db, "repairs", "geom", "fid", std::move(repair_boxes));
    }
    // The rows are built on two threads: a sizing field that is not thread-safe keeps them on one.
    const bool f_shared = !o.f || o.f->thread_safe();
    std::vector<BulkTable> tables;
    tables.push_back({"nodes", db.root_page("nodes"), nv, m.f.size() == nv || f_shared, [&values, srs_id](std::size_t v, Record& r) {
                        thread_local GeomBlob gb(0);
                        gb.set_srs(srs_id);
                        r.clear(static_cast<std::int64_t>(v + 1));
                        r.add_null();  // fid: the rowid
                        values.node(r, gb, v);
                      }});
    tables.push_back({"triangles", db.root_page("triangles"), nt, o.triangle_r_over_f != nullptr || f_shared,
                      [&values, srs_id](std::size_t t, Record& r) {
                        thread_local GeomBlob gb(0);
                        gb.set_srs(srs_id);
                        r.clear(static_cast<std::int64_t>(t + 1));
                        r.add_null();
                        values.triangle(r, gb, t);
                      }});
    db.exec("COMMIT");
    db.close();
    write_bulk_tables(tf.path(), path, tables);
  };
  beside_plans(tables_and_rows);
  lap("tables and node and triangle pages, R-tree plans beside");
  if (index) {
    if (plan_error) std::rethrow_exception(plan_error);
    node_tree.set_plan(std::move(node_plan), path);
    tri_tree.set_plan(std::move(tri_plan), path);
    std::vector<BulkTable> tables;
    node_tree.add_tables(tables);
    tri_tree.add_tables(tables);
    write_bulk_tables(tf.path(), path, tables);
    lap("R-tree pages");
  }
  tf.commit();
  lap("commit");
}

}  // namespace fdr::io::detail
