// The 3D writer chosen by extension, and the consistency check every writer runs first.
#include "tetio/write_tets.hpp"

#include "base/error.hpp"
#include "base/path_util.hpp"

namespace fdr::tetio {
namespace {

[[noreturn]] void fail_internal(const std::string& what) {
  throw Error(ExitCode::kInternal, "3D mesh to write is inconsistent: " + what);
}

template <std::size_t N>
void check_ids(const std::vector<std::array<VertexId, N>>& items, std::size_t npoints, const char* what) {
  for (std::size_t i = 0; i < items.size(); ++i) {
    for (VertexId v : items[i]) {
      if (static_cast<std::size_t>(v) >= npoints) {
        fail_internal(std::string(what) + " " + std::to_string(i) + " has vertex " + std::to_string(v) +
                      " of " + std::to_string(npoints));
      }
    }
  }
}

}  // namespace

void check_mesh_arrays(const tet::TetMesh& m) {
  if (m.tet_material.size() != m.tets.size()) fail_internal("tet_material has " + std::to_string(m.tet_material.size()) + " values for " + std::to_string(m.tets.size()) + " tetrahedra");
  if (m.face_marker.size() != m.faces.size()) fail_internal("face_marker length differs from faces");
  if (m.edge_marker.size() != m.edges.size()) fail_internal("edge_marker length differs from edges");
  for (const auto& [name, values] : m.cell_fields) {
    if (values.size() != m.tets.size()) fail_internal("cell field '" + name + "' has " + std::to_string(values.size()) + " values");
  }
  check_ids(m.tets, m.points.size(), "tetrahedron");
  check_ids(m.faces, m.points.size(), "face");
  check_ids(m.edges, m.points.size(), "edge");
}

void write_tets(const std::string& path, const tet::TetMesh& mesh) {
  const std::string e = lower_ext(path);
  if (e == "vtu") return write_vtu(path, mesh);
  if (e == "msh") return write_msh(path, mesh);
  if (e == "node" || e == "ele") return write_tetgen(path, mesh);
  throw Error(ExitCode::kUsage, path + ": unknown 3D output format '." + e + "' (expected .vtu, .msh, .node or .ele)");
}

}  // namespace fdr::tetio
