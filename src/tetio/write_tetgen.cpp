// TetGen mesh files: BASE.node, BASE.ele, BASE.face (and BASE.edge), committed together.
#include <memory>
#include "base/path_util.hpp"
#include "tetio/write_parts.hpp"

namespace fdr::tetio {
namespace {

std::int64_t n64(std::size_t v) { return static_cast<std::int64_t>(v); }
std::int64_t id(VertexId v) { return static_cast<std::int64_t>(v) + 1; }

void write_node(OutFile& out, const tet::TetMesh& m) {
  out.num(n64(m.points.size())).str(" 3 0 0\n");
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const Point3& p = m.points[i];
    out.num(n64(i + 1)).sp().num(p.x).sp().num(p.y).sp().num(p.z).nl();
  }
}

void write_ele(OutFile& out, const tet::TetMesh& m) {
  out.num(n64(m.tets.size())).str(" 4 1\n");
  for (std::size_t i = 0; i < m.tets.size(); ++i) {
    const auto& t = m.tets[i];
    out.num(n64(i + 1)).sp().num(id(t[0])).sp().num(id(t[1])).sp().num(id(t[2])).sp().num(id(t[3]));
    out.sp().num(static_cast<std::int64_t>(m.tet_material[i])).nl();
  }
}

void write_face(OutFile& out, const tet::TetMesh& m) {
  out.num(n64(m.faces.size())).str(" 1\n");
  for (std::size_t i = 0; i < m.faces.size(); ++i) {
    const auto& f = m.faces[i];
    out.num(n64(i + 1)).sp().num(id(f[0])).sp().num(id(f[1])).sp().num(id(f[2]));
    out.sp().num(static_cast<std::int64_t>(m.face_marker[i])).nl();
  }
}

void write_edge(OutFile& out, const tet::TetMesh& m) {
  out.num(n64(m.edges.size())).str(" 1\n");
  for (std::size_t i = 0; i < m.edges.size(); ++i) {
    const auto& e = m.edges[i];
    out.num(n64(i + 1)).sp().num(id(e[0])).sp().num(id(e[1])).sp().num(static_cast<std::int64_t>(m.edge_marker[i])).nl();
  }
}

}  // namespace

Written prepare_tetgen(const std::string& path, const tet::TetMesh& m) {
  check_mesh_arrays(m);
  const std::string e = lower_ext(path);
  const std::string base = (e == "node" || e == "ele") ? path.substr(0, path.size() - e.size() - 1) : path;
  Written parts;
  write_node(*parts.emplace_back(std::make_unique<OutFile>(base + ".node")), m);
  write_ele(*parts.emplace_back(std::make_unique<OutFile>(base + ".ele")), m);
  write_face(*parts.emplace_back(std::make_unique<OutFile>(base + ".face")), m);
  if (!m.edges.empty()) write_edge(*parts.emplace_back(std::make_unique<OutFile>(base + ".edge")), m);
  return parts;
}

void write_tetgen(const std::string& path, const tet::TetMesh& mesh) {
  Written parts = prepare_tetgen(path, mesh);
  commit_written(parts);
}

}  // namespace fdr::tetio
