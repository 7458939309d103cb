// The 3D input reader chosen by extension.
#include "tetio/read_plc.hpp"

#include "base/error.hpp"
#include "base/path_util.hpp"
#include "tetio/read_tetgen.hpp"
#include "tetio/surface.hpp"

namespace fdr::tetio {

bool is_plc_path(const std::string& path) {
  const std::string e = lower_ext(path);
  return e == "poly" || e == "smesh" || e == "node" || e == "off" || e == "stl" || e == "ply";
}

plc::Plc read_plc(const std::string& path) {
  const std::string e = lower_ext(path);
  if (e == "poly") return read_poly(path);
  if (e == "smesh") return read_smesh(path);
  if (e == "node") return read_node(path);
  if (e == "off") return read_off(path);
  if (e == "stl") return read_stl(path);
  if (e == "ply") return read_ply(path);
  throw Error(ExitCode::kInputUnreadable,
              path + ": unknown 3D input format '." + e + "' (expected .poly, .smesh, .node, .off, .stl or .ply)");
}

}  // namespace fdr::tetio
