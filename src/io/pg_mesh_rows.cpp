// The five PostGIS tables of a mesh and their rows (see pg_mesh_rows.hpp).
#include "io/pg_mesh_rows.hpp"

#include <cmath>

#include "base/redact.hpp"
#include "io/detail.hpp"

namespace fdr::io::detail {

namespace {

std::string geometry(const char* type, std::int32_t srid) {
  std::string g = "geom geometry(";
  g += type;
  if (srid != 0) g += ',' + std::to_string(srid);
  return g + ')';
}

// geom, id, z, f, conformity, marker: as the GeoPackage's nodes.
std::int64_t node_rows(pg::CopyBuffer& b, const mesh::MeshView& m, const WriteOptions& o, std::int32_t srid) {
  const std::vector<double> nn = nearest_neighbour_distance(m);
  const double nan = std::nan("");
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const Point2 w = m.world(static_cast<Index>(v));
    double fv = nan;
    if (!m.f.empty()) fv = m.f[v];
    else if (o.f) fv = (*o.f)(m.vertices[v]);
    double c = nan;
    if (fv > 0 && std::isfinite(nn[v]) && nn[v] > 0) c = std::min(nn[v] / fv, fv / nn[v]);
    b.row(7);
    b.i64(static_cast<std::int64_t>(v + 1));
    b.point(srid, w.x, w.y);
    b.i64(static_cast<std::int64_t>(v + 1));
    b.f8(m.z.empty() ? nan : m.z[v]);
    b.f8(fv);
    b.f8(c);
    b.i32(m.vertex_marker.empty() ? 0 : m.vertex_marker[v]);
  }
  return static_cast<std::int64_t>(m.vertices.size());
}

// geom, id, n1, n2, n3, area, min_angle, R_over_f, quality: as the GeoPackage's triangles.
std::int64_t triangle_rows(pg::CopyBuffer& b, const mesh::MeshView& m, const WriteOptions& o, std::int32_t srid) {
  const double nan = std::nan("");
  double ring[8];
  for (std::size_t tr = 0; tr < m.triangles.size(); ++tr) {
    const auto& v = m.triangles[tr];
    for (int k = 0; k <= 3; ++k) {
      const Point2 w = m.world(v[k % 3]);
      ring[2 * k] = w.x;
      ring[2 * k + 1] = w.y;
    }
    double r = nan;
    if (o.triangle_r_over_f) {
      r = (*o.triangle_r_over_f)[tr];
    } else if (o.f) {
      Point2 c;
      r = circumradius(m, tr, c) / (*o.f)(c);
    }
    const bool have_r = o.f || o.triangle_r_over_f;
    b.row(10);
    b.i64(static_cast<std::int64_t>(tr + 1));
    b.polygon(srid, ring, 4);
    b.i64(static_cast<std::int64_t>(tr + 1));
    for (int k = 0; k < 3; ++k) b.i64(static_cast<std::int64_t>(v[k]) + 1);
    b.f8(o.triangle_area ? (*o.triangle_area)[tr] : triangle_area(m, tr));
    b.f8(o.triangle_min_angle ? (*o.triangle_min_angle)[tr] : triangle_min_angle_deg(m, tr));
    b.f8(have_r ? r : nan);
    b.f8(triangle_quality(m, tr, o));
  }
  return static_cast<std::int64_t>(m.triangles.size());
}

// geom, id, kind, marker, part, closed, num_nodes: the boundary chains, as in the GeoPackage.
std::int64_t boundary_rows(pg::CopyBuffer& b, const mesh::MeshView& m, std::int32_t srid) {
  const std::vector<Chain> chains = build_chains(m);
  std::vector<double> xy;
  for (std::size_t i = 0; i < chains.size(); ++i) {
    const Chain& c = chains[i];
    xy.clear();
    for (Index v : c.nodes) {
      const Point2 w = m.world(v);
      xy.push_back(w.x);
      xy.push_back(w.y);
    }
    if (c.closed) {
      xy.push_back(xy[0]);
      xy.push_back(xy[1]);
    }
    b.row(8);
    b.i64(static_cast<std::int64_t>(i + 1));
    b.linestring(srid, xy);
    b.i32(static_cast<std::int32_t>(i + 1));
    b.text(kind_name(c.marker));
    b.i32(c.marker);
    b.i32(c.part);
    b.boolean(c.closed);
    b.i32(static_cast<std::int32_t>(c.nodes.size()));
  }
  return static_cast<std::int64_t>(chains.size());
}

// geom, kind, size, reason, part: the fixes made to the input (no geometry where unknown).
std::int64_t repair_rows(pg::CopyBuffer& b, const WriteOptions& o, std::int32_t srid) {
  std::int64_t fid = 0;
  for (const RepairRow& r : o.repairs) {
    b.row(6);
    b.i64(++fid);
    if (std::isfinite(r.x) && std::isfinite(r.y)) b.point(srid, r.x, r.y);
    else b.null();
    b.text(r.kind);
    b.f8(r.size);
    b.text(r.reason);
    b.i32(r.part);
  }
  return fid;
}

// key, value: the run's metadata as in the GeoPackage (passwords removed from every value).
std::int64_t metadata_table_rows(pg::CopyBuffer& b, const WriteOptions& o) {
  std::int64_t fid = 0;
  for (const auto& [k, v] : metadata_rows(o)) {
    b.row(3);
    b.i64(++fid);
    b.text(k);
    b.text(redact_passwords(v));
  }
  return fid;
}

}  // namespace

std::vector<PgTable> pg_tables(std::int32_t srid) {
  const std::string real = " double precision";
  return {
      {"nodes", true,
       geometry("Point", srid) + ", id bigint, z" + real + ", f" + real + ", conformity" + real + ", marker integer",
       "fid, geom, id, z, f, conformity, marker"},
      {"triangles", true,
       geometry("Polygon", srid) + ", id bigint, n1 bigint, n2 bigint, n3 bigint, area" + real + ", min_angle" + real +
           ", \"R_over_f\"" + real + ", quality" + real,
       "fid, geom, id, n1, n2, n3, area, min_angle, \"R_over_f\", quality"},
      {"boundaries", true,
       geometry("LineString", srid) +
           ", id integer, kind character varying, marker integer, part integer, closed boolean, num_nodes integer",
       "fid, geom, id, kind, marker, part, closed, num_nodes"},
      {"repairs", true,
       geometry("Point", srid) + ", kind character varying, size" + real + ", reason character varying, part integer",
       "fid, geom, kind, size, reason, part"},
      {"metadata", false, "key character varying, value character varying", "fid, key, value"},
  };
}

std::int64_t pg_rows(std::size_t i, pg::CopyBuffer& b, const mesh::MeshView& m, const WriteOptions& o,
                     std::int32_t srid) {
  switch (i) {
    case 0: return node_rows(b, m, o, srid);
    case 1: return triangle_rows(b, m, o, srid);
    case 2: return boundary_rows(b, m, srid);
    case 3: return repair_rows(b, o, srid);
    default: return metadata_table_rows(b, o);
  }
}

}  // namespace fdr::io::detail
