// GeoPackage writer through SQLite's API: every table written with prepared multi-row INSERTs in
// one transaction on a temporary file that is renamed into place once complete; geometry blobs
// built by hand (gpkg_geom.hpp); spatial indexes through SQLite's rtree module (gpkg_index.cpp).
// OGR is used only to turn the mesh CRS into the WKT1 definition and authority code of
// gpkg_spatial_ref_sys.
#include <ogr_spatialref.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <mutex>

#include "base/step_laps.hpp"
#include "io/antimeridian_ll.hpp"
#include "io/detail.hpp"
#include "io/gdal_util.hpp"
#include "io/gpkg_geom.hpp"
#include "io/gpkg_index.hpp"
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

// Page size, journal and locking of a database written from scratch in one transaction, then
// the transaction opened.
void open_gpkg(SqliteDb& db, std::size_t triangles) {
  // Large meshes get SQLite's largest pages: rows are appended, and SQLite balances the B-tree
  // and writes the file once per page. Small meshes keep 4 KiB pages, since every table and
  // index takes at least one page.
  if (triangles >= kLargePagesFrom) db.exec("PRAGMA page_size = 65536");
  db.exec("PRAGMA application_id = " + std::to_string(kGpkgApplicationId) + "; PRAGMA user_version = " +
          std::to_string(kGpkgUserVersion) + ";");
  // The file is a private temporary renamed onto the target only after COMMIT and close
  // succeeded; a failure or crash before that leaves only the temporary (removed, never renamed),
  // so a rollback journal and syncs would protect nothing.
  db.exec("PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF; PRAGMA locking_mode = EXCLUSIVE; "
          "PRAGMA cache_size = -8192; PRAGMA temp_store = MEMORY;");
  db.exec("BEGIN");
}

void create_feature_tables(SqliteDb& db) {
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
}

// Rows are inserted in fid order without naming the fid: SQLite then appends each row (fid =
// previous + 1, as the ids written assume) instead of searching the B-tree for its place.

// nodes: geom, id, z, f, conformity, marker. `nn`: nearest-neighbour distance per vertex.
void write_nodes(SqliteDb& db, GeomBlob& gb, const mesh::MeshView& m, const WriteOptions& o,
                 const std::vector<double>& nn, Extent& ext) {
  BatchInsert ins(db, "nodes", {"geom", "id", "z", "f", "conformity", "marker"}, 256);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const Point2 p = m.world(static_cast<Index>(v));
    double f = std::nan("");
    if (!m.f.empty()) f = m.f[v];
    else if (o.f) f = (*o.f)(m.vertices[v]);
    double c = std::nan("");
    if (f > 0 && std::isfinite(nn[v]) && nn[v] > 0) c = std::min(nn[v] / f, f / nn[v]);
    const std::string& g = gb.point(p.x, p.y);
    ins.add_blob(g.data(), g.size()).add_int(static_cast<std::int64_t>(v + 1));
    if (m.z.empty()) ins.add_null();
    else ins.add_real_or_null(m.z[v]);
    ins.add_real_or_null(f).add_real_or_null(c).add_int(m.vertex_marker.empty() ? 0 : m.vertex_marker[v]);
    ins.end_row();
    ext.add(p.x, p.x, p.y, p.y);
  }
  ins.finish();
}

// triangles: geom, id, n1, n2, n3, area, min_angle, R_over_f, quality.
void write_triangles(SqliteDb& db, GeomBlob& gb, const mesh::MeshView& m, const WriteOptions& o) {
  BatchInsert ins(db, "triangles", {"geom", "id", "n1", "n2", "n3", "area", "min_angle", "R_over_f", "quality"}, 128);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tr = m.triangles[t];
    Point2 w[3];
    for (int k = 0; k < 3; ++k) w[k] = m.world(tr[k]);
    if (o.continue_across_antimeridian) continue_longitudes(w, 3, true);
    const std::string& g = gb.polygon(w, 3);
    ins.add_blob(g.data(), g.size()).add_int(static_cast<std::int64_t>(t + 1));
    for (int k = 0; k < 3; ++k) ins.add_int(static_cast<std::int64_t>(tr[k]) + 1);
    ins.add_real_or_null(o.triangle_area ? (*o.triangle_area)[t] : triangle_area(m, t));
    ins.add_real_or_null(o.triangle_min_angle ? (*o.triangle_min_angle)[t] : triangle_min_angle_deg(m, t));
    if (o.f || o.triangle_r_over_f) {
      double r;
      if (o.triangle_r_over_f) {
        r = (*o.triangle_r_over_f)[t];
      } else {
        Point2 c;
        r = circumradius(m, t, c) / (*o.f)(c);
      }
      ins.add_real_or_null(r);
    } else {
      ins.add_null();
    }
    ins.add_real_or_null(triangle_quality(m, t, o));
    ins.end_row();
  }
  ins.finish();
}

// boundaries: geom, id, kind, marker, part, closed, num_nodes. Returns each chain's envelope.
std::vector<IndexBox> write_boundaries(SqliteDb& db, GeomBlob& gb, const mesh::MeshView& m,
                                       const std::vector<Chain>& chains, Extent& ext, bool antimeridian) {
  BatchInsert ins(db, "boundaries", {"geom", "id", "kind", "marker", "part", "closed", "num_nodes"}, 32);
  std::vector<IndexBox> boxes;
  std::vector<Point2> pts;
  for (std::size_t i = 0; i < chains.size(); ++i) {
    const Chain& c = chains[i];
    pts.clear();
    for (Index v : c.nodes) pts.push_back(m.world(v));
    if (antimeridian) continue_longitudes(pts.data(), pts.size(), c.closed);
    const std::string& g = gb.linestring(pts.data(), static_cast<std::uint32_t>(pts.size()), c.closed);
    ins.add_blob(g.data(), g.size()).add_int(static_cast<std::int64_t>(i + 1)).add_text(kind_name(c.marker));
    ins.add_int(c.marker).add_int(c.part).add_int(c.closed ? 1 : 0).add_int(static_cast<std::int64_t>(c.nodes.size()));
    ins.end_row();
    ext.add(gb.minx, gb.maxx, gb.miny, gb.maxy);
    boxes.push_back({gb.minx, gb.maxx, gb.miny, gb.maxy});
  }
  ins.finish();
  return boxes;
}

// repairs: geom, kind, size, reason, part.
void write_repairs(SqliteDb& db, GeomBlob& gb, const std::vector<RepairRow>& repairs, Extent& ext) {
  BatchInsert ins(db, "repairs", {"geom", "kind", "size", "reason", "part"}, 64);
  for (const RepairRow& r : repairs) {
    const std::string& g = gb.point(r.x, r.y);
    ins.add_blob(g.data(), g.size()).add_text(r.kind).add_real_or_null(r.size).add_text(r.reason).add_int(r.part);
    ins.end_row();
    if (std::isfinite(r.x) && std::isfinite(r.y)) ext.add(r.x, r.x, r.y, r.y);
  }
  ins.finish();
}

// metadata: key, value; the title and bound B added when the caller's rows lack them.
void write_metadata(SqliteDb& db, const WriteOptions& o) {
  BatchInsert ins(db, "metadata", {"key", "value"}, 16);
  for (const auto& [k, v] : metadata_rows(o)) {
    ins.add_text(k).add_text(v);
    ins.end_row();
  }
  ins.finish();
}

// The spatial indexes of the four feature tables, each box the envelope its geometry blob has.
void write_indexes(SqliteDb& db, const mesh::MeshView& m, bool antimeridian, const std::vector<IndexBox>& chain_boxes,
                   const std::vector<RepairRow>& repairs, StepLaps& lap) {
  build_gpkg_rtree(db, "nodes", "geom", m.vertices.size(), [&m](std::size_t v, IndexBox& b) {
    const Point2 p = m.world(static_cast<Index>(v));
    b = {p.x, p.x, p.y, p.y};
    return true;
  });
  lap("node rtree");
  build_gpkg_rtree(db, "triangles", "geom", m.triangles.size(), [&m, antimeridian](std::size_t t, IndexBox& b) {
    Point2 w[3];
    for (int k = 0; k < 3; ++k) w[k] = m.world(m.triangles[t][k]);
    if (antimeridian) continue_longitudes(w, 3, true);
    b = {w[0].x, w[0].x, w[0].y, w[0].y};
    for (int k = 1; k < 3; ++k) {
      b.minx = std::min(b.minx, w[k].x), b.maxx = std::max(b.maxx, w[k].x);
      b.miny = std::min(b.miny, w[k].y), b.maxy = std::max(b.maxy, w[k].y);
    }
    return true;
  });
  lap("triangle rtree");
  build_gpkg_rtree(db, "boundaries", "geom", chain_boxes.size(), [&chain_boxes](std::size_t i, IndexBox& b) {
    b = chain_boxes[i];
    return true;
  });
  build_gpkg_rtree(db, "repairs", "geom", repairs.size(), [&repairs](std::size_t i, IndexBox& b) {
    const RepairRow& r = repairs[i];
    b = {r.x, r.x, r.y, r.y};
    return std::isfinite(r.x) && std::isfinite(r.y);
  });
}

}  // namespace

void write_gpkg(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  StepLaps lap(debug::Aid::kGpkg, "gpkg");  // developer aid (base/step_laps.hpp)
  const SrsRow srs = srs_row(m.crs_wkt, path);
  std::vector<double> nn = nearest_neighbour_distance(m);
  lap("srs, nearest neighbours");

  TempFile tf(path);  // declared before the database: the database closes first on failure
  tf.release_for_library();
  SqliteDb db(tf.path(), path);
  open_gpkg(db, m.triangles.size());
  create_core_tables(db, srs);
  create_feature_tables(db);
  GeomBlob gb(static_cast<std::int32_t>(srs.id));
  Extent mesh_ext, repair_ext;
  write_nodes(db, gb, m, o, nn, mesh_ext);
  std::vector<double>().swap(nn);
  lap("nodes");
  write_triangles(db, gb, m, o);
  lap("triangles");
  const std::vector<IndexBox> chain_boxes = write_boundaries(db, gb, m, build_chains(m), mesh_ext, o.continue_across_antimeridian);
  write_repairs(db, gb, o.repairs, repair_ext);
  write_metadata(db, o);
  // Table order as OGR lists layers: the order of gpkg_contents rows.
  register_table(db, "nodes", "POINT", srs.id, mesh_ext);
  register_table(db, "triangles", "POLYGON", srs.id, mesh_ext);
  register_table(db, "boundaries", "LINESTRING", srs.id, mesh_ext);
  register_table(db, "repairs", "POINT", srs.id, repair_ext);
  register_table(db, "metadata", nullptr, 0, {});
  lap("boundaries, repairs, metadata");
  if (o.gpkg_spatial_index) write_indexes(db, m, o.continue_across_antimeridian, chain_boxes, o.repairs, lap);
  db.exec("COMMIT");
  db.close();
  tf.commit();
  lap("commit, close, rename");
}

}  // namespace fdr::io::detail
