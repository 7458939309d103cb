// Step: cut-off water removal (cut_off.hpp).
#include "coast/cut_off.hpp"

#include <algorithm>

#include "coast/reconnect.hpp"
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

// The connection of the cut-off `piece` to `main` (both of `body`) widened to connect_width
// (reconnect.hpp) and reported; null when none is found or it would meet other water.
GeomPtr reconnect(const OGRPolygon& body, const OGRPolygon& piece, const OGRPolygon& main,
                  const std::vector<const OGRPolygon*>& others, const OGREnvelope& inbox, const Options& o,
                  Result& res) {
  const double hair = 1e-3 * (o.close_width > 0 ? o.close_width : o.connect_width);
  const GeomPtr lost = lost_connection(body, piece, main, 2 * o.connect_width, hair);
  if (!lost) return nullptr;
  GeomPtr c = widened_connection(*lost, o.connect_width, inbox, others);
  if (!c) return nullptr;
  const double a = piece.get_Area();
  ++res.reconnected;
  res.repairs.push_back({"water_connection_widened", inside_point(lost.get()), a,
                         "water body of " + num(a) + " m^2 joined to the rest only through a connection narrower than " +
                             num(o.min_feature) + " m (--min-feature) is kept: the connection (" +
                             num(area_of(lost.get())) +
                             " m^2 of water) was widened to at least " + num(o.connect_width) + " m",
                         -1});
  return c;
}

}  // namespace

GeomPtr remove_cut_off(GeomPtr R, const OGRGeometry& W0, const Options& o, Result& res) {
  FilterLaps lap("  cut off");
  std::vector<std::unique_ptr<OGRPolygon>> wps, rps;
  polygons_of(&W0, wps);
  polygons_of(R.get(), rps);
  const std::vector<int> owner = owners(wps, rps);
  lap("owners");
  std::vector<int> best(wps.size(), -1);
  for (std::size_t j = 0; j < rps.size(); ++j) {
    if (owner[j] < 0) continue;
    int& b = best[static_cast<std::size_t>(owner[j])];
    if (b < 0 || rps[j]->get_Area() > rps[static_cast<std::size_t>(b)]->get_Area()) b = static_cast<int>(j);
  }
  OGREnvelope inbox;
  W0.getEnvelope(&inbox);
  // Decided first, moved after: the reconnections read the main pieces and the other bodies.
  std::vector<char> keep(rps.size(), 1);
  std::vector<std::unique_ptr<OGRPolygon>> kept, corridors;
  for (std::size_t j = 0; j < rps.size(); ++j) {
    if (owner[j] < 0 || best[static_cast<std::size_t>(owner[j])] == static_cast<int>(j)) continue;
    const double a = rps[j]->get_Area();
    const std::size_t oj = static_cast<std::size_t>(owner[j]);
    if (o.connect_area > 0 && o.connect_width > 0 && !(a < o.connect_area)) {
      std::vector<const OGRPolygon*> others;  // water of the other input bodies
      for (std::size_t k = 0; k < rps.size(); ++k)
        if (owner[k] >= 0 && owner[k] != owner[j]) others.push_back(rps[k].get());
      if (GeomPtr c = reconnect(*wps[oj], *rps[j], *rps[static_cast<std::size_t>(best[oj])], others, inbox, o, res)) {
        polygons_of(c.get(), corridors);
        continue;
      }
    }
    keep[j] = 0;
    ++res.cut_off;
    res.cut_off_area += a;
    res.repairs.push_back({"cut_off_water_removed", inside_point(rps[j].get()), a,
                           "water body of " + num(a) + " m^2 joined to the rest only through a connection "
                           "narrower than " + num(o.min_feature) + " m (--min-feature); it was removed",
                           -1});
  }
  for (std::size_t j = 0; j < rps.size(); ++j)
    if (keep[j]) kept.push_back(std::move(rps[j]));
  lap("reconnect");
  if (corridors.empty()) return multi(kept);
  const double before = [&] {
    double s = 0;
    for (const auto& k : kept) s += k->get_Area();
    return s;
  }();
  for (auto& c : corridors) kept.push_back(std::move(c));
  GeomPtr out = union_pieces(kept, std::max(1e-6 * o.connect_width, 1e-9), "water with widened connections");
  res.reconnected_area += std::max(0.0, area_of(out.get()) - before);
  lap("union");
  return out;
}

}  // namespace fdr::coast
