// The 3D writer chosen by extension, and the consistency check every writer runs first.
#include "tetio/write_tets.hpp"
#include "tetio/write_parts.hpp"

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

bool is_tets_output_path(const std::string& path) {
  const std::string e = lower_ext(path);
  return e == "vtu" || e == "msh" || e == "node" || e == "ele";
}

namespace {

[[noreturn]] void fail_format(const std::string& path) {
  throw Error(ExitCode::kUsage,
              path + ": unknown 3D output format '." + lower_ext(path) + "' (expected .vtu, .msh, .node or .ele)");
}

Written prepare(const std::string& path, const tet::TetMesh& mesh, VtuEncoding encoding) {
  const std::string e = lower_ext(path);
  if (e == "vtu") return prepare_vtu(path, mesh, encoding);
  if (e == "msh") return prepare_msh(path, mesh);
  if (e == "node" || e == "ele") return prepare_tetgen(path, mesh);
  fail_format(path);
}

}  // namespace

void commit_written(Written& parts) {
  std::vector<OutFile*> files;
  for (auto& f : parts) files.push_back(f.get());
  commit_outputs(files);
}

void write_tets(const std::string& path, const tet::TetMesh& mesh) { write_tets_all({path}, mesh); }

void write_tets_all(const std::vector<std::string>& paths, const tet::TetMesh& mesh, VtuEncoding encoding) {
  for (const std::string& p : paths) {
    if (!is_tets_output_path(p)) fail_format(p);  // before anything is written
  }
  Written all;
  for (const std::string& p : paths) {
    for (auto& f : prepare(p, mesh, encoding)) all.push_back(std::move(f));
  }
  commit_written(all);
}

}  // namespace fdr::tetio
