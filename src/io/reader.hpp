// Mesh readers (2dm, fort.14, SCHISM gr3/ll, Telemac Selafin, msh 4.1 ASCII, Triangle node/ele, fdrmesh
// GeoPackage) for `fdrmesh quality` and tests.
#pragma once
#include <string>
#include "mesh/mesh_view.hpp"

namespace fdr::io {

struct ReadOptions {
  // fort.14 stores depth positive down: z = -DP by default; false reads z = DP.
  bool fort14_depth_positive_down = true;
};

// Reads a mesh; the format is chosen by extension as in format_from_path (UGRID .nc, *_net.nc and
// .vtu are write-only; .gr3/.ll depths are always positive down). The result has origin (0,0) and world coordinates as vertices, so coordinates read
// back bit-exactly. Boundary chains become `edges` (marker = EdgeKind, part = chain/nodestring id).
// An msh written on the sphere (a --global run's) is read back in lon/lat degrees with the
// elevation of its $NodeData "z", as its fort.14 reads.
// Missing/unopenable file -> Error(kInputUnreadable); malformed content ->
// Error(kInputMalformed, "<file>:<line>: ...").
mesh::MeshView read_mesh(const std::string& path, const ReadOptions& options = {});

}  // namespace fdr::io
