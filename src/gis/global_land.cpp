// Land pieces in a plane for GEOS: polygons, valid copies, pieces that meet united
// (global_land.hpp).
#include "gis/global_land.hpp"

#include <algorithm>
#include <cmath>

#include <cpl_error.h>

#include "base/error.hpp"
#include "gis/global_domain.hpp"
#include "gis/vector_layers.hpp"

namespace fdr::gis {

OGRPolygon plane_polygon(const std::vector<Point2>& ring) {
  OGRLinearRing r;
  for (const Point2& p : ring) r.addPoint(p.x, p.y);
  r.addPoint(ring[0].x, ring[0].y);
  OGRPolygon poly;
  poly.addRing(&r);
  return poly;
}

std::unique_ptr<OGRGeometry> valid_copy(const OGRGeometry& g, const std::string& what) {
  if (g.IsValid()) return std::unique_ptr<OGRGeometry>(g.clone());
  std::unique_ptr<OGRGeometry> v(g.MakeValid());
  if (!v) throw Error(ExitCode::kInvalidGeometry, what + ": cannot make it valid: " + CPLGetLastErrorMsg());
  return v;
}

// The land pieces made disjoint: pieces that meet (envelopes overlapping, then GEOS Intersects)
// are united group by group, the parts of a polygon cut at the antimeridian among them. Why not
// one union of everything: nearly all pieces meet no other, and a union of thousands of
// disjoint polygons costs seconds for nothing.
std::vector<std::unique_ptr<OGRPolygon>> disjoint_land(std::vector<std::unique_ptr<OGRPolygon>> pieces,
                                                       const std::string& label) {
  const std::size_t n = pieces.size();
  std::vector<OGREnvelope> env(n);
  for (std::size_t i = 0; i < n; ++i) pieces[i]->getEnvelope(&env[i]);
  std::vector<std::size_t> order(n), up(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = up[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return env[a].MinX < env[b].MinX || (env[a].MinX == env[b].MinX && a < b);
  });
  // GEOS copies both geometries on every plain Intersects call: a continent tested against the
  // hundreds of islands in its envelope is prepared once instead.
  std::vector<PreparedPtr> prepared(n);
  auto meet = [&](std::size_t a, std::size_t b) {
    if (pieces[a]->getExteriorRing()->getNumPoints() < pieces[b]->getExteriorRing()->getNumPoints()) std::swap(a, b);
    if (!prepared[a]) prepared[a].reset(OGRCreatePreparedGeometry(OGRGeometry::ToHandle(pieces[a].get())));
    return OGRPreparedGeometryIntersects(prepared[a].get(), OGRGeometry::ToHandle(pieces[b].get())) != 0;
  };
  std::vector<std::size_t> active;
  for (std::size_t k : order) {
    std::erase_if(active, [&](std::size_t a) { return env[a].MaxX < env[k].MinX; });
    for (std::size_t a : active)
      if (env[a].MaxY >= env[k].MinY && env[a].MinY <= env[k].MaxY && find_root(up, a) != find_root(up, k) && meet(a, k))
        up[find_root(up, a)] = find_root(up, k);
    active.push_back(k);
  }
  prepared.clear();
  std::vector<std::vector<std::size_t>> groups(n);
  for (std::size_t i = 0; i < n; ++i) groups[find_root(up, i)].push_back(i);
  std::vector<std::unique_ptr<OGRPolygon>> out;
  for (auto& g : groups) {
    if (g.size() == 1) out.push_back(std::move(pieces[g[0]]));
    if (g.size() < 2) continue;
    OGRMultiPolygon mp;
    for (std::size_t i : g) mp.addGeometry(pieces[i].get());
    std::unique_ptr<OGRGeometry> u(mp.UnionCascaded());
    if (!u) throw Error(ExitCode::kInvalidGeometry, label + ": union of the land polygons failed: " + CPLGetLastErrorMsg());
    std::vector<const OGRPolygon*> ps;
    collect_polygons(u.get(), ps);
    for (const OGRPolygon* p : ps) out.emplace_back(p->clone());
  }
  return out;
}

bool winds_round_pole(const std::vector<LonLat>& ring) {
  double turn = 0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    double d = ring[(i + 1) % n].lon_deg - ring[i].lon_deg;
    if (d > 180) d -= 360;
    if (d < -180) d += 360;
    turn += d;
  }
  return std::fabs(turn) > 180;
}

}  // namespace fdr::gis
