// The coast generalisation's driver: the steps in order (generalise.hpp).
#include "coast/generalise.hpp"

#include <cmath>
#include <cstdio>
#include <unordered_set>

#include "base/error.hpp"
#include "coast/convex.hpp"
#include "coast/cut_off.hpp"
#include "coast/gap_closure.hpp"
#include "coast/geometry_ops.hpp"
#include "coast/islets.hpp"
#include "coast/narrow_gaps.hpp"
#include "coast/openings.hpp"
#include "coast/removed.hpp"
#include "coast/report.hpp"
#include "coast/restore.hpp"
#include "coast/tiny_edges.hpp"
#include "coast/tips.hpp"
#include "coast/union.hpp"
#include "coast/widen.hpp"

namespace fdr::coast {
namespace {

// The result polygons as rings (outer counter-clockwise, holes clockwise), with tiny edges
// dropped where the opening changed the coast; res gets them and output_area.
void output_polygons(const OwnedPolygons& outp, const OGRGeometry& W0, const Options& o, const IsletPlacer& islets,
                     Result& res) {
  // Input vertices (exact coordinates), for the tiny-edge clean-up.
  std::unordered_set<std::uint64_t> input_vertex;
  if (o.close_width > 0) {
    std::vector<std::unique_ptr<OGRPolygon>> wps;
    polygons_of(&W0, wps);
    for (const auto& w : wps)
      for (int k = -1; k < w->getNumInteriorRings(); ++k) {
        const OGRLinearRing* r = k < 0 ? w->getExteriorRing() : w->getInteriorRing(k);
        for (int i = 0; i < r->getNumPoints(); ++i) input_vertex.insert(point_key(r->getX(i), r->getY(i)));
      }
  }
  for (const auto& p : outp) {
    if (p->IsEmpty()) continue;
    Rings rings;
    rings.push_back(ring_points(p->getExteriorRing(), true));
    for (int k = 0; k < p->getNumInteriorRings(); ++k) rings.push_back(ring_points(p->getInteriorRing(k), false));
    if (rings[0].size() < 3) continue;
    if (o.close_width > 0) rings = drop_tiny_edges(std::move(rings), input_vertex, o.close_width / 4);
    res.output_area += std::fabs(signed_area(rings[0]));
    for (std::size_t k = 1; k < rings.size(); ++k) res.output_area -= std::fabs(signed_area(rings[k]));
    res.polygons.push_back(std::move(rings));
  }
  OGREnvelope inbox;
  W0.getEnvelope(&inbox);
  close_narrow_gaps(o, inbox, res);
  list_narrow_gaps(o, W0, res, &islets);
}

// Developer aid (kFilter): the input's size on stderr.
void print_input(const Polygons& input) {
  std::size_t nv = 0, nr = 0;
  for (const auto& rings : input)
    for (const auto& r : rings) {
      nv += r.size();
      ++nr;
    }
  std::fprintf(stderr, "filter input: %zu polygons, %zu rings, %zu vertices\n", input.size(), nr, nv);
}

// Developer aid (kFilterWkt, its value a path): the result as WKT, one polygon a line.
void dump_wkt(const OwnedPolygons& outp) {
  const char* path = debug::value(debug::Aid::kFilterWkt);
  if (!path) return;
  if (FILE* fp = std::fopen(path, "w")) {
    for (const auto& p : outp) {
      char* wkt = nullptr;
      p->exportToWkt(&wkt);
      std::fprintf(fp, "%s\n", wkt);
      CPLFree(wkt);
    }
    std::fclose(fp);
  }
}

}  // namespace

Options resolution_options(double hmin) {
  Options o;
  o.close_width = 0.15 * hmin;
  o.min_feature = 0.1 * hmin;
  o.widen_width = 0.65 * hmin;
  o.min_island_area = 0.3 * hmin * hmin;
  o.list_area = 0.5 * hmin * hmin;
  // A water body of more than a few hmin^2 behind a connection the openings close keeps that
  // connection, about one element across (reconnect.hpp).
  o.connect_area = 4 * hmin * hmin;
  o.connect_width = 0.9 * hmin;
  // Water left narrower than hmin/10 is closed unless a water body of more than 100 hmin^2 lies
  // behind it (gap_closure.hpp).
  o.gap_body_area = 100 * hmin * hmin;
  o.narrow_gap = 0.5 * hmin;  // narrow_gaps.hpp
  // Tips of land thinner than the close width stay unless other land is within hmin/2 of their
  // end (tips.hpp).
  o.tip_clearance = 0.5 * hmin;
  o.islet_side = 0.7 * hmin;  // islet_placer.hpp
  o.islet_shift = 0.4 * hmin;
  o.join_islets = true;
  // Every islet placement and join keeps hmin/2 from all other land, so that no element needs
  // to be narrower than that beside it; islets nearer than that to each other go as clusters.
  o.islet_clearance = 0.5 * hmin;
  return o;
}

Result generalise(const Polygons& input, const Options& o) {
  GdalQuiet quiet;
  // The steps' times under the filter's developer aid and as sub-stages of the read under the
  // stages' one (FDR_DEBUG_STAGES), beside the pipeline's stage table.
  FilterLaps filter_lap("filter");
  StepLaps stage_lap(debug::Aid::kStages, "stage read:");
  auto lap = [&](const char* step) {
    filter_lap(step);
    stage_lap(step);
  };
  Result res;
  res.close_width = o.close_width;
  if (filter_lap.on()) print_input(input);
  GeomPtr W = unite(input, res);
  lap("union");
  const GeomPtr W0(W->clone());  // the input water bodies (ownership of the result's pieces)
  IsletPlacer islets(o, res);
  W = replace_islets(std::move(W), islets, o, res);
  lap("islands");
  W = widen(std::move(W), o, res);
  lap("widen");
  W = add_islet_triangles(std::move(W), islets);
  lap("islets");
  W = close_thin_land(std::move(W), o, res);
  lap("closing");
  GeomPtr R = open_water(W, o, res);
  lap("openings");
  R = remove_cut_off(std::move(R), *W0, o, res);
  lap("owners");
  R = replace_remnants(std::move(R), islets, o, res);
  lap("remnants");
  // Back to the input's coordinates: buffers return the unchanged coast only up to rounding
  // (and a vertex with a slight turn as two close arc points). Every result vertex within 5 % of
  // --close-width of an input vertex takes that vertex's exact coordinates, so coast,
  // breaklines, open boundaries and fixed points still meet exactly where nothing was removed.
  if (o.close_width > 0) R = CoastRestorer(W0.get(), 0.05 * o.close_width, o.restore_full_rounds).restore(std::move(R));
  lap("restore");
  std::vector<std::unique_ptr<OGRPolygon>> outp;
  polygons_of(R.get(), outp);
  std::shared_ptr<GoneWater> gone;  // W0 - result, for the listing of removed water
  bool early = false;               // the listing starts at once (early_listing_rss)
  if (o.close_width > 0) {
    // Built here, not with W0: its index of W0's vertices would add to the openings' peak.
    snap_to_input(outp, Snapper(W0.get(), 0.05 * o.close_width));
    gone = start_gone(*W0, outp, o, &early);
    report_removed_bodies(*W0, *R, o, res);
  }
  lap("removed (start)");
  output_polygons(outp, *W0, o, islets, res);
  if (o.close_width > 0) list_removed(std::move(gone), early, o, res);
  lap("removed");
  res.output_pieces = res.polygons.size();
  dump_wkt(outp);
  if (res.polygons.empty())
    throw Error(ExitCode::kInvalidGeometry,
                "no water wider than " + num(o.close_width) +
                    " m (--close-width, default --hmin) is left; lower --hmin or give --close-width 0");
  return res;
}

Polygons offset_polygons(const Polygons& input, double d) {
  GdalQuiet quiet;
  auto m = std::make_unique<OGRMultiPolygon>();
  for (const auto& rings : input) {
    OGRPolygon p = to_ogr(rings);
    if (!p.IsEmpty()) m->addGeometry(&p);
  }
  GeomPtr g = offset(*m, d);
  std::vector<std::unique_ptr<OGRPolygon>> ps;
  polygons_of(g.get(), ps);
  Polygons out;
  for (const auto& p : ps) {
    Rings rings;
    rings.push_back(ring_points(p->getExteriorRing(), true));
    for (int k = 0; k < p->getNumInteriorRings(); ++k) rings.push_back(ring_points(p->getInteriorRing(k), false));
    if (rings[0].size() >= 3) out.push_back(std::move(rings));
  }
  return out;
}

}  // namespace fdr::coast
