// Reading OGR layers for the vector input: features flattened to 2D with curves linearized, their
// coordinates checked, and the geometry helpers the input assembly shares (private to fdr_gis).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <ogr_geometry.h>
#include <ogr_spatialref.h>

#include "base/types.hpp"
#include "gis/vector_input.hpp"

namespace fdr::gis {

// v with `prec` decimals.
std::string num(double v, int prec = 6);
// "at (x, y)": the centre of g's envelope, for messages.
std::string where_str(const OGRGeometry* g);

// One feature's geometry, flattened to 2D and with curves linearized.
struct Feature {
  std::int64_t fid = -1;
  std::unique_ptr<OGRGeometry> geom;
};

struct LayerData {
  std::string file, layer;
  OGRSpatialReference srs;  // traditional GIS order
  std::vector<Feature> features;
  std::string label() const { return file + ": layer '" + layer + "'"; }
};

// The features of ref's layer (the first without a name) with a geometry, after its --where
// filter (`option` names it in messages), in its CRS or s_srs; every coordinate checked.
LayerData read_layer(const LayerRef& ref, const std::string& s_srs, const char* option);

// Appends the polygons in g (Polygon, MultiPolygon, collections of them) to out; returns the
// first geometry of another type, or nullptr.
const OGRGeometry* collect_polygons(const OGRGeometry* g, std::vector<const OGRPolygon*>& out);
// The same for lines (points in collections, by-products of intersections, are skipped).
const OGRGeometry* collect_lines(const OGRGeometry* g, std::vector<const OGRSimpleCurve*>& out);
// The vertices of c.
std::vector<Point2> curve_points(const OGRSimpleCurve* c);

}  // namespace fdr::gis
