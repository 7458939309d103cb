// TetGen's input formats (.node, .poly, .smesh) and its mesh files (.node/.ele/.face).
#include "tetio/read_tetgen.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include "base/path_util.hpp"
#include "predicates/predicates3d.hpp"
#include "tetio/text_lines.hpp"

namespace fdr::tetio {
namespace {

// Header counts come from the file: reserving only up to this many keeps a garbage count from
// allocating before the missing lines are noticed.
constexpr std::int64_t kReserveCap = 1 << 16;

std::int64_t count_field(const TextLines& in, std::size_t i, const std::string& what) {
  const std::int64_t n = in.integer(i);
  if (n < 0) in.fail("negative " + what + " " + std::to_string(n));
  return n;
}

// A node list whose header is the current line of `in`: its points are appended to plc.points
// (markers to plc.point_markers when the file has them). Returns the first point's number (the
// base of every index in the file); `dimension_out` gets the declared dimension.
std::int64_t read_nodes(TextLines& in, plc::Plc& plc, int& dimension_out) {
  const std::int64_t n = count_field(in, 0, "number of points");
  const std::int64_t dim = in.size() > 1 ? in.integer(1) : 3;
  const std::int64_t nattr = in.size() > 2 ? count_field(in, 2, "number of attributes") : 0;
  const std::int64_t markers = in.size() > 3 ? in.integer(3) : 0;
  dimension_out = static_cast<int>(dim);
  if (dim != 3) in.fail("dimension " + std::to_string(dim) + ": the 3D reader needs 3");
  if (markers != 0 && markers != 1) in.fail("boundary marker flag must be 0 or 1, not " + std::to_string(markers));
  const std::size_t fields = 4 + static_cast<std::size_t>(nattr) + static_cast<std::size_t>(markers);
  plc.points.reserve(static_cast<std::size_t>(std::min(n, kReserveCap)));
  std::int64_t base = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    in.expect("point " + std::to_string(i + 1) + " of " + std::to_string(n));
    in.need(fields, "point number, x, y, z" + std::string(nattr ? ", attributes" : "") + (markers ? ", marker" : ""));
    const std::int64_t id = in.integer(0);
    if (i == 0) {
      if (id != 0 && id != 1) in.fail("the first point's number must be 0 or 1, not " + std::to_string(id));
      base = id;
    } else if (id != base + i) {
      in.fail("point number " + std::to_string(id) + " out of sequence (expected " + std::to_string(base + i) + ")");
    }
    plc.points.push_back({in.real(1), in.real(2), in.real(3)});
    if (markers) plc.point_markers.push_back(static_cast<std::int32_t>(in.integer(fields - 1)));
  }
  return base;
}

// Opens the .node file next to `path` (same base name), for a .poly/.smesh whose node list is empty.
std::int64_t read_sibling_nodes(const std::string& path, plc::Plc& plc) {
  const std::string node = std::filesystem::path(path).replace_extension(".node").string();
  TextLines in(node, read_file_bytes(node));
  in.expect("the node list header");
  int dim = 0;
  return read_nodes(in, plc, dim);
}

std::int64_t read_point_section(TextLines& in, plc::Plc& plc) {
  in.expect("the node list header");
  int dim = 0;
  if (in.integer(0) == 0) {
    if (in.size() > 1 && in.integer(1) != 3) in.fail("dimension " + shown(in.token(1)) + ": the 3D reader needs 3");
    return read_sibling_nodes(in.path(), plc);
  }
  return read_nodes(in, plc, dim);
}

VertexId vertex_field(const TextLines& in, std::size_t i, std::int64_t base, std::size_t npoints) {
  const std::int64_t v = in.integer(i) - base;
  if (v < 0 || v >= static_cast<std::int64_t>(npoints)) {
    in.fail("vertex " + shown(in.token(i)) + " out of range (points " + std::to_string(base) + ".." +
            std::to_string(base + static_cast<std::int64_t>(npoints) - 1) + ")");
  }
  return static_cast<VertexId>(v);
}

Point3 point_fields(const TextLines& in, std::size_t first) { return {in.real(first), in.real(first + 1), in.real(first + 2)}; }

// A facet made only of 2-corner polygons bounds no area: its polygons are free segments.
bool move_segments_out(plc::Facet& f, plc::Plc& plc) {
  if (!f.holes.empty()) return false;
  for (const auto& poly : f.polygons) {
    if (poly.size() > 2) return false;
  }
  for (const auto& poly : f.polygons) {
    if (poly.size() == 2) plc.segments.push_back({poly[0], poly[1]});
  }
  return true;
}

// The .poly facet list: each facet a line "polygons [holes] [marker]", its polygons, its hole points.
void read_poly_facets(TextLines& in, plc::Plc& plc, std::int64_t base) {
  in.expect("the facet list header");
  const std::int64_t nf = count_field(in, 0, "number of facets");
  const bool markers = in.size() > 1 && in.integer(1) != 0;
  plc.facets.reserve(static_cast<std::size_t>(std::min(nf, kReserveCap)));
  for (std::int64_t i = 0; i < nf; ++i) {
    in.expect("facet " + std::to_string(i + base) + " (" + std::to_string(i + 1) + " of " + std::to_string(nf) + ")");
    plc::Facet f;
    const std::int64_t np = count_field(in, 0, "number of polygons");
    const std::int64_t nh = in.size() > 1 ? count_field(in, 1, "number of holes") : 0;
    if (markers && in.size() > 2) f.marker = static_cast<std::int32_t>(in.integer(2));
    if (np == 0) in.fail("facet " + std::to_string(i + base) + " has no polygon");
    for (std::int64_t p = 0; p < np; ++p) {
      in.expect("polygon " + std::to_string(p + 1) + " of facet " + std::to_string(i + base));
      const std::int64_t k = count_field(in, 0, "number of corners");
      if (k == 0) in.fail("a polygon needs at least one corner");
      if (static_cast<std::int64_t>(in.size()) < k + 1) in.need(static_cast<std::size_t>(k) + 1, "corner count and corners");
      std::vector<VertexId> poly(static_cast<std::size_t>(k));
      for (std::int64_t c = 0; c < k; ++c) poly[c] = vertex_field(in, static_cast<std::size_t>(c + 1), base, plc.points.size());
      f.polygons.push_back(std::move(poly));
    }
    for (std::int64_t h = 0; h < nh; ++h) {
      in.expect("hole " + std::to_string(h + 1) + " of facet " + std::to_string(i + base));
      in.need(4, "hole number, x, y, z");
      f.holes.push_back(point_fields(in, 1));
    }
    if (!move_segments_out(f, plc)) plc.facets.push_back(std::move(f));
  }
}

// The .smesh facet list: one polygon per line, "corners v1 .. vk [marker]".
void read_smesh_facets(TextLines& in, plc::Plc& plc, std::int64_t base) {
  in.expect("the facet list header");
  const std::int64_t nf = count_field(in, 0, "number of facets");
  const bool markers = in.size() > 1 && in.integer(1) != 0;
  plc.facets.reserve(static_cast<std::size_t>(std::min(nf, kReserveCap)));
  for (std::int64_t i = 0; i < nf; ++i) {
    in.expect("facet " + std::to_string(i + 1) + " of " + std::to_string(nf));
    const std::int64_t k = count_field(in, 0, "number of corners");
    if (k < 3) in.fail("a facet needs at least 3 corners, not " + std::to_string(k));
    if (static_cast<std::int64_t>(in.size()) < k + 1) in.need(static_cast<std::size_t>(k) + 1, "corner count and corners");
    plc::Facet f;
    f.polygons.emplace_back(static_cast<std::size_t>(k));
    for (std::int64_t c = 0; c < k; ++c) {
      f.polygons[0][c] = vertex_field(in, static_cast<std::size_t>(c + 1), base, plc.points.size());
    }
    if (markers && static_cast<std::int64_t>(in.size()) > k + 1) f.marker = static_cast<std::int32_t>(in.integer(k + 1));
    plc.facets.push_back(std::move(f));
  }
}

// Part 3 (volume holes) and part 4 (regions) of .poly and .smesh. TetGen's format calls part 3
// mandatory but TetGen itself reads a file that ends after the facets, so this reader does too.
void read_holes_and_regions(TextLines& in, plc::Plc& plc) {
  if (!in.next()) return;
  const std::int64_t nh = count_field(in, 0, "number of holes");
  for (std::int64_t h = 0; h < nh; ++h) {
    in.expect("volume hole " + std::to_string(h + 1) + " of " + std::to_string(nh));
    in.need(4, "hole number, x, y, z");
    plc.holes.push_back(point_fields(in, 1));
  }
  if (!in.next()) return;
  const std::int64_t nr = count_field(in, 0, "number of regions");
  for (std::int64_t r = 0; r < nr; ++r) {
    in.expect("region " + std::to_string(r + 1) + " of " + std::to_string(nr));
    in.need(5, "region number, x, y, z, attribute");
    plc::Region reg;
    reg.point = point_fields(in, 1);
    reg.attribute = in.real(4);
    if (in.size() > 5) reg.max_volume = in.real(5);
    plc.regions.push_back(reg);
  }
}

TextLines open_lines(const std::string& path) { return TextLines(path, read_file_bytes(path)); }

}  // namespace

plc::Plc read_node(const std::string& path) {
  plc::Plc plc;
  plc.source = path;
  TextLines in = open_lines(path);
  in.expect("the node list header");
  int dim = 0;
  read_nodes(in, plc, dim);
  return plc;
}

plc::Plc read_poly(const std::string& path) {
  plc::Plc plc;
  plc.source = path;
  TextLines in = open_lines(path);
  const std::int64_t base = read_point_section(in, plc);
  read_poly_facets(in, plc, base);
  read_holes_and_regions(in, plc);
  return plc;
}

plc::Plc read_smesh(const std::string& path) {
  plc::Plc plc;
  plc.source = path;
  TextLines in = open_lines(path);
  const std::int64_t base = read_point_section(in, plc);
  read_smesh_facets(in, plc, base);
  read_holes_and_regions(in, plc);
  return plc;
}

int poly_dimension(const std::string& path) {
  TextLines in = open_lines(path);
  if (!in.next()) fail_malformed(path, 0, "empty file: no node list header with the dimension");
  if (in.size() < 2) in.fail("the node list header has no dimension field");
  const std::int64_t dim = in.integer(1);
  if (dim != 2 && dim != 3) in.fail("dimension " + std::to_string(dim) + " (expected 2 or 3)");
  return static_cast<int>(dim);
}

namespace {

std::string mesh_base(const std::string& path) {
  const std::string e = lower_ext(path);
  if (e == "node" || e == "ele" || e == "face") return path.substr(0, path.size() - e.size() - 1);
  return path;
}

void read_ele(const std::string& path, std::int64_t base, tet::TetMesh& m) {
  TextLines in = open_lines(path);
  in.expect("the element list header");
  const std::int64_t nt = count_field(in, 0, "number of tetrahedra");
  const std::int64_t per = in.size() > 1 ? in.integer(1) : 4;
  const std::int64_t nattr = in.size() > 2 ? count_field(in, 2, "number of attributes") : 0;
  if (per != 4 && per != 10) in.fail("nodes per tetrahedron must be 4 or 10, not " + std::to_string(per));
  m.tets.reserve(static_cast<std::size_t>(std::min(nt, kReserveCap)));
  for (std::int64_t i = 0; i < nt; ++i) {
    in.expect("tetrahedron " + std::to_string(i + 1) + " of " + std::to_string(nt));
    in.need(static_cast<std::size_t>(1 + per + nattr), "number, nodes" + std::string(nattr ? ", attributes" : ""));
    std::array<VertexId, 4> t{};
    for (int k = 0; k < 4; ++k) t[k] = vertex_field(in, static_cast<std::size_t>(1 + k), base, m.points.size());
    const int s = predicates::orient3d(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]);
    if (s == 0) {
      throw Error(ExitCode::kInvalidGeometry, path + ":" + std::to_string(in.line()) + ": tetrahedron " +
                                                  shown(in.token(0)) + " has zero volume");
    }
    if (s < 0) std::swap(t[0], t[1]);
    m.tets.push_back(t);
    m.tet_material.push_back(nattr ? static_cast<std::int32_t>(std::llround(in.real(static_cast<std::size_t>(1 + per)))) : 0);
  }
}

void read_face(const std::string& path, std::int64_t base, tet::TetMesh& m) {
  TextLines in = open_lines(path);
  in.expect("the face list header");
  const std::int64_t nf = count_field(in, 0, "number of faces");
  const bool markers = in.size() > 1 && in.integer(1) != 0;
  for (std::int64_t i = 0; i < nf; ++i) {
    in.expect("face " + std::to_string(i + 1) + " of " + std::to_string(nf));
    in.need(markers ? 5 : 4, markers ? "number, 3 nodes, marker" : "number, 3 nodes");
    std::array<VertexId, 3> f{};
    for (int k = 0; k < 3; ++k) f[k] = vertex_field(in, static_cast<std::size_t>(1 + k), base, m.points.size());
    m.faces.push_back(f);
    m.face_marker.push_back(markers ? static_cast<std::int32_t>(in.integer(4)) : 0);
  }
}

}  // namespace

tet::TetMesh read_tetgen_mesh(const std::string& path) {
  const std::string base_name = mesh_base(path);
  plc::Plc nodes;
  nodes.source = base_name + ".node";
  TextLines in = open_lines(nodes.source);
  in.expect("the node list header");
  int dim = 0;
  const std::int64_t base = read_nodes(in, nodes, dim);
  tet::TetMesh m;
  m.points = std::move(nodes.points);
  read_ele(base_name + ".ele", base, m);
  if (std::filesystem::exists(base_name + ".face")) read_face(base_name + ".face", base, m);
  return m;
}

}  // namespace fdr::tetio
