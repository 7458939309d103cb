// Wells (boreholes) in a terrain volume: vertical PLC segments at a TIN vertex between two
// elevations, clipped to the top and the base, and the spacing cap that refines around them.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>
#include "base/point3.hpp"
#include "base/types.hpp"
#include "sizing/spacing3d.hpp"
#include "terrain/surfaces.hpp"
#include "terrain/terrain_plc.hpp"

namespace fdr::terrain {

// The depth range of a well as its source gives it: elevations (metres, positive up) or depths
// below the DEM at the well (metres, positive down).
enum class WellRangeKind { kElevation, kDepth };

// One well as read: where it is (local frame), its range, and what messages call it.
struct Well {
  std::string name;        // its `name` attribute, else "FID n"
  std::string where;       // "FILE: layer 'L', feature FID n (name) at (x, y)" in its source CRS, for messages
  Point2 xy;               // local frame
  WellRangeKind kind = WellRangeKind::kElevation;
  double upper = 0;        // the upper end: elevation, or depth (the smaller depth)
  double lower = 0;        // the lower end: elevation, or depth (the larger depth)
};

// A well placed in the volume: its TIN vertex and its ends as elevations, top >= hi > lo >= base.
struct WellColumn {
  std::string name;
  VertexId tin_vertex = 0;
  double hi = 0, lo = 0;
};

// What place_well did to the well's range: ends clipped to the top or the base, ends moved onto a
// surface nearer than the snap distance.
struct WellRepairs {
  bool clipped_top = false, clipped_base = false;
  int snapped = 0;
};

// The well's range as elevations at its column, clipped to [base, top] (a listed repair), with
// an end nearer than `snap` to one of the column's surface elevations (`column`, from the top
// down) moved onto it, so the mesh need not resolve the gap. Throws Error(kInvalidGeometry)
// naming w.where when the range lies outside [base, top] or is empty.
WellColumn place_well(const Well& w, VertexId tin_vertex, const std::vector<double>& column, double snap,
                      WellRepairs* repairs = nullptr);

// The elevations of every surface of the stack at TIN vertex v, from the top down.
std::vector<double> column_at(const std::vector<Surface>& stack, VertexId v);

// Adds every well to the PLC as free segments: the vertical from hi down to lo at its TIN vertex,
// split at every surface vertex between them (the well meets each horizon at its vertex there, so
// segment and facets meet at a vertex, never across). New vertices at ends that are on no surface.
// Returns, per well, its PLC vertex chain from the top down. Throws Error(kInvalidGeometry) for a
// well at a boundary vertex of the TIN (it would lie in a side wall).
std::vector<std::vector<VertexId>> add_well_segments(TerrainPlc& tp, const Tin& tin, const std::vector<Surface>& stack,
                                                     const std::vector<WellColumn>& wells);

// Caps the spacing grid at h on every node within one cell diagonal of a segment, so that the
// trilinear field is at most h on the segments themselves (every corner of a cell a segment
// crosses is within that distance); the caller gradient-limits afterwards.
void cap_near_segments(sizing::Grid3& g, const std::vector<std::array<Point3, 2>>& segments, double h);

}  // namespace fdr::terrain
