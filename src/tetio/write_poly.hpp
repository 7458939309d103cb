// A plc::Plc written as a TetGen .poly (e.g. a PLC built in code, for TetGen beside fdrmesh).
#pragma once
#include <string>
#include "plc/plc.hpp"

namespace fdr::tetio {

// TetGen .poly, 1-based: points (with markers when the PLC has them), facets (polygons, hole
// points, markers), volume holes, regions (attribute and volume bound). Free segments become
// facets of one 2-corner polygon each, which read_poly turns back into segments. All or nothing
// (base/out_file.hpp); vertex ids out of range are Error(kInternal) before anything is written.
void write_poly(const std::string& path, const plc::Plc& plc);

}  // namespace fdr::tetio
