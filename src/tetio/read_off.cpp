// Object File Format (.off): "OFF", counts "vertices faces edges", vertex lines, then face lines
// "n i1 .. in" (0-based, trailing colour values ignored). Comments start with '#'.
#include <algorithm>
#include "tetio/surface.hpp"
#include "tetio/text_lines.hpp"

namespace fdr::tetio {

plc::Plc read_off(const std::string& path) {
  TextLines in(path, read_file_bytes(path));
  in.expect("the OFF header");
  std::string_view head = in.token(0);
  if (head.size() < 3 || head.substr(head.size() - 3) != "OFF" || head.find('4') != std::string_view::npos ||
      head.find('n') != std::string_view::npos) {
    in.fail("not an OFF file: the first word is '" + shown(head) + "', expected OFF (or COFF, NOFF, STOFF)");
  }
  std::size_t first = 1;
  if (in.size() == 1) {
    in.expect("the counts line (vertices faces edges)");
    first = 0;
  }
  in.need(first + 2, "vertex and face counts");
  const std::int64_t nv = in.integer(first), nf = in.integer(first + 1);
  if (nv < 0 || nf < 0) in.fail("negative vertex or face count");
  Surface s;
  s.points.reserve(static_cast<std::size_t>(std::min<std::int64_t>(nv, 1 << 16)));
  for (std::int64_t i = 0; i < nv; ++i) {
    in.expect("vertex " + std::to_string(i) + " of " + std::to_string(nv));
    in.need(3, "x y z");
    s.points.push_back({in.real(0), in.real(1), in.real(2)});
  }
  for (std::int64_t f = 0; f < nf; ++f) {
    in.expect("face " + std::to_string(f) + " of " + std::to_string(nf));
    const std::int64_t k = in.integer(0);
    if (k < 3) in.fail("face " + std::to_string(f) + " has " + std::to_string(k) + " corners (at least 3)");
    if (static_cast<std::int64_t>(in.size()) < k + 1) in.need(static_cast<std::size_t>(k) + 1, "corner count and corners");
    std::vector<VertexId> face(static_cast<std::size_t>(k));
    for (std::int64_t c = 0; c < k; ++c) {
      const std::int64_t v = in.integer(static_cast<std::size_t>(c + 1));
      if (v < 0 || v >= nv) in.fail("vertex " + std::to_string(v) + " out of range (0.." + std::to_string(nv - 1) + ")");
      face[c] = static_cast<VertexId>(v);
    }
    s.faces.push_back(std::move(face));
  }
  return surface_to_plc(std::move(s), path);
}

}  // namespace fdr::tetio
