// The water of a global run: land polygons joined across the antimeridian and subtracted from the
// coast of the land mass holding the pole, in the stereographic plane (global_domain.hpp).
#include "gis/global_domain.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <type_traits>

#include <cpl_error.h>
#include <ogr_api.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>

#include "base/error.hpp"
#include "base/step_laps.hpp"
#include "gis/gdal_util.hpp"
#include "gis/vector_layers.hpp"

namespace fdr::gis {

namespace {

bool same(LonLat a, LonLat b) { return a.lon_deg == b.lon_deg && a.lat_deg == b.lat_deg; }

LonLat sphere_point(LonLat p) {
  if (p.lat_deg <= -90.0) return {0.0, -90.0};
  if (p.lat_deg >= 90.0) return {0.0, 90.0};
  if (p.lon_deg == -180.0) p.lon_deg = 180.0;
  return p;
}

std::string at(LonLat p) { return "(" + num(p.lon_deg) + ", " + num(p.lat_deg) + ")"; }

// A ring in the plane as a GEOS-ready polygon.
OGRPolygon plane_polygon(const std::vector<Point2>& ring) {
  OGRLinearRing r;
  for (const Point2& p : ring) r.addPoint(p.x, p.y);
  r.addPoint(ring[0].x, ring[0].y);
  OGRPolygon poly;
  poly.addRing(&r);
  return poly;
}

// g's polygons, made valid first when GEOS finds g invalid (a projected ring touching itself).
std::unique_ptr<OGRGeometry> valid_copy(const OGRGeometry& g, const std::string& what) {
  if (g.IsValid()) return std::unique_ptr<OGRGeometry>(g.clone());
  std::unique_ptr<OGRGeometry> v(g.MakeValid());
  if (!v) throw Error(ExitCode::kInvalidGeometry, what + ": cannot make it valid: " + CPLGetLastErrorMsg());
  return v;
}

// Signed area on the sphere of a ring of the plane (counter-clockwise positive): the sum of the
// spherical triangles (projection centre, a, b), none of which comes near the centre's antipode.
double sphere_ring_area(const std::vector<Point2>& ring, const SphereStereo& proj) {
  const Point3 c = unit_vector(proj.centre());
  double a = 0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i)
    a += spherical_triangle_area(c, unit_vector(proj.inverse(ring[i])), unit_vector(proj.inverse(ring[(i + 1) % n])),
                                 proj.radius());
  return a;
}

double plane_ring_area(const std::vector<Point2>& r) {
  double a = 0;
  for (std::size_t i = 0, n = r.size(); i < n; ++i) {
    const Point2 p = r[i] - r[0], q = r[(i + 1) % n] - r[0];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

struct LandRing {
  std::int64_t fid;
  std::vector<LonLat> ll;  // as read
  bool holds_pole = false;
};

// Every land polygon's exterior ring in lon/lat (WGS 84, traditional order); holes counted.
std::vector<LandRing> land_rings(LayerData& L, LonLat pole, GlobalWater& out) {
  OGRSpatialReference ll;
  ll.importFromEPSG(4326);
  ll.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::vector<LandRing> rings;
  for (auto& f : L.features) {
    if (!L.srs.IsSame(&ll)) {
      f.geom->assignSpatialReference(&L.srs);
      if (f.geom->transformTo(&ll) != OGRERR_NONE)
        throw Error(ExitCode::kCrsError, L.label() + ", feature FID " + std::to_string(f.fid) +
                                             ": cannot transform to WGS 84 lon/lat");
    }
    std::vector<const OGRPolygon*> ps;
    if (const OGRGeometry* bad = collect_polygons(f.geom.get(), ps))
      throw Error(ExitCode::kInvalidGeometry, L.label() + ", feature FID " + std::to_string(f.fid) + " " +
                                                  where_str(bad) + ": geometry is " + bad->getGeometryName() +
                                                  ", expected Polygon or MultiPolygon");
    for (const OGRPolygon* p : ps) {
      if (p->IsEmpty()) continue;
      ++out.land_polygons;
      out.land_holes_filled += static_cast<std::size_t>(p->getNumInteriorRings());
      LandRing r{f.fid, {}, false};
      for (const Point2& q : curve_points(p->getExteriorRing())) r.ll.push_back({q.x, q.y});
      if (r.ll.size() >= 2 && same(r.ll.front(), r.ll.back())) r.ll.pop_back();
      r.holds_pole = ring_holds_pole(r.ll, pole);
      rings.push_back(std::move(r));
    }
  }
  return rings;
}

// The ring in the plane (sphere_ring, densified, projected); empty when degenerate.
std::vector<Point2> plane_ring(const LandRing& r, const SphereStereo& proj, double step, GlobalWater& out,
                               const std::string& label) {
  std::vector<LonLat> s = sphere_ring(r.ll);
  if (s.size() < 3) return {};
  out.densify_points += densify_lonlat(s, step);
  std::vector<Point2> pts;
  pts.reserve(s.size());
  for (const LonLat& p : s) {
    const Point2 q = proj.forward(p);
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || std::max(std::fabs(q.x), std::fabs(q.y)) > 1e3 * proj.radius())
      throw Error(ExitCode::kInvalidGeometry,
                  label + ", feature FID " + std::to_string(r.fid) + ": vertex " + at(p) + " lies at the pole " +
                      at(proj.pole()) + " of the projection" +
                      (r.holds_pole ? ": the coast of the land holding the pole reaches it; give --pole inside that land"
                                    : ": only the land holding the pole may contain it"));
    pts.push_back(q);
  }
  return pts;
}

struct PreparedDeleter {
  void operator()(OGRPreparedGeometryH h) const { OGRDestroyPreparedGeometry(h); }
};
using PreparedPtr = std::unique_ptr<std::remove_pointer_t<OGRPreparedGeometryH>, PreparedDeleter>;

// Union-find over land pieces.
std::size_t find_root(std::vector<std::size_t>& up, std::size_t i) {
  while (up[i] != i) i = up[i] = up[up[i]];
  return i;
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

// water minus the disjoint land: land inside it becomes holes directly, land crossing its
// boundary is subtracted with GEOS, land outside it (inside the pole's land mass) is dropped.
std::unique_ptr<OGRGeometry> subtract_land(std::unique_ptr<OGRGeometry> water,
                                           std::vector<std::unique_ptr<OGRPolygon>> land, const std::string& what) {
  std::vector<std::unique_ptr<OGRPolygon>> inside;
  OGRMultiPolygon crossing;
  {
    const PreparedPtr pw(OGRCreatePreparedGeometry(OGRGeometry::ToHandle(water.get())));
    for (auto& q : land) {
      OGRGeometryH h = OGRGeometry::ToHandle(q.get());
      if (OGRPreparedGeometryContains(pw.get(), h)) inside.push_back(std::move(q));
      else if (OGRPreparedGeometryIntersects(pw.get(), h)) crossing.addGeometry(q.get());
    }
  }
  if (!crossing.IsEmpty()) {
    water.reset(water->Difference(&crossing));
    if (!water) throw Error(ExitCode::kInvalidGeometry, what + " failed: " + CPLGetLastErrorMsg());
  }
  std::vector<const OGRPolygon*> ps;
  collect_polygons(water.get(), ps);
  std::vector<std::unique_ptr<OGRPolygon>> parts;
  std::vector<PreparedPtr> prepared;
  std::vector<OGREnvelope> envs(ps.size());
  for (std::size_t k = 0; k < ps.size(); ++k) {
    parts.emplace_back(ps[k]->clone());
    parts[k]->getEnvelope(&envs[k]);
    prepared.emplace_back(OGRCreatePreparedGeometry(OGRGeometry::ToHandle(parts[k].get())));
  }
  for (auto& q : inside) {
    OGREnvelope e;
    q->getEnvelope(&e);
    for (std::size_t k = 0; k < parts.size(); ++k)
      if (envs[k].Contains(e) && OGRPreparedGeometryContains(prepared[k].get(), OGRGeometry::ToHandle(q.get()))) {
        parts[k]->addRing(q->getExteriorRing());
        break;
      }
  }
  auto result = std::make_unique<OGRMultiPolygon>();
  for (auto& p : parts) result->addGeometryDirectly(p.release());
  return result;
}

}  // namespace

std::vector<LonLat> sphere_ring(std::vector<LonLat> ring) {
  std::vector<LonLat> out;
  out.reserve(ring.size());
  for (LonLat p : ring) {
    p = sphere_point(p);
    if (!out.empty() && same(out.back(), p)) continue;
    if (out.size() >= 2 && same(out[out.size() - 2], p)) {  // a -> b -> a: b is a spike's tip
      out.pop_back();
      continue;
    }
    out.push_back(p);
  }
  // The same across the ring's start.
  for (bool changed = true; changed && out.size() >= 2;) {
    changed = false;
    const std::size_t n = out.size();
    if (same(out.front(), out.back())) {
      out.pop_back();
      changed = true;
    } else if (n >= 3 && same(out[n - 1], out[1])) {
      out.erase(out.begin(), out.begin() + 2);
      changed = true;
    } else if (n >= 3 && same(out[n - 2], out[0])) {
      out.resize(n - 2);
      changed = true;
    }
  }
  if (out.size() < 3) out.clear();
  return out;
}

bool ring_holds_pole(const std::vector<LonLat>& ring, LonLat pole) {
  if (std::fabs(pole.lat_deg) >= 90.0)
    return std::any_of(ring.begin(), ring.end(), [&](LonLat p) {
      return pole.lat_deg < 0 ? p.lat_deg <= -90.0 : p.lat_deg >= 90.0;
    });
  bool in = false;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const LonLat a = ring[i], b = ring[(i + 1) % n];
    if ((a.lat_deg > pole.lat_deg) == (b.lat_deg > pole.lat_deg)) continue;
    const double x = a.lon_deg + (pole.lat_deg - a.lat_deg) / (b.lat_deg - a.lat_deg) * (b.lon_deg - a.lon_deg);
    if (pole.lon_deg < x) in = !in;
  }
  return in;
}

std::size_t densify_lonlat(std::vector<LonLat>& ring, double step) {
  if (!(step > 0) || ring.size() < 2) return 0;
  std::vector<LonLat> out;
  out.reserve(ring.size());
  std::size_t added = 0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const LonLat a = ring[i];
    LonLat b = ring[(i + 1) % n];
    out.push_back(a);
    // An edge across the antimeridian (179.9 -> -179.9) is the short way round, not 359.8 degrees.
    if (b.lon_deg - a.lon_deg > 180.0) b.lon_deg -= 360.0;
    if (a.lon_deg - b.lon_deg > 180.0) b.lon_deg += 360.0;
    const double span = std::max(std::fabs(b.lon_deg - a.lon_deg), std::fabs(b.lat_deg - a.lat_deg));
    if (!(span > step)) continue;
    const int k = static_cast<int>(std::min(std::ceil(span / step), 1e5));
    for (int j = 1; j < k; ++j) {
      const double t = static_cast<double>(j) / k;
      double lon = a.lon_deg + (b.lon_deg - a.lon_deg) * t;
      if (lon > 180.0) lon -= 360.0;
      if (lon < -180.0) lon += 360.0;
      out.push_back({lon, a.lat_deg + (b.lat_deg - a.lat_deg) * t});
    }
    added += static_cast<std::size_t>(k - 1);
  }
  ring = std::move(out);
  return added;
}

GlobalWater global_water(const LayerRef& land, const std::string& s_srs, const SphereStereo& proj, double step) {
  StepLaps lap(debug::Aid::kFilter, "global water");
  LayerData L = read_layer(land, s_srs, "--land");
  lap("read");
  GlobalWater out;
  out.file = L.file;
  out.layer = L.layer;
  std::vector<LandRing> rings = land_rings(L, proj.pole(), out);
  // The land holding the pole: the largest (most vertices) of the rings that hold it.
  std::size_t pole = rings.size();
  for (std::size_t i = 0; i < rings.size(); ++i)
    if (rings[i].holds_pole && (pole == rings.size() || rings[i].ll.size() > rings[pole].ll.size())) pole = i;
  if (pole == rings.size())
    throw Error(ExitCode::kInvalidGeometry, L.label() + ": no land polygon holds the pole " + at(proj.pole()) +
                                                " of the projection; give --pole LON,LAT inside the land that bounds "
                                                "the ocean (Antarctica)");
  out.pole_fid = rings[pole].fid;
  GdalQuiet quiet;
  std::vector<std::unique_ptr<OGRPolygon>> others;
  std::vector<Point2> coast;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    if (std::any_of(rings[i].ll.begin(), rings[i].ll.end(), [](LonLat p) { return std::fabs(p.lon_deg) == 180.0; }))
      ++out.antimeridian_rings;
    std::vector<Point2> pr = plane_ring(rings[i], proj, step, out, L.label());
    if (pr.empty()) continue;
    if (i == pole) {
      coast = std::move(pr);
      continue;
    }
    const OGRPolygon poly = plane_polygon(pr);
    std::unique_ptr<OGRGeometry> v = valid_copy(poly, L.label() + ", feature FID " + std::to_string(rings[i].fid));
    std::vector<const OGRPolygon*> ps;
    collect_polygons(v.get(), ps);
    for (const OGRPolygon* p : ps) others.emplace_back(p->clone());
  }
  lap("rings");
  if (coast.size() < 3)
    throw Error(ExitCode::kInvalidGeometry, L.label() + ", feature FID " + std::to_string(out.pole_fid) +
                                                ": the land holding the pole has no coast left on the sphere");
  const std::string what = L.label() + ": the sphere minus land";
  std::unique_ptr<OGRGeometry> water = valid_copy(plane_polygon(coast), what + " (outer coast, FID " +
                                                                            std::to_string(out.pole_fid) + ")");
  std::vector<std::unique_ptr<OGRPolygon>> pieces = disjoint_land(std::move(others), L.label());
  lap("union");
  water = subtract_land(std::move(water), std::move(pieces), what);
  lap("difference");
  std::vector<const OGRPolygon*> ps;
  collect_polygons(water.get(), ps);
  if (ps.empty()) throw Error(ExitCode::kInvalidGeometry, L.label() + ": the land covers the whole sphere");
  for (const OGRPolygon* p : ps) {
    out.polygons.emplace_back();
    for (const OGRLinearRing* r : *p) {
      std::vector<Point2> pts = curve_points(r);
      if (pts.size() >= 2 && pts.front() == pts.back()) pts.pop_back();
      if (pts.size() < 3) continue;
      const bool hole = !out.polygons.back().empty();
      const double a = std::fabs(sphere_ring_area(pts, proj));
      out.water_area_m2 += hole ? -a : a;
      if ((plane_ring_area(pts) > 0) == hole) std::reverse(pts.begin(), pts.end());  // outer CCW, holes CW
      out.polygons.back().push_back(std::move(pts));
    }
    if (out.polygons.back().empty()) out.polygons.pop_back();
  }
  lap("rings out");
  return out;
}

}  // namespace fdr::gis
