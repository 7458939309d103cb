// Vector input: OGR layers (domain polygons or land + extent, open boundary, breaklines, points) -> PSLG.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>
#include "base/types.hpp"
#include "gis/crs.hpp"
#include "coast/generalise.hpp"
#include "pslg/clean.hpp"
#include "pslg/pslg.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::gis {

// One OGR source: a file (any OGR format), an optional layer name (default: the first layer)
// and an optional OGR SQL attribute filter (--where).
struct LayerRef {
  std::string path;
  std::string layer;
  std::string where;
  bool given() const { return !path.empty(); }
};

struct DomainOptions {
  LayerRef domain;          // polygons of the meshing domain (e.g. water); or use land + extent
  LayerRef land;            // land polygons subtracted from `extent` (needs `extent`)
  std::optional<std::array<double, 4>> extent;  // xmin, ymin, xmax, ymax
  // Global run: the sphere minus `land` (no extent), in the stereographic frame whose point at
  // infinity is this pole inside the land that bounds the ocean (gis/global_domain.hpp).
  std::optional<LonLat> global_pole;
  bool extent_in_lonlat = true;  // false: `extent` is in the land layer's CRS
  LayerRef open_boundary;   // lines on which boundary segments become EdgeKind::kOpen
  LayerRef breaklines;      // lines clipped to the domain, EdgeKind::kBreakline
  LayerRef points;          // points inside the domain become fixed vertices
  std::string s_srs;        // CRS for layers that have none (else such layers are kCrsError)
  std::string t_srs;        // working CRS; empty: automatic (choose_frame)
  // Geographic layers: segments spanning more than this many degrees of longitude or latitude
  // get points along their lon/lat line before projection (a box side follows its parallel);
  // 0: a segment is the chord between its projected ends, as GDAL and QGIS draw it.
  double densify_deg = 0;

  bool clean = true;        // run pslg::clean on the result
  double snap_distance_m = -1;  // < 0: default max(1e-6 * domain diameter, 0.01 m)
  // Tiny islands: rings with area < factor * f(c)^2 are dropped (pslg::CleanOptions); needs
  // `spacing` (called once the frame is known, returns f in the local frame). 0: keep all.
  double min_island_area_factor = 0;
  std::function<sizing::SizingPtr(const Frame&)> spacing;
  double simplify_factor = 0;     // off by default
  double simplify_tolerance_m = 0;
  // Coast generalisation (coast/generalise.hpp), called with the domain box in the local frame
  // once the frame is known; unset: the polygons are used as read.
  std::function<coast::Options(const Box2& local_box)> features;
};

// Where a PSLG segment `part` came from (index = Segment::part).
struct SourcePart {
  std::string file;
  std::string layer;
  std::int64_t fid = -1;   // OGR feature id
  std::string role;        // "outer ring", "hole", "open boundary", "breakline", "extent box"
  int ring = -1;           // ring index within the feature's polygon (0 = outer), -1 for lines
};

struct RepairRecord {
  pslg::Repair repair;     // repair.where converted to world (frame CRS) coordinates
  LonLat lonlat;           // the same place in WGS 84
};

struct GisCounts {
  std::size_t polygon_features = 0;  // domain features read (after --where)
  std::size_t polygons = 0;          // polygons (a MultiPolygon counts its members)
  std::size_t outer_rings = 0;
  std::size_t holes = 0;
  std::size_t boundary_segments = 0;  // before cleaning (after densification)
  // Long segments of geographic (lon/lat) layers split on reading: a straight lon/lat segment is
  // a curve in the working frame (a 46-degree box side as one chord crosses whole islands).
  std::size_t densified_segments = 0; // source segments (rings, open lines, breaklines) split
  std::size_t densify_points = 0;     // points inserted into them
  std::size_t long_chords = 0;        // lon/lat ring segments over 1 degree kept as chords (no --densify)
  std::size_t open_segments = 0;      // boundary segments marked kOpen (before cleaning)
  std::size_t open_parts = 0;         // maximal runs of open segments along the rings
  std::size_t open_features = 0;      // features read from the open-boundary layer
  std::size_t breakline_features = 0;
  std::size_t breakline_segments = 0; // after clipping, before cleaning
  std::size_t fixed_points = 0;       // points inside the domain
  std::size_t points_outside = 0;     // points dropped because they are outside the domain
  std::size_t repairs = 0;
};

struct GisInput {
  Frame frame;
  pslg::Pslg pslg;                    // local frame; pslg.origin = frame.origin()
  pslg::Pslg raw;                     // the same before pslg::clean
  // Domain polygons in the local frame, each polygon = rings (outer first, then holes), ring
  // vertices without the closing repeat. Use for area checks (not necessarily valid geometry).
  std::vector<std::vector<std::vector<Point2>>> domain_polygons;
  std::vector<std::vector<std::vector<Point2>>> input_polygons;  // as read, before the resolution filter
  double domain_area_m2 = 0;          // sum of signed ring areas (outer positive, holes negative)
  std::vector<SourcePart> parts;      // indexed by Segment::part
  std::vector<RepairRecord> repairs;
  std::vector<RepairRecord> feature_repairs;  // from the resolution filter (kept by clean_domain)
  coast::Result features;             // its figures (polygons cleared); input_pieces 0 when off
  GisCounts counts;
  double snap_distance_m = 0;         // the snap distance actually used
};

// Reads, projects and assembles the domain. Errors (fdr::Error):
//   kUsage           neither domain nor land+extent given, bad --where syntax
//   kInputUnreadable "<file>: cannot open", "<file>: no layer 'x' (layers: a, b)"
//   kInvalidGeometry no polygon features, wrong geometry type (file, layer, FID, coordinates),
//                    --where selecting nothing
//   kCrsError        layer without CRS and no s_srs, unknown t_srs/s_srs
GisInput read_domain(const DomainOptions& options);

// Runs pslg::clean on in.raw with `options` and replaces in.pslg / in.repairs.
void clean_domain(GisInput& in, const pslg::CleanOptions& options);

// Starts the resolution filter's deferred removed-water listing beside the caller (see
// coast::start_removed); finish_features takes it.
void start_features(GisInput& in);

// Adds the resolution filter's deferred removed-water listing (coast::Options::defer_removed)
// to in.features, in.feature_repairs and in.repairs (after the filter's other repairs, where
// they were listed before the listing could be deferred); nothing when none is pending.
void finish_features(GisInput& in);

}  // namespace fdr::gis
