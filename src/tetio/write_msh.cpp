// Gmsh MSH 4.1 ASCII writer: entities and physical groups by material (volumes), face marker
// (surfaces) and edge marker (curves); all nodes in one block of the first entity.
#include <algorithm>
#include <map>
#include <span>
#include "base/point3.hpp"
#include "tetio/write_parts.hpp"

namespace fdr::tetio {
namespace {

// One entity of dimension `dim`: the elements (indices into the mesh's array) of one marker value.
struct Group {
  int dim = 0;
  int entity = 0;        // entity tag, 1.. within the dimension
  std::int32_t value = 0;  // material or marker
  std::int64_t physical = 0;
  std::string name;
  std::vector<std::size_t> items;
};

// Groups of equal values in increasing order of value; physical tag = value, shifted so that the
// smallest is at least 1.
std::vector<Group> groups_of(int dim, std::span<const std::int32_t> values, const std::vector<std::string>& names,
                             const char* prefix) {
  std::map<std::int32_t, std::vector<std::size_t>> by_value;
  for (std::size_t i = 0; i < values.size(); ++i) by_value[values[i]].push_back(i);
  std::vector<Group> out;
  if (by_value.empty()) return out;
  const std::int64_t shift = by_value.begin()->first >= 1 ? 0 : 1 - static_cast<std::int64_t>(by_value.begin()->first);
  for (auto& [v, items] : by_value) {
    Group g;
    g.dim = dim;
    g.entity = static_cast<int>(out.size()) + 1;
    g.value = v;
    g.physical = v + shift;
    const bool named = v >= 0 && static_cast<std::size_t>(v) < names.size() && !names[v].empty();
    g.name = named ? names[v] : prefix + std::to_string(v);
    g.items = std::move(items);
    out.push_back(std::move(g));
  }
  return out;
}

template <std::size_t N>
Box3 box_of(const Group& g, const std::vector<std::array<VertexId, N>>& elems, const std::vector<Point3>& pts) {
  Box3 b;
  for (std::size_t i : g.items) {
    for (VertexId v : elems[i]) b.add(pts[v]);
  }
  return b;
}

// A Gmsh quoted name: a double quote inside would end the string, so it becomes a single quote.
std::string quoted(std::string s) {
  std::replace(s.begin(), s.end(), '"', '\'');
  return "\"" + s + "\"";
}

void write_physical_names(OutFile& out, const std::vector<const std::vector<Group>*>& all) {
  std::int64_t n = 0;
  for (const auto* gs : all) n += static_cast<std::int64_t>(gs->size());
  out.str("$PhysicalNames\n").num(n).nl();
  for (const auto* gs : all) {
    for (const Group& g : *gs) out.num(static_cast<std::int64_t>(g.dim)).sp().num(g.physical).sp().str(quoted(g.name)).nl();
  }
  out.str("$EndPhysicalNames\n");
}

void write_entity(OutFile& out, const Group& g, const Box3& b) {
  out.num(static_cast<std::int64_t>(g.entity));
  for (double v : {b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z}) out.sp().num(v);
  out.str(" 1 ").num(g.physical).str(" 0\n");  // one physical tag, no bounding entities
}

template <std::size_t N>
void write_element_blocks(OutFile& out, const std::vector<Group>& groups, const std::vector<std::array<VertexId, N>>& elems,
                          int gmsh_type, std::int64_t& tag) {
  for (const Group& g : groups) {
    out.num(static_cast<std::int64_t>(g.dim)).sp().num(static_cast<std::int64_t>(g.entity)).sp();
    out.num(static_cast<std::int64_t>(gmsh_type)).sp().num(static_cast<std::int64_t>(g.items.size())).nl();
    for (std::size_t i : g.items) {
      out.num(tag++);
      for (VertexId v : elems[i]) out.sp().num(static_cast<std::int64_t>(v) + 1);
      out.nl();
    }
  }
}

void write_nodes(OutFile& out, const std::vector<Point3>& pts, const Group* host) {
  const std::int64_t n = host ? static_cast<std::int64_t>(pts.size()) : 0;
  out.str("$Nodes\n").num(std::int64_t{host ? 1 : 0}).sp().num(n).sp().num(std::int64_t{n ? 1 : 0}).sp().num(n).nl();
  if (host) {
    out.num(static_cast<std::int64_t>(host->dim)).sp().num(static_cast<std::int64_t>(host->entity)).str(" 0 ").num(n).nl();
    for (std::int64_t i = 1; i <= n; ++i) out.num(i).nl();
    for (const Point3& p : pts) out.num(p.x).sp().num(p.y).sp().num(p.z).nl();
  }
  out.str("$EndNodes\n");
}

}  // namespace

Written prepare_msh(const std::string& path, const tet::TetMesh& m) {
  check_mesh_arrays(m);
  const auto vols = groups_of(3, m.tet_material, m.material_names, "material_");
  const auto surfs = groups_of(2, m.face_marker, m.marker_names, "marker_");
  const auto curves = groups_of(1, m.edge_marker, m.marker_names, "marker_");
  Written parts;
  OutFile& out = *parts.emplace_back(std::make_unique<OutFile>(path));
  out.str("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
  write_physical_names(out, {&curves, &surfs, &vols});
  out.str("$Entities\n0 ").num(static_cast<std::int64_t>(curves.size())).sp().num(static_cast<std::int64_t>(surfs.size()));
  out.sp().num(static_cast<std::int64_t>(vols.size())).nl();
  for (const Group& g : curves) write_entity(out, g, box_of(g, m.edges, m.points));
  for (const Group& g : surfs) write_entity(out, g, box_of(g, m.faces, m.points));
  for (const Group& g : vols) write_entity(out, g, box_of(g, m.tets, m.points));
  out.str("$EndEntities\n");
  const Group* host = !vols.empty() ? &vols[0] : !surfs.empty() ? &surfs[0] : !curves.empty() ? &curves[0] : nullptr;
  write_nodes(out, m.points, host);
  const std::int64_t ne = static_cast<std::int64_t>(m.edges.size() + m.faces.size() + m.tets.size());
  const std::int64_t nblocks = static_cast<std::int64_t>(curves.size() + surfs.size() + vols.size());
  out.str("$Elements\n").num(nblocks).sp().num(ne).sp().num(std::int64_t{ne ? 1 : 0}).sp().num(ne).nl();
  std::int64_t tag = 1;
  write_element_blocks(out, curves, m.edges, 1, tag);
  write_element_blocks(out, surfs, m.faces, 2, tag);
  write_element_blocks(out, vols, m.tets, 4, tag);
  out.str("$EndElements\n");
  return parts;
}

void write_msh(const std::string& path, const tet::TetMesh& mesh) {
  Written parts = prepare_msh(path, mesh);
  commit_written(parts);
}

}  // namespace fdr::tetio
