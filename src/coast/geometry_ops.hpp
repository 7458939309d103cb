// The coast generalisation's adapter to GEOS (through OGR): every overlay, buffer and conversion
// the steps use, with the workarounds that keep GEOS fast and exact on large coasts (holes
// detached from overlays, unions only where pieces meet, differences traced by faces).
#pragma once
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <cpl_error.h>
#include <ogr_api.h>
#include <ogr_geometry.h>

#include "base/types.hpp"
#include "coast/generalise.hpp"

namespace fdr::coast {

using GeomPtr = std::unique_ptr<OGRGeometry>;
using OwnedPolygons = std::vector<std::unique_ptr<OGRPolygon>>;

// Quarter-circle segments of the buffers: the arcs are resampled to f afterwards, so a coarse
// polygon (15 degrees per chord, sagitta 0.9 % of r) is enough.
constexpr int kQuadSegs = 4;

// Silences GDAL's stderr messages on this thread while alive: failures surface as fdr::Error
// (checked) with CPLGetLastErrorMsg() in the message instead.
class GdalQuiet {
 public:
  GdalQuiet() { CPLPushErrorHandler(CPLQuietErrorHandler); }
  ~GdalQuiet() { CPLPopErrorHandler(); }
  GdalQuiet(const GdalQuiet&) = delete;
  GdalQuiet& operator=(const GdalQuiet&) = delete;
};

// g owned; throws Error(kInvalidGeometry) naming `what` when GEOS returned nothing.
GeomPtr checked(OGRGeometry* g, const char* what);

// The polygons of g (Polygon, MultiPolygon, collections), as owned copies.
void polygons_of(const OGRGeometry* g, OwnedPolygons& out);
// A multipolygon of ps (emptied).
std::unique_ptr<OGRMultiPolygon> multi(OwnedPolygons& ps);

// Exact key of a coordinate pair (bit patterns), for "is this one of W's vertices".
std::uint64_t point_key(double x, double y);

// A prepared geometry: fast repeated intersection tests against one polygon.
class Prepared {
 public:
  explicit Prepared(const OGRGeometry* g)
      : h_(OGRCreatePreparedGeometry(OGRGeometry::ToHandle(const_cast<OGRGeometry*>(g)))), g_(g) {}
  ~Prepared() {
    if (h_) OGRDestroyPreparedGeometry(h_);
  }
  Prepared(const Prepared&) = delete;
  Prepared& operator=(const Prepared&) = delete;
  bool intersects(const OGRGeometry* o) const {
    if (h_) return OGRPreparedGeometryIntersects(h_, OGRGeometry::ToHandle(const_cast<OGRGeometry*>(o)));
    return g_->Intersects(o);
  }
  bool contains(const OGRGeometry* o) const {
    if (h_) return OGRPreparedGeometryContains(h_, OGRGeometry::ToHandle(const_cast<OGRGeometry*>(o)));
    return g_->Contains(o);
  }

 private:
  OGRPreparedGeometryH h_;
  const OGRGeometry* g_;
};

// The union of polygon pieces, overlaid only where they meet (grown by `hair`). `family`
// (optional, one label per piece): pieces with the same label have disjoint interiors.
GeomPtr union_pieces(OwnedPolygons& ps, double hair, const char* what, const std::vector<int>* family = nullptr);

double area_of(const OGRGeometry* g);
// A point inside g (GEOS's point on surface; the centroid when that fails).
Point2 inside_point(const OGRGeometry* g);

// ps (emptied) with the holes (emptied) put into the polygon whose outer ring holds each (by its
// first vertex); the holes must lie inside ps and touch nothing.
GeomPtr with_holes(OwnedPolygons& ps, std::vector<std::unique_ptr<OGRLinearRing>>& holes, const char* what);

// b minus u, where u's polygons are disjoint (a union's pieces); those strictly inside b become
// holes without an overlay.
GeomPtr minus_disjoint(GeomPtr b, const OGRGeometry& u, const char* what);
// b minus the disjoint polygons of u that touch b's boundary, overlaid with b's nearby holes only.
GeomPtr minus_touching(GeomPtr b, const OGRGeometry& u, const char* what);

// g grown by r (shrunk for r < 0), ring by ring; near_repeats: g is an earlier buffer's output,
// its clusters of vertices within 1e-6 r are merged first.
GeomPtr offset(const OGRGeometry& g, double r, int quad_segs = kQuadSegs, bool near_repeats = false);
// open(g, r) = (g - r) + r. Empty when nothing of g is wider than 2r.
GeomPtr opening(const OGRGeometry& g, double r);

// The vertices two rings of g (or one ring twice) share: pinch points, where the water is zero
// wide. Ring closures do not count.
std::vector<Point2> pinch_points(const OGRGeometry* g);

// a - b for two polygonal geometries whose boundaries share most of their segments bit for bit,
// by the faces of the segments they do not share; `overlay`: by GEOS's overlay of the whole.
GeomPtr difference_by_faces(const OGRGeometry* a, const OGRGeometry* b, const char* what, bool overlay = false);
// a - b when b lies inside a and their boundaries run together: traced by
// pslg::contained_difference (null when that refuses or with `overlay`).
GeomPtr traced_difference(const OGRGeometry& a, const OGRGeometry& b, const char* what, bool overlay = false);
// traced_difference, GEOS's overlay when that gives nothing.
GeomPtr difference_contained(const OGRGeometry& a, const OGRGeometry& b, const char* what, bool overlay = false);

// Rebuilds every polygon of ps with the holes for which keep(hole, |area|) is true (called once
// per hole, in order); true when some hole was dropped.
template <class Keep>
bool filter_holes(OwnedPolygons& ps, Keep keep) {
  bool dropped = false;
  for (auto& p : ps) {
    if (p->getNumInteriorRings() == 0) continue;
    OGRPolygon q;
    q.addRing(const_cast<OGRLinearRing*>(p->getExteriorRing()));
    for (int k = 0; k < p->getNumInteriorRings(); ++k) {
      const OGRLinearRing* h = p->getInteriorRing(k);
      if (keep(h, std::fabs(h->get_Area()))) q.addRing(const_cast<OGRLinearRing*>(h));
      else dropped = true;
    }
    *p = q;
  }
  return dropped;
}

// An OGR ring from vertices without the closing repeat.
OGRLinearRing closed_ring(const std::vector<Point2>& ring);
// The polygon of rings (rings of fewer than 3 vertices left out).
OGRPolygon to_ogr(const Rings& rings);
// The vertices of r without the closing repeat and consecutive duplicates, counter-clockwise
// when ccw, else clockwise.
std::vector<Point2> ring_points(const OGRLinearRing* r, bool ccw);

// The rectangle of an envelope as a polygon (to clip by a box).
OGRPolygon box_polygon(const OGREnvelope& e);

}  // namespace fdr::coast
