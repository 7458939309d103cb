// Land polygons of a global run in a plane, as GEOS (through OGR) needs them: rings as polygons,
// made valid, and pieces that meet united so that the land is a set of disjoint polygons.
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include <ogr_api.h>
#include <ogr_geometry.h>

#include "base/types.hpp"

namespace fdr::gis {

struct PreparedDeleter {
  void operator()(OGRPreparedGeometryH h) const { OGRDestroyPreparedGeometry(h); }
};
using PreparedPtr = std::unique_ptr<std::remove_pointer_t<OGRPreparedGeometryH>, PreparedDeleter>;

// Union-find: the root of i, halving the path.
inline std::size_t find_root(std::vector<std::size_t>& up, std::size_t i) {
  while (up[i] != i) i = up[i] = up[up[i]];
  return i;
}

// A ring in the plane (no closing repeat) as a polygon.
OGRPolygon plane_polygon(const std::vector<Point2>& ring);

// g's polygons, made valid first when GEOS finds g invalid (a projected ring touching itself);
// exit kInvalidGeometry naming `what` when that fails.
std::unique_ptr<OGRGeometry> valid_copy(const OGRGeometry& g, const std::string& what);

// The land pieces made disjoint: pieces that meet (envelopes overlapping, then GEOS Intersects)
// are united group by group, the parts of a polygon cut at the antimeridian among them.
std::vector<std::unique_ptr<OGRPolygon>> disjoint_land(std::vector<std::unique_ptr<OGRPolygon>> pieces,
                                                       const std::string& label);

// True when the lon/lat ring turns round a pole (its longitudes add up to +-360 degrees): it is
// no polygon of the lon/lat plane and cannot be clipped there.
bool winds_round_pole(const std::vector<LonLat>& ring);

}  // namespace fdr::gis
