// TetGen's input formats as a plc::Plc: .node (a point set), .poly (3D PLC) and .smesh (a PLC whose
// facets are single polygons), indices 0- or 1-based as the first point's number says.
#pragma once
#include <string>
#include "plc/plc.hpp"
#include "tet/tet_mesh.hpp"

namespace fdr::tetio {

plc::Plc read_node(const std::string& path);
plc::Plc read_poly(const std::string& path);
plc::Plc read_smesh(const std::string& path);

// The dimension a .poly file declares on its first data line (2 for Triangle's planar files, 3
// for TetGen's), so a caller can pick the 2D or the 3D mesher. Unreadable file:
// Error(kInputUnreadable); no or bad dimension line: Error(kInputMalformed).
int poly_dimension(const std::string& path);

// A TetGen mesh (BASE.node + BASE.ele, BASE.face when present): tetrahedra turned to positive
// volume, the first element attribute as material, face markers from the .face file. `path` is
// BASE or any of BASE.node / BASE.ele.
tet::TetMesh read_tetgen_mesh(const std::string& path);

}  // namespace fdr::tetio
