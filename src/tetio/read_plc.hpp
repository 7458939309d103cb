// The 3D input of a run, whatever its format: a plc::Plc read by the file's extension.
#pragma once
#include <string>
#include "plc/plc.hpp"

namespace fdr::tetio {

// Reads .poly (3D), .smesh, .node (a point set: no facets; the mesher takes its convex hull),
// .off, .stl or .ply (closed surfaces: one facet per face). The extension is matched without
// case. Unknown extension or unreadable file: Error(kInputUnreadable); bad content:
// Error(kInputMalformed, "<file>:<line>: ..."); an open or degenerate surface:
// Error(kInvalidGeometry). The geometric checks of the PLC itself (planarity, intersections,
// hole and region points) are plc::check's.
plc::Plc read_plc(const std::string& path);

// Whether read_plc takes this file's extension.
bool is_plc_path(const std::string& path);

}  // namespace fdr::tetio
