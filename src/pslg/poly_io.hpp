// Triangle .poly / .node reading and writing (J. R. Shewchuk's documented file formats).
#pragma once
#include <string>
#include "pslg/pslg.hpp"

namespace fdr::pslg {

// Reads a .poly file: vertices (or, if its vertex count is 0, the sibling .node file), segments,
// holes and the optional regions section. '#' starts a comment; indices may start at 0 or 1
// (taken from the first vertex id; ids must then be consecutive). Vertex attributes are read and
// discarded. A comment line "# fdrmesh-origin X Y" (written by write_poly) sets Pslg::origin.
// Errors: missing/unreadable file -> Error(kInputUnreadable, "<file>: ..."); any malformed
// content -> Error(kInputMalformed, "<file>:<line>: <what>").
Pslg read_poly(const std::string& path);

// Reads a bare .node file (vertices and their markers only).
Pslg read_node(const std::string& path);

// Writes a .poly file (0-based, vertex markers if present, segment markers, holes, regions)
// atomically: to "<path>.tmp", then renamed. Coordinates are written with 17 significant
// digits, so read_poly(write_poly(g)) == g except Segment::part (not in the format, read as -1).
// Errors: Error(kOutputError, "<file>: ...").
void write_poly(const Pslg& pslg, const std::string& path);

}  // namespace fdr::pslg
