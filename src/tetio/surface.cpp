// Closed polygonal surfaces as PLCs: exact merging of equal points and the closedness check.
#include "tetio/surface.hpp"

#include <algorithm>
#include <bit>
#include <sstream>
#include <unordered_map>
#include "base/error.hpp"

namespace fdr::tetio {
namespace {

struct Key {
  std::uint64_t x, y, z;
  bool operator==(const Key&) const = default;
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    std::uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
    h ^= (k.y + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2));
    h ^= (k.z * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2));
    return static_cast<std::size_t>(h);
  }
};
// +0 and -0 compare equal as coordinates, so they must hash alike.
std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v == 0 ? 0.0 : v); }

std::string coords(Point3 p) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

[[noreturn]] void fail_geometry(const std::string& path, const std::string& what) {
  throw Error(ExitCode::kInvalidGeometry, path + ": " + what);
}

// Every undirected edge must be used by an even number of faces (two for a manifold surface).
void check_closed(const plc::Plc& plc, const std::string& path) {
  struct Use {
    VertexId a, b;
    std::size_t face;
  };
  std::vector<Use> uses;
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const auto& poly = plc.facets[f].polygons[0];
    for (std::size_t i = 0; i < poly.size(); ++i) {
      VertexId a = poly[i], b = poly[(i + 1) % poly.size()];
      uses.push_back({std::min(a, b), std::max(a, b), f});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const Use& p, const Use& q) {
    return p.a != q.a ? p.a < q.a : p.b != q.b ? p.b < q.b : p.face < q.face;
  });
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b) ++j;
    if ((j - i) % 2 != 0) {
      fail_geometry(path, "the surface is not closed: the edge from " + coords(plc.points[uses[i].a]) + " to " +
                              coords(plc.points[uses[i].b]) + " belongs to " + std::to_string(j - i) +
                              " face(s), the first face " + std::to_string(uses[i].face));
    }
    i = j;
  }
}

}  // namespace

std::vector<VertexId> merge_equal_points(const std::vector<Point3>& points, std::vector<Point3>& distinct) {
  std::unordered_map<Key, VertexId, KeyHash> ids;
  ids.reserve(points.size());
  std::vector<VertexId> remap(points.size());
  distinct.clear();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point3 p = points[i];
    auto [it, fresh] = ids.try_emplace(Key{bits(p.x), bits(p.y), bits(p.z)}, static_cast<VertexId>(distinct.size()));
    if (fresh) distinct.push_back(p);
    remap[i] = it->second;
  }
  return remap;
}

plc::Plc surface_to_plc(Surface s, const std::string& path) {
  plc::Plc plc;
  plc.source = path;
  const std::vector<VertexId> remap = merge_equal_points(s.points, plc.points);
  plc.facets.reserve(s.faces.size());
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    plc::Facet facet;
    std::vector<VertexId> poly;
    poly.reserve(s.faces[f].size());
    for (VertexId v : s.faces[f]) poly.push_back(remap[v]);
    std::vector<VertexId> sorted = poly;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      const auto rep = *std::adjacent_find(sorted.begin(), sorted.end());
      fail_geometry(path, "face " + std::to_string(f) + " uses the point " + coords(plc.points[rep]) + " twice");
    }
    facet.polygons.push_back(std::move(poly));
    if (!s.face_marker.empty()) facet.marker = s.face_marker[f];
    plc.facets.push_back(std::move(facet));
  }
  if (plc.facets.empty()) fail_geometry(path, "the surface has no face");
  check_closed(plc, path);
  return plc;
}

}  // namespace fdr::tetio
