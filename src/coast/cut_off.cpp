// Step: cut-off water removal (cut_off.hpp).
#include "coast/cut_off.hpp"

#include <algorithm>

#include "coast/report.hpp"

namespace fdr::coast {
namespace {

// The input body (index into wps) that owns each piece of rps: the one holding its inner point,
// else the one holding most of its vertices, else the one it meets; -1: none (or one piece only).
std::vector<int> owners(const OwnedPolygons& wps, const OwnedPolygons& rps) {
  std::vector<int> owner(rps.size(), -1);
  std::vector<Point2> rin(rps.size());  // inner points, computed once
  std::vector<char> has_rin(rps.size(), 0);
  for (std::size_t i = 0; i < wps.size() && rps.size() > 1; ++i) {
    Prepared pw(wps[i].get());
    OGREnvelope we;
    wps[i]->getEnvelope(&we);
    for (std::size_t j = 0; j < rps.size(); ++j) {
      if (owner[j] >= 0) continue;
      if (!has_rin[j]) { rin[j] = inside_point(rps[j].get()); has_rin[j] = 1; }
      const Point2 q = rin[j];
      if (!(we.MinX <= q.x && q.x <= we.MaxX && we.MinY <= q.y && q.y <= we.MaxY)) continue;
      OGRPoint pt(q.x, q.y);
      if (pw.intersects(&pt)) owner[j] = static_cast<int>(i);
    }
  }
  // A piece whose inner point lies outside every input body (water the closing added between
  // land that was thinner than --close-width): its owner is the input body it overlaps most.
  for (std::size_t j = 0; j < rps.size() && rps.size() > 1; ++j) {
    if (owner[j] >= 0) continue;
    OGREnvelope re;
    rps[j]->getEnvelope(&re);
    // (by its vertices, most of which are input coast: an overlay with a large polygon is slow)
    int best = 0;
    const OGRLinearRing* ring = rps[j]->getExteriorRing();
    const int nv = ring->getNumPoints();
    for (std::size_t i = 0; i < wps.size(); ++i) {
      OGREnvelope we;
      wps[i]->getEnvelope(&we);
      if (!we.Intersects(re)) continue;
      Prepared pw(wps[i].get());
      int hits = 0;
      for (int k = 0; k < nv; k += std::max(1, nv / 16)) {
        OGRPoint pt(ring->getX(k), ring->getY(k));
        hits += pw.intersects(&pt);
      }
      if (hits > best) {
        best = hits;
        owner[j] = static_cast<int>(i);
      }
    }
    // (water the widening added: its vertices lie on former land; the body it meets owns it)
    for (std::size_t i = 0; i < wps.size() && owner[j] < 0; ++i) {
      OGREnvelope we;
      wps[i]->getEnvelope(&we);
      if (!we.Intersects(re)) continue;
      Prepared pw(wps[i].get());
      if (pw.intersects(rps[j].get())) owner[j] = static_cast<int>(i);
    }
  }
  return owner;
}

}  // namespace

GeomPtr remove_cut_off(GeomPtr R, const OGRGeometry& W0, const Options& o, Result& res) {
  std::vector<std::unique_ptr<OGRPolygon>> wps, rps;
  polygons_of(&W0, wps);
  polygons_of(R.get(), rps);
  const std::vector<int> owner = owners(wps, rps);
  std::vector<int> best(wps.size(), -1);
  for (std::size_t j = 0; j < rps.size(); ++j) {
    if (owner[j] < 0) continue;
    int& b = best[static_cast<std::size_t>(owner[j])];
    if (b < 0 || rps[j]->get_Area() > rps[static_cast<std::size_t>(b)]->get_Area()) b = static_cast<int>(j);
  }
  std::vector<std::unique_ptr<OGRPolygon>> kept;
  for (std::size_t j = 0; j < rps.size(); ++j) {
    if (owner[j] >= 0 && best[static_cast<std::size_t>(owner[j])] != static_cast<int>(j)) {
      const double a = rps[j]->get_Area();
      ++res.cut_off;
      res.cut_off_area += a;
      res.repairs.push_back({"cut_off_water_removed", inside_point(rps[j].get()), a,
                             "water body of " + num(a) + " m^2 joined to the rest only through a connection "
                             "narrower than " + num(o.min_feature) + " m (--min-feature); it was removed",
                             -1});
      continue;
    }
    kept.push_back(std::move(rps[j]));
  }
  R = multi(kept);
  return R;
}

}  // namespace fdr::coast
