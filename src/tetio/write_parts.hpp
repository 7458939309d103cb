// The writers' first half: each format written completely to temporary files that are not yet
// committed, so that several outputs of one run can be committed as one (write_tets_all).
#pragma once
#include <memory>
#include <string>
#include <vector>
#include "base/out_file.hpp"
#include "tet/tet_mesh.hpp"
#include "tetio/write_tets.hpp"

namespace fdr::tetio {

using Written = std::vector<std::unique_ptr<OutFile>>;

Written prepare_vtu(const std::string& path, const tet::TetMesh& mesh, VtuEncoding encoding);
Written prepare_msh(const std::string& path, const tet::TetMesh& mesh);
Written prepare_tetgen(const std::string& path, const tet::TetMesh& mesh);

// Commits every file of `parts` as one (commit_outputs).
void commit_written(Written& parts);

}  // namespace fdr::tetio
